// feint/io/csv.hpp - a streaming RFC 4180 reader for plain and gzip-compressed CSV.
//
// Records are read one at a time from a large buffer; field views stay valid until the next call
// to next(). Quoted fields, doubled quotes, embedded line breaks, LF or CRLF line ends and a UTF-8
// BOM are handled. Gzip input is recognised by its magic bytes (not its name), so `-` (stdin) and
// renamed files work too.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace feint::io {

struct CsvOptions {
  /// Field separator; 0 = detect from the header line (the most frequent of `,` `;` TAB outside
  /// quotes; `,` when none occurs).
  char delimiter = 0;
  /// Every record must have as many fields as the header (a short or long row is invalid data).
  bool require_header_width = true;
  /// Number of leading rows (after the header) to skip, e.g. Qualtrics' two extra header rows.
  /// Skipped rows still count for line numbers.
  std::size_t skip_rows = 0;
  /// The file has no header row (a MATLAB `writematrix`/`csvwrite` export): the first row is data.
  /// Columns are then named by `column_names` (in order; a file with more columns names the rest
  /// by position) or, without names, by their 1-based position: `1`, `2`, ...
  bool no_header = false;
  std::vector<std::string> column_names;
};

class CsvReader {
 public:
  /// Opens `path` (`-` = standard input) and reads the header. Throws IoError when the file cannot
  /// be opened or read, InvalidData when it has no header or is malformed.
  explicit CsvReader(std::string path, CsvOptions options = {});
  ~CsvReader();
  CsvReader(const CsvReader&) = delete;
  CsvReader& operator=(const CsvReader&) = delete;
  CsvReader(CsvReader&&) noexcept;
  CsvReader& operator=(CsvReader&&) noexcept;

  /// Column names as written in the header (BOM removed, not trimmed or lower-cased); with
  /// no_header, the given names or `1`, `2`, ...
  const std::vector<std::string>& header() const noexcept;
  /// Index of a column (after trimming): the column spelled exactly `name` if there is one, else
  /// the one column equal to it ignoring case; -1 when absent. Two or more columns that equal it
  /// only ignoring case (`Pad` and `PAD` for `pad`) are ambiguous: InvalidData naming the file and
  /// both columns, followed by `hint` (e.g. "name one exactly with --map pad=COLUMN").
  int column(std::string_view name, std::string_view hint = {}) const;

  /// Reads the next non-empty record; false at end of input. Throws InvalidData on an unterminated
  /// quote, text after a closing quote, a stray quote, or (by default) a wrong field count.
  bool next();
  /// Fields of the current record; views into the reader's buffer, valid until next(). With
  /// no_header, before the first next() they are the first row (which next() then hands out).
  const std::vector<std::string_view>& fields() const noexcept;
  std::string_view field(std::size_t i) const noexcept;

  /// 1-based physical line on which the current record starts (the header is line 1).
  std::uint64_t line() const noexcept;
  /// Number of data records returned so far.
  std::uint64_t records() const noexcept;
  /// Bytes of (possibly compressed) input consumed so far, for progress reports.
  std::uint64_t bytes_consumed() const noexcept;
  const std::string& path() const noexcept;
  char delimiter() const noexcept;
  bool compressed() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Splits one line of text into CSV fields (for command-line values such as `--compare A,B`).
std::vector<std::string> split_csv_line(std::string_view line, char delimiter = ',');

/// Quotes a field for CSV output when it contains the delimiter, a quote or a line break.
std::string csv_escape(std::string_view field, char delimiter = ',');

}  // namespace feint::io

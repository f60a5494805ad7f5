// feint/io/scores.hpp - per-participant scores tables, the input of `feint table`/`feint describe`.
//
// formats.md: the tables accept any CSV with `participant`, `iteration`, optional `condition`, and
// numeric metric columns (the output of `feint score`, or metrics computed elsewhere). One value per
// participant, condition and iteration: a second row with the same key is an error naming both
// lines. Bad input stops the load with `file:line: column 'x': value ... (P01/adaptive/3)`
// (InvalidData, exit 65).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace feint::io {

struct ScoresOptions {
  /// Metric columns to load (must exist, must be numeric). Empty cells are missing values (kept as
  /// nullopt, excluded from that metric's tests and counted in the report's note); text, `nan`,
  /// `inf` are invalid.
  std::vector<std::string> metrics = {"error", "confusion"};
  std::string participant_column = "participant";
  std::string iteration_column = "iteration";
  std::string condition_column = "condition";  ///< optional: absent = one condition ("")
  /// Field separator (0 = detected from the header, as io::CsvReader) and decimal mark of the
  /// metric values ('.', or ',' for a European export; 0 = '.' in a `,`-delimited file, else the
  /// first value holding a `,` or `.` decides).
  char delimiter = 0;
  char decimal = 0;
  /// The study's conditions (settings, --compare): with two or more, a table without the
  /// condition column is invalid instead of pooled into one condition.
  std::vector<std::string> expected_conditions;
};

/// One row of a scores table: a participant's values in one condition and iteration.
struct ScoreRecord {
  std::string participant;
  std::string condition;  ///< "" when the file has no condition column
  long long iteration = 0;
  std::vector<std::optional<double>> values;  ///< one per ScoresTable::metrics; nullopt = missing
  std::uint64_t line = 0;                     ///< physical line in the file
};

struct ScoresTable {
  std::string path;
  std::vector<std::string> metrics;  ///< as requested (ScoresOptions::metrics)
  bool has_condition = false;
  std::vector<ScoreRecord> records;  ///< file order

  /// Conditions in order of first appearance ({""} without a condition column).
  std::vector<std::string> conditions() const;
  /// Distinct iterations, ascending.
  std::vector<long long> iterations() const;
  /// Index of a metric in `metrics`; -1 when absent.
  int metric_index(const std::string& name) const noexcept;
};

/// Loads a scores CSV (gzip, `-`, delimiters as io::CsvReader). Throws IoError when unreadable and
/// InvalidData for: a missing required or metric column, an empty participant, a condition empty
/// on some rows only (a condition column empty on every row means no conditions), an
/// iteration that is not a whole number in [0, 1e9], a non-numeric metric value, a duplicate
/// (participant, condition, iteration), or no data rows at all.
ScoresTable load_scores(const std::string& path, const ScoresOptions& options = {});

/// What the scores' sidecar (written by `feint score` beside its output) says about how the
/// numbers were made. Every field is empty when unknown.
struct ScoresProvenance {
  std::string sidecar_path;            ///< the file read, "" when none was found
  std::string confusion_normalisation; ///< e.g. "speed (confusion in fraction of ...)"
  std::vector<std::pair<std::string, std::string>> settings;  ///< every key/value found
  /// Non-empty when a sidecar was found but ignored because it does not describe this table (its
  /// recorded size/CRC-32, `output_check`, differ from the file's: another run's sidecar, or a
  /// table edited since); says which sidecar and why.
  std::string ignored;
};

/// Looks for the sidecar of `scores_path` and reads it; an absent or unreadable sidecar gives an
/// empty provenance (never an error: tables of metrics computed elsewhere have none), and so does
/// a sidecar whose `output_check` (size and CRC-32 of the table `feint score` wrote) does not match
/// the file (then `ignored` says so).
ScoresProvenance read_scores_provenance(const std::string& scores_path);

/// One numeric column of any CSV, optionally split by a grouping column (`feint describe`).
struct NumericColumn {
  std::string path;
  std::string column;                ///< as written in the file's header
  std::string by;                    ///< grouping column as in the header, "" for none
  std::vector<std::string> groups;   ///< group names in order of first appearance ({""} if no by)
  std::vector<std::vector<double>> values;  ///< per group, file order
  /// The same values as written (trimmed): statistics read from the decimal text exactly are
  /// accurate beyond what a double-rounded value allows (NIST StRD NumAcc4).
  std::vector<std::vector<std::string>> texts;
  std::vector<std::size_t> missing;  ///< empty cells per group (excluded)
};

/// Reads `column` (and `by`, if non-empty). InvalidData for a missing column, a non-numeric value,
/// or no data rows; empty cells are missing values, counted.
NumericColumn load_numeric_column(const std::string& path, const std::string& column,
                                  const std::string& by = "");

}  // namespace feint::io

// tests/stats/golden_csv.hpp - a tiny reader for the golden CSV files of tests/golden/stats/.
//
// The stats tests link only feint_stats, so they cannot use feint::io. Golden files are written by
// the R scripts beside them: a header line, comma-separated fields, no quotes, "NA" for missing.
#pragma once

#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace feint::test {

/// Splits one line on commas (no quoting).
inline std::vector<std::string> split_commas(const std::string& line, char sep = ',') {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, sep)) out.push_back(field);
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

/// One row: field by column name.
class GoldenRow {
 public:
  GoldenRow(const std::map<std::string, std::size_t>* index, std::vector<std::string> fields,
            std::size_t line)
      : index_(index), fields_(std::move(fields)), line_(line) {}

  const std::string& str(const std::string& column) const {
    auto it = index_->find(column);
    if (it == index_->end()) throw std::runtime_error("golden CSV: no column " + column);
    if (it->second >= fields_.size())
      throw std::runtime_error("golden CSV line " + std::to_string(line_) + ": short row");
    return fields_[it->second];
  }
  /// The number, or nullopt for "NA" / "" / "NaN".
  std::optional<double> num(const std::string& column) const {
    const std::string& s = str(column);
    if (s.empty() || s == "NA" || s == "NaN") return std::nullopt;
    if (s == "Inf") return HUGE_VAL;
    if (s == "-Inf") return -HUGE_VAL;
    return std::strtod(s.c_str(), nullptr);
  }
  double number(const std::string& column) const {
    auto v = num(column);
    if (!v) throw std::runtime_error("golden CSV line " + std::to_string(line_) + ": " + column + " is NA");
    return *v;
  }
  /// Numbers separated by `sep` within one field (e.g. a sample "1.5;2;3").
  std::vector<double> numbers(const std::string& column, char sep = ';') const {
    std::vector<double> out;
    for (const auto& f : split_commas(str(column), sep))
      if (!f.empty()) out.push_back(f == "NA" ? std::nan("") : std::strtod(f.c_str(), nullptr));
    return out;
  }
  std::size_t line() const { return line_; }

 private:
  const std::map<std::string, std::size_t>* index_;
  std::vector<std::string> fields_;
  std::size_t line_;
};

/// A whole golden file in memory.
class GoldenCsv {
 public:
  explicit GoldenCsv(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open golden file " + path);
    std::string line;
    std::getline(in, line);
    const auto header = split_commas(line);
    for (std::size_t i = 0; i < header.size(); ++i) index_[header[i]] = i;
    std::size_t no = 1;
    while (std::getline(in, line)) {
      ++no;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.empty()) continue;
      rows_.emplace_back(&index_, split_commas(line), no);
    }
  }
  GoldenCsv(const GoldenCsv&) = delete;  // rows point at index_
  GoldenCsv& operator=(const GoldenCsv&) = delete;

  const std::vector<GoldenRow>& rows() const { return rows_; }

 private:
  std::map<std::string, std::size_t> index_;
  std::vector<GoldenRow> rows_;
};

/// Path of a golden file in tests/golden/stats/.
inline std::string golden_path(const std::string& name) {
  return std::string(FEINT_SOURCE_DIR) + "/tests/golden/stats/" + name;
}

}  // namespace feint::test

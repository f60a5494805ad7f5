#include "feint/io/scores.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include <fmt/format.h>
#include <zlib.h>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

namespace feint::io {

namespace {

std::string header_list(const CsvReader& reader) {
  std::string out;
  for (const auto& h : reader.header()) {
    if (!out.empty()) out += ", ";
    out += h;
  }
  return out;
}

int require_column(const CsvReader& reader, const std::string& name, std::string_view role) {
  const int i = reader.column(name, fmt::format("name one exactly with {}", role));
  if (i < 0) {
    throw InvalidData(fmt::format("{}:1: column '{}' ({}) is missing; the header has: {}",
                                  reader.path(), name, role, header_list(reader)));
  }
  return i;
}

std::string trial_key(const ScoreRecord& r, bool has_condition) {
  return has_condition ? fmt::format("{}/{}/{}", r.participant, r.condition, r.iteration)
                       : fmt::format("{}/{}", r.participant, r.iteration);
}

// Where a scores table's columns are (indices into its header; condition -1 when absent).
struct ScoreColumns {
  int participant = -1;
  int iteration = -1;
  int condition = -1;
  std::vector<int> metrics;
};

// The columns the options name, each missing one named in a single message (not one per run), and
// the condition column required when the study has two or more conditions.
ScoreColumns find_score_columns(const CsvReader& reader, const std::string& path,
                                const ScoresOptions& options) {
  ScoreColumns cols;
  std::vector<std::string> missing;
  auto find = [&](const std::string& name, std::string_view role, std::string_view option) {
    const int i = reader.column(name, fmt::format("name one exactly with {}", option));
    if (i < 0) missing.push_back(fmt::format("'{}' ({})", name, role));
    return i;
  };
  cols.participant = find(options.participant_column, "participant", "--participant-column");
  cols.iteration = find(options.iteration_column, "iteration", "--iteration-column");
  cols.condition = reader.column(options.condition_column,
                                 "name one exactly with --condition-column");
  for (const auto& m : options.metrics) cols.metrics.push_back(find(m, "metric", "--metric"));
  if (missing.size() == 1) {
    const bool metric = missing[0].ends_with("(metric)");
    const std::string name = missing[0].substr(0, missing[0].rfind(" ("));
    throw InvalidData(metric ? fmt::format("{}:1: metric column {} is missing; the header has: {}",
                                           path, name, header_list(reader))
                             : fmt::format("{}:1: column {} is missing; the header has: {}", path,
                                           missing[0], header_list(reader)));
  }
  if (!missing.empty()) {
    throw InvalidData(fmt::format("{}:1: columns {} are missing; the header has: {}", path,
                                  fmt::join(missing, ", "), header_list(reader)));
  }
  if (cols.condition < 0 && options.expected_conditions.size() >= 2) {
    throw InvalidData(fmt::format(
        "{}:1: no condition column '{}', but the study has {} conditions ({}): name it with "
        "--condition-column COLUMN (the header has: {}); the conditions would otherwise be pooled",
        path, options.condition_column, options.expected_conditions.size(),
        fmt::join(options.expected_conditions, ", "), header_list(reader)));
  }
  return cols;
}

// Metric values in the table's decimal mark (ScoresOptions::decimal): the given one, '.' in a
// ','-delimited file, else the first value holding a '.' or ',' decides.
class MetricNumbers {
 public:
  MetricNumbers(const ScoresOptions& options, const CsvReader& reader)
      : mark_(options.decimal != 0 ? options.decimal : reader.delimiter() == ',' ? '.' : 0) {}

  std::optional<double> operator()(std::string_view text) {
    if (mark_ == 0) {
      if (text.find('.') != std::string_view::npos) mark_ = '.';
      else if (text.find(',') != std::string_view::npos) mark_ = ',';
    }
    if (mark_ != ',') return parse_double(text);
    if (text.find('.') != std::string_view::npos) return std::nullopt;
    comma_scratch_.assign(text);
    std::replace(comma_scratch_.begin(), comma_scratch_.end(), ',', '.');
    return parse_double(comma_scratch_);
  }
  char mark() const noexcept { return mark_; }

 private:
  char mark_;
  std::string comma_scratch_;  // reused for every value: no allocation per row
};

// A condition column that is empty on EVERY row means no conditions (`feint score` writes one for
// logs without a condition column); empty on some rows only is an error, reported once the whole
// file has been seen. This remembers the first row of each kind.
struct ConditionPresence {
  std::uint64_t first_empty = 0;
  std::uint64_t first_given = 0;
  std::string first_empty_participant;

  void note(const ScoreRecord& rec) {
    if (rec.condition.empty()) {
      if (first_empty == 0) {
        first_empty = rec.line;
        first_empty_participant = rec.participant;
      }
    } else if (first_given == 0) {
      first_given = rec.line;
    }
  }
};

// The row's iteration: a whole number from 0 to 1e9.
long long read_iteration(const CsvReader& reader, int column, const ScoreRecord& rec,
                         bool has_condition, const std::string& path) {
  const std::string_view it_text = reader.field(static_cast<std::size_t>(column));
  auto iteration = parse_integer(it_text);
  if (iteration && (*iteration < 0 || *iteration > 1000000000)) iteration.reset();
  if (!iteration) {
    throw InvalidData(fmt::format(
        "{}:{}: column '{}': '{}' is not an iteration number (participant {}{}; expected a "
        "whole number from 0 to 1e9)",
        path, rec.line, reader.header()[static_cast<std::size_t>(column)], it_text, rec.participant,
        has_condition ? "/" + rec.condition : std::string()));
  }
  return *iteration;
}

// The row's metric values into rec.values, an empty cell as missing.
void read_metric_values(const CsvReader& reader, const std::vector<int>& columns,
                        MetricNumbers& number, bool has_condition, const std::string& path,
                        ScoreRecord& rec) {
  for (std::size_t m = 0; m < columns.size(); ++m) {
    const std::string_view text = reader.field(static_cast<std::size_t>(columns[m]));
    if (trim(text).empty()) {
      rec.values.emplace_back();  // missing: excluded from this metric's tests, and counted
      continue;
    }
    const auto v = number(text);
    if (!v) {
      const char mark = number.mark();
      throw InvalidData(fmt::format("{}:{}: column '{}': '{}' is not a number ({}; expected a "
                                    "finite number with a decimal {}, or an empty cell{})",
                                    path, rec.line,
                                    reader.header()[static_cast<std::size_t>(columns[m])], text,
                                    trial_key(rec, has_condition),
                                    mark == ',' ? "comma" : "point",
                                    mark != ',' && text.find(',') != std::string_view::npos
                                        ? "; a decimal comma? give --delimiter ';' --decimal ,"
                                        : mark == ',' ? "; give --decimal . if the point is the decimal mark" : ""));
    }
    rec.values.push_back(*v);
  }
}

// After the last row: a condition column empty on some rows only is an error; empty on all of them,
// it means one condition for everybody.
void settle_conditions(const ConditionPresence& conditions, const CsvReader& reader,
                       int condition_column, const std::string& path, ScoresTable& table) {
  if (table.has_condition && conditions.first_empty != 0) {
    if (conditions.first_given != 0) {
      throw InvalidData(fmt::format("{}:{}: column '{}': empty condition (participant {}; line {} "
                                    "has one: every row needs its condition, or none does)",
                                    path, conditions.first_empty,
                                    reader.header()[static_cast<std::size_t>(condition_column)],
                                    conditions.first_empty_participant, conditions.first_given));
    }
    table.has_condition = false;  // an empty column: one condition for everybody
  }
}

}  // namespace

std::vector<std::string> ScoresTable::conditions() const {
  std::vector<std::string> out;
  std::set<std::string> seen;
  for (const auto& r : records) {
    if (seen.insert(r.condition).second) out.push_back(r.condition);
  }
  if (out.empty()) out.emplace_back();
  return out;
}

std::vector<long long> ScoresTable::iterations() const {
  std::set<long long> s;
  for (const auto& r : records) s.insert(r.iteration);
  return {s.begin(), s.end()};
}

int ScoresTable::metric_index(const std::string& name) const noexcept {
  const std::string lower = to_lower(name);
  for (std::size_t i = 0; i < metrics.size(); ++i) {
    if (to_lower(metrics[i]) == lower) return static_cast<int>(i);
  }
  return -1;
}

ScoresTable load_scores(const std::string& path, const ScoresOptions& options) {
  if (options.decimal != 0 && options.decimal != '.' && options.decimal != ',') {
    throw UsageError(fmt::format("--decimal '{}': expected . or ,", options.decimal));
  }
  CsvOptions copt;
  copt.delimiter = options.delimiter;
  CsvReader reader(path, copt);
  ScoresTable table;
  table.path = path;
  table.metrics = options.metrics;
  const ScoreColumns cols = find_score_columns(reader, path, options);
  table.has_condition = cols.condition >= 0;
  MetricNumbers number(options, reader);

  // (participant, condition, iteration) -> line, to name both places of a duplicate.
  std::map<std::tuple<std::string, std::string, long long>, std::uint64_t> seen;
  ConditionPresence conditions;
  while (reader.next()) {
    ScoreRecord rec;
    rec.line = reader.line();
    rec.participant = std::string(trim(reader.field(static_cast<std::size_t>(cols.participant))));
    if (table.has_condition) {
      rec.condition = std::string(trim(reader.field(static_cast<std::size_t>(cols.condition))));
    }
    if (rec.participant.empty()) {
      throw InvalidData(fmt::format("{}:{}: column '{}': empty participant (expected an id)", path,
                                    rec.line,
                                    reader.header()[static_cast<std::size_t>(cols.participant)]));
    }
    if (table.has_condition) conditions.note(rec);
    rec.iteration = read_iteration(reader, cols.iteration, rec, table.has_condition, path);
    read_metric_values(reader, cols.metrics, number, table.has_condition, path, rec);
    const auto [pos, inserted] =
        seen.emplace(std::make_tuple(rec.participant, rec.condition, rec.iteration), rec.line);
    if (!inserted) {
      throw InvalidData(fmt::format(
          "{}:{}: duplicate participant/{}iteration {}: already on line {} (one value per "
          "participant and iteration is expected)",
          path, rec.line, table.has_condition ? "condition/" : "",
          trial_key(rec, table.has_condition), pos->second));
    }
    table.records.push_back(std::move(rec));
  }
  if (table.records.empty()) {
    throw InvalidData(fmt::format("{}: no data rows (expected one row per participant and "
                                  "iteration after the header)",
                                  path));
  }
  settle_conditions(conditions, reader, cols.condition, path, table);
  return table;
}

// ---------------------------------------------------------------------------------------------
// Sidecar

namespace {

std::string read_small_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return {};
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Minimal reader of a flat JSON object {"key": value, ...} or nested objects: collects every
// "key": scalar pair (strings unescaped for \" and \\ only; numbers/booleans as written), with
// nested keys joined by '.'.
void collect_json(std::string_view s, std::size_t& i, const std::string& prefix,
                  std::vector<std::pair<std::string, std::string>>& out, int depth);

void skip_ws(std::string_view s, std::size_t& i) {
  while (i < s.size() && (s[i] == ' ' || s[i] == '\n' || s[i] == '\r' || s[i] == '\t')) ++i;
}

std::string read_json_string(std::string_view s, std::size_t& i) {
  std::string out;
  ++i;  // opening quote
  while (i < s.size() && s[i] != '"') {
    if (s[i] == '\\' && i + 1 < s.size()) {
      ++i;
      switch (s[i]) {
        case 'n': out += '\n'; break;
        case 't': out += '\t'; break;
        default: out += s[i];
      }
    } else {
      out += s[i];
    }
    ++i;
  }
  if (i < s.size()) ++i;  // closing quote
  return out;
}

void skip_json_value(std::string_view s, std::size_t& i) {
  int level = 0;
  while (i < s.size()) {
    const char c = s[i];
    if (c == '"') {
      read_json_string(s, i);
      if (level == 0) return;
      continue;
    }
    if (c == '{' || c == '[') ++level;
    if (c == '}' || c == ']') {
      if (level == 0) return;
      --level;
      ++i;
      if (level == 0) return;
      continue;
    }
    if (level == 0 && c == ',') return;
    ++i;
  }
}

void collect_json(std::string_view s, std::size_t& i, const std::string& prefix,
                  std::vector<std::pair<std::string, std::string>>& out, int depth) {
  skip_ws(s, i);
  if (i >= s.size() || s[i] != '{' || depth > 8) {
    skip_json_value(s, i);
    return;
  }
  ++i;
  while (i < s.size()) {
    skip_ws(s, i);
    if (i < s.size() && s[i] == '}') {
      ++i;
      return;
    }
    if (i >= s.size() || s[i] != '"') return;  // malformed: stop quietly
    const std::string key = prefix + read_json_string(s, i);
    skip_ws(s, i);
    if (i >= s.size() || s[i] != ':') return;
    ++i;
    skip_ws(s, i);
    if (i < s.size() && s[i] == '{') {
      collect_json(s, i, key + ".", out, depth + 1);
    } else if (i < s.size() && s[i] == '"') {
      out.emplace_back(key, read_json_string(s, i));
    } else if (i < s.size() && s[i] == '[') {
      const std::size_t start = i;
      skip_json_value(s, i);
      out.emplace_back(key, std::string(s.substr(start, i - start)));
    } else {
      const std::size_t start = i;
      while (i < s.size() && s[i] != ',' && s[i] != '}') ++i;
      std::string v(s.substr(start, i - start));
      while (!v.empty() && (v.back() == ' ' || v.back() == '\n' || v.back() == '\r')) v.pop_back();
      out.emplace_back(key, v);
    }
    skip_ws(s, i);
    if (i < s.size() && s[i] == ',') ++i;
  }
}

// key=value or key: value lines (# comments).
void collect_lines(std::string_view s, std::vector<std::pair<std::string, std::string>>& out) {
  std::size_t i = 0;
  while (i < s.size()) {
    auto j = s.find('\n', i);
    if (j == std::string_view::npos) j = s.size();
    std::string_view line = trim(s.substr(i, j - i));
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    i = j + 1;
    if (line.empty() || line.front() == '#') continue;
    const auto k = line.find_first_of("=:");
    if (k == std::string_view::npos) continue;
    out.emplace_back(std::string(trim(line.substr(0, k))), std::string(trim(line.substr(k + 1))));
  }
}

}  // namespace

ScoresProvenance read_scores_provenance(const std::string& scores_path) {
  ScoresProvenance prov;
  if (scores_path.empty() || scores_path == "-") return prov;
  namespace fs = std::filesystem;
  const fs::path p(scores_path);
  fs::path stem = p;
  if (stem.extension() == ".gz") stem.replace_extension();
  stem.replace_extension();  // scores.csv -> scores
  const std::vector<fs::path> candidates = {
      fs::path(scores_path + ".json"),     fs::path(scores_path + ".meta.json"),
      fs::path(stem.string() + ".json"),  fs::path(stem.string() + ".meta.json"),
      fs::path(stem.string() + ".sidecar.json"), fs::path(scores_path + ".settings"),
  };
  for (const auto& c : candidates) {
    std::error_code ec;
    if (!fs::is_regular_file(c, ec)) continue;
    const std::string text = read_small_file(c);
    if (text.empty()) continue;
    std::size_t i = 0;
    skip_ws(text, i);
    if (i < text.size() && text[i] == '{') {
      collect_json(text, i, "", prov.settings, 0);
    } else {
      collect_lines(text, prov.settings);
    }
    prov.sidecar_path = c.string();
    break;
  }
  // A sidecar that records the table it belongs to must match this file byte for byte.
  std::string want_bytes, want_crc;
  for (const auto& [k, v] : prov.settings) {
    if (k == "output_check.bytes") want_bytes = v;
    if (k == "output_check.crc32") want_crc = to_lower(v);
  }
  if (!want_bytes.empty() || !want_crc.empty()) {
    const std::string table = read_small_file(p);
    const uLong crc = ::crc32_z(::crc32(0L, Z_NULL, 0),
                                reinterpret_cast<const Bytef*>(table.data()), table.size());
    const std::string got_crc = fmt::format("{:08x}", static_cast<unsigned long>(crc));
    if (want_bytes != std::to_string(table.size()) || want_crc != got_crc) {
      ScoresProvenance none;
      none.ignored = fmt::format(
          "{} ignored: it describes a table of {} bytes (CRC-32 {}), but {} has {} bytes (CRC-32 "
          "{}); it belongs to another run or the table was changed since",
          prov.sidecar_path, want_bytes, want_crc, scores_path, table.size(), got_crc);
      return none;
    }
  }
  // The confusion normalisation: `feint score` writes settings.confusion_norm ("speed"/"raw") and
  // describes the unit in units.confusion; other tools may write any key naming a normalisation.
  std::string norm, unit;
  for (const auto& [k, v] : prov.settings) {
    const std::string key = to_lower(k);
    if (norm.empty() && (key.find("confusion_norm") != std::string::npos ||
                         key.find("normali") != std::string::npos)) {
      norm = v;
    }
    if (unit.empty() && key == "units.confusion") unit = v;
  }
  if (!norm.empty()) {
    prov.confusion_normalisation = unit.empty() ? norm : norm + " (confusion in " + unit + ")";
  }
  return prov;
}

// ---------------------------------------------------------------------------------------------
// One numeric column

NumericColumn load_numeric_column(const std::string& path, const std::string& column,
                                  const std::string& by) {
  CsvReader reader(path);
  NumericColumn out;
  out.path = path;
  out.column = column;
  out.by = by;
  const int iv = require_column(reader, column, "--column");
  const int ib = by.empty() ? -1 : require_column(reader, by, "--by");
  out.column = std::string(trim(reader.header()[static_cast<std::size_t>(iv)]));  // as in the file
  if (ib >= 0) out.by = std::string(trim(reader.header()[static_cast<std::size_t>(ib)]));
  std::map<std::string, std::size_t> index;
  while (reader.next()) {
    std::string group;
    if (ib >= 0) group = std::string(trim(reader.field(static_cast<std::size_t>(ib))));
    auto [it, inserted] = index.emplace(group, out.groups.size());
    if (inserted) {
      out.groups.push_back(group);
      out.values.emplace_back();
      out.texts.emplace_back();
      out.missing.push_back(0);
    }
    const std::size_t g = it->second;
    const std::string_view text = reader.field(static_cast<std::size_t>(iv));
    if (trim(text).empty()) {
      ++out.missing[g];
      continue;
    }
    const auto v = parse_double(text);
    if (!v) {
      throw InvalidData(fmt::format(
          "{}:{}: column '{}': '{}' is not a number ({}expected a finite number with a decimal "
          "point, or an empty cell)",
          path, reader.line(), reader.header()[static_cast<std::size_t>(iv)], text,
          ib >= 0 ? fmt::format("{} {}; ", reader.header()[static_cast<std::size_t>(ib)], group)
                  : std::string()));
    }
    out.values[g].push_back(*v);
    out.texts[g].emplace_back(trim(text));
  }
  if (out.groups.empty()) {
    throw InvalidData(fmt::format("{}: no data rows (expected at least one row after the header)",
                                  path));
  }
  return out;
}

}  // namespace feint::io

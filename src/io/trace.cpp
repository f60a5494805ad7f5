#include "feint/io/trace.hpp"

#include <glob.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <regex>
#include <set>
#include <string_view>
#include <unordered_map>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

namespace feint::io {

namespace fs = std::filesystem;

std::string Trial::label() const {
  return condition.empty() ? fmt::format("{}/{}", participant, iteration)
                           : fmt::format("{}/{}/{}", participant, condition, iteration);
}

namespace {

enum Field : int {
  kParticipant,
  kCondition,
  kIteration,
  kStrategy,
  kVariant,
  kTarget,
  kT,
  kPad,
  kPadSpeed,
  kRobotX,  // optional per-sample robot position (m), read only together
  kRobotY,
  kFieldCount
};

const std::array<const char*, kFieldCount> kFieldNames = {
    "participant", "condition", "iteration", "strategy", "variant", "target", "t", "pad",
    "pad_speed", "robot_x", "robot_y"};

constexpr std::array<bool, kFieldCount> kRequired = {true, false, true, false, false, true,
                                                     true, true,  false, false, false};

constexpr long long kMaxIteration = 1000000000;  // as io::load_scores

std::string display_name(const std::string& path) { return path == "-" ? "<stdin>" : path; }

// Where a trial's rows begin, for "appeared before" messages.
struct Location {
  std::uint32_t file = 0;
  std::uint64_t line = 0;
};

// Columns of the current file: index per field (-1 = absent) and the header's spelling.
struct Columns {
  std::array<int, kFieldCount> index{};
  std::array<std::string, kFieldCount> name{};
  std::size_t width = 0;
};

// One trial being assembled from its rows.
struct Builder {
  Trial trial;
  std::string participant, condition, iteration;  // key as written (trimmed)
  std::string iteration_key;  // the iteration's value (`01` -> `1`), or its text when not a number
  std::string target_text, strategy_text, variant_text, pad_speed_text;
  std::uint32_t file = 0;
  std::uint64_t last_line = 0;
  std::string error;  // lenient mode: the first problem (full message); empty = valid
  std::uint64_t error_line = 0;
  std::uint32_t error_file = 0;
  std::uint64_t padding = 0;       // all-NaN t/pad rows seen since the last valid sample
  std::uint64_t padding_line = 0;  // the first of them

  std::string label() const {
    return condition.empty() ? fmt::format("{}/{}", participant, iteration)
                             : fmt::format("{}/{}/{}", participant, condition, iteration);
  }
};

// Plain decimals (the bulk of a log) take the exact fast path; the rest parse_double.
[[gnu::always_inline]] inline std::optional<double> parse_number(std::string_view s) noexcept {
  return detail::parse_decimal_fast(s);
}

// Trims blanks only when there are any (the common case has none).
[[gnu::always_inline]] inline std::string_view trim_fast(std::string_view v) noexcept {
  if (!v.empty() && (v.front() == ' ' || v.front() == '\t' || v.back() == ' ' || v.back() == '\t')) {
    return trim(v);
  }
  return v;
}

// A t or pad cell that holds no value: how MATLAB (NaN), R (NA) and pandas (empty) pad
// fixed-length arrays.
bool is_missing(std::string_view v) noexcept {
  if (v.empty()) return true;
  if (v.size() > 3) return false;
  const std::string l = to_lower(v);
  return l == "nan" || l == "na";
}

// The columns a file lacks, gathered so that one message names them all.
struct MissingColumns {
  std::vector<std::string> columns;  // as the message names them
  std::vector<std::string> maps;     // the --map that would name each
  bool id = false;                   // the participant's column is among them
  bool samples = false;              // t or pad is among them
};

bool has_data_extension(const fs::path& p) {
  std::string name = to_lower(p.filename().string());
  if (name.size() > 3 && name.ends_with(".gz")) name.resize(name.size() - 3);
  return name.ends_with(".csv") || name.ends_with(".tsv") || name.ends_with(".txt");
}

}  // namespace

namespace detail {
bool looks_like_condition(std::string_view header_cell) {
  const std::string k = to_lower(trim(header_cell));
  return k.starts_with("cond") || k == "group" || k == "arm" || k == "treatment" || k == "between";
}
}  // namespace detail

using detail::looks_like_condition;

const std::vector<std::string>& trace_field_names() {
  static const std::vector<std::string> names(kFieldNames.begin(), kFieldNames.end());
  return names;
}

std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  auto add = [&](const std::string& path) {
    if (path == "-") {
      if (seen.insert("-").second) out.push_back(path);
      return;
    }
    std::error_code ec;
    const auto canon = fs::weakly_canonical(path, ec);
    if (seen.insert(ec ? path : canon.string()).second) out.push_back(path);
  };
  for (const auto& input : inputs) {
    if (input == "-") {
      add(input);
      continue;
    }
    std::error_code ec;
    const auto status = fs::status(input, ec);
    if (fs::is_directory(status)) {
      // A study folder (its feint.toml beside a logs/ folder, as feint collect and feint simulate
      // study write it) means its logs: the questionnaires next to them are not logs.
      const fs::path logs = fs::path(input) / "logs";
      const std::string dir = fs::is_regular_file(fs::path(input) / "feint.toml", ec) && fs::is_directory(logs, ec)
                                  ? logs.string()
                                  : input;
      std::vector<std::string> found;
      for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
           it.increment(ec)) {
        if (it->is_regular_file() && has_data_extension(it->path())) {
          found.push_back(it->path().string());
        }
      }
      if (ec) throw IoError(fmt::format("cannot read directory '{}': {}", dir, ec.message()));
      if (found.empty()) {
        throw IoError(fmt::format("directory '{}' holds no data files (*.csv, *.tsv, *.txt, "
                                  "optionally .gz)", dir));
      }
      std::sort(found.begin(), found.end());
      for (const auto& f : found) add(f);
    } else if (fs::exists(status)) {
      add(input);
    } else if (input.find_first_of("*?[") != std::string::npos) {
      glob_t g{};
      const int rc = ::glob(input.c_str(), 0, nullptr, &g);
      std::vector<std::string> found;
      if (rc == 0) {
        for (std::size_t i = 0; i < g.gl_pathc; ++i) found.emplace_back(g.gl_pathv[i]);
      }
      ::globfree(&g);
      if (found.empty()) throw IoError(fmt::format("no file matches '{}'", input));
      std::sort(found.begin(), found.end());
      for (const auto& f : found) {
        if (fs::is_directory(f)) {
          for (const auto& sub : expand_inputs({f})) add(sub);
        } else {
          add(f);
        }
      }
    } else {
      throw IoError(fmt::format("cannot open '{}': No such file or directory", input));
    }
  }
  if (out.empty()) throw UsageError("no input files given");
  return out;
}

struct TraceReader::Impl {
  std::vector<std::string> files;
  std::vector<std::string> names;  // display names
  TraceOptions options;
  std::size_t next_file = 0;
  std::uint32_t file_index = 0;  // index of the open file
  std::unique_ptr<CsvReader> reader;
  Columns cols;
  const std::vector<std::string_view>* row = nullptr;  // fields of the reader's current record

  Builder cur;
  bool have_cur = false;
  std::unordered_map<std::string, Location> seen;  // streaming: where each trial began
  std::string key_scratch;

  // unsorted mode
  bool buffered = false;
  std::vector<Builder> groups;
  std::unordered_map<std::string, std::size_t> group_index;
  std::size_t next_group = 0;

  std::uint64_t rows_read = 0;
  std::uint64_t rows_ok = 0;
  std::uint64_t rows_bad = 0;
  std::uint64_t trials_bad = 0;
  std::uint64_t bytes_done = 0;

  // Per file: the decimal mark ('.', ',', 0 = not known yet), the id from the path, the JSON
  // samples column.
  char mark = '.';
  std::string comma_scratch;
  std::string file_participant;
  int samples_index = -1;
  std::vector<double> json_t, json_pad;
  std::string unit_name = "seconds";
  // What diagnostics() reports.
  std::uint64_t rows_padding = 0, trials_padded = 0;
  std::size_t comma_files = 0;
  Diagnostic first_comma;
  long long min_iteration = std::numeric_limits<long long>::max(), max_iteration = -1;
  std::string min_iteration_at;  // file:line of the smallest iteration

  bool strict() const { return !options.on_reject; }

  [[noreturn]] void throw_at(std::uint32_t file, std::uint64_t line, const std::string& what,
                             const std::string& label) const {
    throw InvalidData(fmt::format("{}:{}: {} (trial {})", names[file], line, what, label));
  }

  // A problem with the trial `b` at `line` of the current file.
  void invalid(Builder& b, std::uint64_t line, const std::string& what) {
    if (strict()) throw_at(file_index, line, what, b.label());
    if (b.error.empty()) {
      b.error = fmt::format("{}:{}: {} (trial {})", names[file_index], line, what, b.label());
      b.error_line = line;
      b.error_file = file_index;
    }
  }

  // Opens the next input file and reads its header: false when there is none left.
  bool open_next_file() {
    if (reader) {
      bytes_done += reader->bytes_consumed();
      reader.reset();
    }
    if (next_file >= files.size()) return false;
    file_index = static_cast<std::uint32_t>(next_file++);
    CsvOptions copt;
    copt.delimiter = options.delimiter;
    copt.require_header_width = false;  // a short/long row is a problem of its trial
    copt.no_header = options.no_header;
    copt.column_names = options.column_names;
    reader = std::make_unique<CsvReader>(files[file_index], copt);
    row = &reader->fields();
    const std::string& name = names[file_index];
    if (options.no_header) reject_header_as_data(name);
    mark = options.decimal != 0 ? options.decimal : reader->delimiter() == ',' ? '.' : 0;
    if (!options.participant_from_path.empty()) file_participant = participant_from(files[file_index]);
    find_columns(name);
    check_condition_column(name);
    if (cols.index[kPadSpeed] < 0 && !options.pad_speed && options.require_pad_speed) {
      throw UsageError(fmt::format(
          "{}: no 'pad_speed' column, but the 'speed' confusion normalisation needs the pad "
          "speed: give --pad-speed V (pad units per second), name the column with --map "
          "pad_speed=COLUMN, or use --confusion-norm raw",
          name));
    }
    check_robot_columns(name);
    return true;
  }

  // --no-header: a header read as data would fail later on its iteration; say what happened
  // instead. (Before the first next(), fields() holds the first row, which next() hands out again.)
  void reject_header_as_data(const std::string& name) const {
    for (const auto f : reader->fields()) {
      const std::string cell = to_lower(trim(f));
      if (std::find(kFieldNames.begin(), kFieldNames.end(), cell) != kFieldNames.end()) {
        throw InvalidData(fmt::format("{}:{}: --no-header, but the first row holds the column "
                                      "name '{}': the file has a header; drop --no-header "
                                      "(and --columns) and name its columns with --map",
                                      name, reader->line(), trim(f)));
      }
    }
  }

  // cols (and samples_index) for the open file; every missing column in one message.
  void find_columns(const std::string& name) {
    const bool json = !options.samples_column.empty();
    cols = {};
    cols.width = reader->header().size();
    MissingColumns missing;
    for (int f = 0; f < kFieldCount; ++f) find_column(static_cast<Field>(f), json, missing);
    if (json) {
      samples_index = reader->column(options.samples_column,
                                     "name one exactly with --samples-column (the exact-case match is taken)");
      if (samples_index < 0) {
        missing.columns.push_back(
            fmt::format("'{}' (given by --samples-column)", options.samples_column));
      }
    }
    if (!missing.columns.empty()) throw_missing_columns(missing, json, name);
  }

  // The column of field f (by its name or its --map), noted in `missing` when a required or
  // mapped one is absent.
  void find_column(Field f, bool json, MissingColumns& missing) {
    const auto mapped = options.column_map.find(kFieldNames[f]);
    const bool is_mapped = mapped != options.column_map.end();
    const std::string want = is_mapped ? mapped->second : kFieldNames[f];
    cols.name[f] = want;
    // Replaced by an option: the column is not read.
    if ((f == kPadSpeed && options.pad_speed) ||
        (f == kParticipant && !options.participant_from_path.empty()) ||
        (json && (f == kT || f == kPad))) {
      cols.index[f] = -1;
      return;
    }
    const int idx = reader->column(
        want, fmt::format("name one exactly with --map {}=COLUMN (the exact-case match is taken)",
                          kFieldNames[f]));
    cols.index[f] = idx;
    if (idx >= 0) {
      cols.name[f] = reader->header()[static_cast<std::size_t>(idx)];
      return;
    }
    if (is_mapped) {
      missing.columns.push_back(
          fmt::format("'{}' (given by --map {}={})", want, kFieldNames[f], want));
    } else if (kRequired[f]) {
      missing.columns.push_back(fmt::format("'{}' (required)", want));
    } else {
      return;
    }
    missing.maps.push_back(fmt::format("--map {}=COLUMN", kFieldNames[f]));
    missing.id = missing.id || f == kParticipant;
    missing.samples = missing.samples || f == kT || f == kPad;
  }

  // The message for missing columns, with the options that would fix it.
  [[noreturn]] void throw_missing_columns(const MissingColumns& missing, bool json,
                                          const std::string& name) const {
    const auto& header = reader->header();
    std::string fixes = missing.maps.empty()
                            ? std::string("give --samples-column the JSON column's name")
                            : fmt::format("name the study's column{} with {}",
                                          missing.maps.size() > 1 ? "s" : "",
                                          fmt::join(missing.maps, " "));
    if (missing.id) {
      fixes += "; ids only in the file or folder name: --participant-from-path filename (or "
               "dirname, or a regular expression whose first group is the id)";
    }
    if (missing.samples && !json) {
      fixes += "; samples stored as a JSON array in one cell (jsPsych): --samples-column COLUMN";
    }
    bool numeric = !options.no_header;
    for (const auto& h : header) numeric = numeric && parse_double(h).has_value();
    if (numeric) {
      fixes = fmt::format("the first row holds only numbers, so the file has no header: name its "
                          "{} columns by position with --no-header --columns "
                          "participant,iteration,target,t,pad (one name per column, in order) or "
                          "--no-header --map t=3 (columns are numbered from 1); ",
                          header.size()) + fixes;
    }
    throw InvalidData(fmt::format("{}:1: no column {} (the header has: {}); {}", name,
                                  fmt::join(missing.columns, ", no column "),
                                  fmt::join(header, ", "), fixes));
  }

  // Without a condition column, trials are pooled into one condition: wrong when the study has
  // several, or when another column looks like the condition (unless --single-condition).
  void check_condition_column(const std::string& name) const {
    if (cols.index[kCondition] >= 0 || options.single_condition) return;
    const auto& header = reader->header();
    if (options.expected_conditions.size() >= 2) {
      throw InvalidData(fmt::format(
          "{}:1: no condition column '{}', but the study has {} conditions ({}): name the "
          "column with --map condition=COLUMN (the header has: {}); trials would otherwise be "
          "pooled into one condition", name, cols.name[kCondition],
          options.expected_conditions.size(), fmt::join(options.expected_conditions, ", "),
          fmt::join(header, ", ")));
    }
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (looks_like_condition(header[i])) {
        throw InvalidData(fmt::format(
            "{}:1: column '{}' (column {}) looks like the condition, but the condition is read "
            "from a column named '{}': name it with --map condition={}, or give "
            "--single-condition to pool every trial into one condition",
            name, header[i], i + 1, cols.name[kCondition], trim(header[i])));
      }
    }
  }

  // The robot's position is read only when asked for and per sample (a JSON cell holds a whole
  // trial), and needs both of its columns.
  void check_robot_columns(const std::string& name) {
    const bool json = !options.samples_column.empty();
    if (!options.read_robot_path || json) {
      cols.index[kRobotX] = cols.index[kRobotY] = -1;
    } else if ((cols.index[kRobotX] >= 0) != (cols.index[kRobotY] >= 0)) {
      const Field has = cols.index[kRobotX] >= 0 ? kRobotX : kRobotY;
      const Field lacks = has == kRobotX ? kRobotY : kRobotX;
      throw InvalidData(fmt::format("{}:1: column '{}' without '{}' (the robot's position needs "
                                    "both; name it with --map {}=COLUMN)", name, cols.name[has],
                                    cols.name[lacks], kFieldNames[lacks]));
    }
  }

  // TraceOptions::participant_from_path applied to one file.
  std::string participant_from(const std::string& path) const {
    const std::string& rule = options.participant_from_path;
    if (path == "-") {
      throw UsageError("--participant-from-path cannot name the participant of standard input "
                       "(give the files by name)");
    }
    const fs::path p(path);
    std::string id;
    if (rule == "filename") {
      id = p.filename().string();
      const auto dot = id.find('.');
      if (dot != std::string::npos && dot > 0) id.resize(dot);
    } else if (rule == "dirname") {
      id = p.parent_path().filename().string();
    } else {
      std::smatch m;
      if (!std::regex_search(path, m, path_regex) || m.size() < 2 || m[1].length() == 0) {
        throw InvalidData(fmt::format(
            "{}: --participant-from-path '{}' does not match this path (its first group "
            "must capture the id, e.g. 'sub-([0-9]+)')", display_name(path), rule));
      }
      id = m[1].str();
    }
    if (id.empty()) {
      throw InvalidData(fmt::format("{}: --participant-from-path {} gives an empty id",
                                    display_name(path), rule));
    }
    return id;
  }
  std::regex path_regex;

  // A number in the file's decimal mark. The common case ('.') is the fast path.
  [[gnu::always_inline]] std::optional<double> num(std::string_view s) {
    if (mark == '.') return parse_number(s);
    return num_other(s);
  }
  // A cell holding a JSON array or object (a whole trace in one cell) is no number, and its commas
  // say nothing about the decimal mark.
  static bool is_list(std::string_view s) {
    const auto first = s.find_first_not_of(" \t");
    return first != std::string_view::npos && (s[first] == '[' || s[first] == '{');
  }
  std::optional<double> num_other(std::string_view s) {
    if (is_list(s)) return std::nullopt;
    if (mark == 0) {  // not known yet: the first value with a mark decides
      const bool comma = s.find(',') != std::string_view::npos;
      if (s.find('.') != std::string_view::npos) {
        mark = '.';
      } else if (comma) {
        mark = ',';
        if (comma_files++ == 0) {
          first_comma = {"decimal-comma", names[file_index], reader->line(), "",
                         fmt::format("{}:{}: numbers read with a decimal comma ('{}'; the file is "
                                     "'{}'-delimited)", names[file_index], reader->line(), s,
                                     reader->delimiter() == '\t' ? "tab" : std::string(1, reader->delimiter()))};
        }
      }
      if (mark != ',') return parse_number(s);
    }
    if (s.find('.') != std::string_view::npos) return std::nullopt;
    comma_scratch.assign(s);
    std::replace(comma_scratch.begin(), comma_scratch.end(), ',', '.');
    return parse_number(comma_scratch);  // the same exact fast path as a decimal point
  }
  // Why a number cell was not read, when the decimal mark may be the reason.
  std::string mark_hint(std::string_view s) const {
    if (is_list(s)) {
      // jsPsych writes one row per trial, its trace as JSON arrays in cells: not a decimal mark.
      return "; the cell holds a list (a JSON array, as jsPsych writes a whole trace in one row): "
             "feint reads one row per pad sample, or a trial's whole trace from one JSON cell: "
             "put the arrays in one column as {\"t\":[...],\"pad\":[...]} and give "
             "--samples-column COLUMN (docs/formats.md, \"Files from other labs\"), or write one "
             "row per sample";
    }
    if (mark == ',' && s.find('.') != std::string_view::npos) {
      return options.decimal == ','
                 ? "; --decimal , is given, so a '.' is not allowed"
                 : "; this file's numbers use a decimal comma (detected), so a '.' is not allowed: "
                   "give --decimal . if the point is the decimal mark";
    }
    if (s.find(',') != std::string_view::npos) {
      return "; a decimal comma? give --delimiter ';' --decimal ,";
    }
    return {};
  }
  // A cell as a message shows it: a long one (a whole trace in one cell) cut to its first 40
  // characters, so that the message stays readable.
  static std::string shown_cell(std::string_view s) {
    return s.size() <= 60 ? std::string(s) : std::string(s.substr(0, 40)) + "\u2026";
  }

  [[gnu::always_inline]] std::string_view get(Field f) const {
    const int i = cols.index[f];
    if (i < 0) return f == kParticipant ? std::string_view(file_participant) : std::string_view{};
    const auto idx = static_cast<std::size_t>(i);
    return idx < row->size() ? trim_fast((*row)[idx]) : std::string_view{};
  }

  // Starts a trial with the key of the current row.
  void start(Builder& b, std::string_view p, std::string_view c, std::string_view it) {
    reset_trial(b, p, c, it);
    const std::uint64_t line = reader->line();
    if (reader->fields().size() != cols.width) return;  // reported by add_row
    if (p.empty()) invalid(b, line, fmt::format("column '{}': empty (every row needs a participant)",
                                                cols.name[kParticipant]));
    if (cols.index[kCondition] >= 0 && c.empty()) {
      invalid(b, line, fmt::format("column '{}': empty (expected the condition's name)",
                                   cols.name[kCondition]));
    }
    read_iteration(b, line, it);
    read_target(b, line);
    read_pad_speed(b, line);
  }

  // b for a new trial: its key and trial-level text from the current row, no samples, no error
  // (b's buffers are reused, not reallocated).
  void reset_trial(Builder& b, std::string_view p, std::string_view c, std::string_view it) {
    b.participant.assign(p);
    b.condition.assign(c);
    b.iteration.assign(it);
    b.iteration_key.assign(iteration_key(it));
    b.file = file_index;
    b.error.clear();
    b.error_line = 0;
    b.last_line = 0;
    b.padding = 0;
    b.padding_line = 0;
    Trial& t = b.trial;
    t.padding_rows = 0;
    t.times.clear();
    t.pads.clear();
    t.robot_x.clear();
    t.robot_y.clear();
    t.rows = 0;
    t.line = reader->line();
    t.file = names[file_index];
    t.participant = b.participant;
    t.condition = b.condition;
    t.iteration = 0;
    t.strategy.assign(get(kStrategy));
    t.variant.assign(get(kVariant));
    b.strategy_text = t.strategy;
    b.variant_text = t.variant;
    b.target_text.assign(get(kTarget));
    b.pad_speed_text.assign(get(kPadSpeed));
    t.target = 0;
    t.pad_speed = options.pad_speed;
  }

  // The trial's iteration (counted from 1 in Trial), and the range seen for diagnostics().
  void read_iteration(Builder& b, std::uint64_t line, std::string_view it) {
    if (const auto i = parse_integer(it);
        i && *i >= 0 && *i <= kMaxIteration - (options.iteration_base == 0 ? 1 : 0)) {
      b.trial.iteration = options.iteration_base == 0 ? *i + 1 : *i;
      if (*i < min_iteration) {
        min_iteration = *i;
        min_iteration_at = fmt::format("{}:{}", names[file_index], line);
      }
      max_iteration = std::max(max_iteration, *i);
      if (*i == 0 && options.iteration_base == 1) {
        invalid(b, line, fmt::format("column '{}': iteration 0 with --iteration-base 1 (give "
                                     "--iteration-base 0 if the iterations are numbered from 0)",
                                     cols.name[kIteration]));
      }
    } else if (i) {
      // The scores tables take iterations 0..1e9 (io/scores.hpp): what score accepts, table reads.
      invalid(b, line, fmt::format("column '{}': {} is outside 0 to 1e9 (expected an iteration "
                                   "number)", cols.name[kIteration], it));
    } else {
      invalid(b, line, it.empty() ? fmt::format("column '{}': empty (expected a whole number)",
                                                cols.name[kIteration])
                                  : fmt::format("column '{}': '{}' is not a whole number",
                                                cols.name[kIteration], it));
    }
  }

  // The trial's target: left (0), right (1) or a pad coordinate in [0, 1].
  void read_target(Builder& b, std::uint64_t line) {
    Trial& t = b.trial;
    const std::string tl = to_lower(b.target_text);
    if (tl == "left") {
      t.target = 0;
    } else if (tl == "right") {
      t.target = 1;
    } else if (const auto v = num(tl)) {
      if (*v < 0 || *v > 1) {
        invalid(b, line, fmt::format("column '{}': {} is outside [0, 1] (expected left, right, or "
                                     "a pad coordinate in [0, 1])", cols.name[kTarget], b.target_text));
      }
      t.target = *v;
    } else {
      invalid(b, line,
              b.target_text.empty()
                  ? fmt::format("column '{}': empty (expected left, right, or a number in [0, 1])",
                                cols.name[kTarget])
                  : fmt::format("column '{}': '{}' is not left, right, or a number in [0, 1]",
                                cols.name[kTarget], b.target_text));
    }
  }

  // The trial's pad speed from its column, unless --pad-speed gives it.
  void read_pad_speed(Builder& b, std::uint64_t line) {
    if (options.pad_speed || cols.index[kPadSpeed] < 0) return;
    if (b.pad_speed_text.empty()) {
      if (options.require_pad_speed) {
        invalid(b, line, fmt::format("column '{}': empty (the 'speed' confusion normalisation "
                                     "needs the pad speed in pad units per second; or give "
                                     "--pad-speed V)", cols.name[kPadSpeed]));
      }
    } else if (const auto v = num(b.pad_speed_text); v && *v > 0) {
      b.trial.pad_speed = *v;
    } else {
      invalid(b, line, fmt::format("column '{}': '{}' is not a number > 0 (pad units per second)",
                                   cols.name[kPadSpeed], b.pad_speed_text));
    }
  }

  // Trial-level text that must not change within a trial; numbers compare by value.
  void check_constant(Builder& b, Field f, std::string_view now, const std::string& first,
                      bool numeric) {
    if (now == first) return;
    if (numeric) {
      const auto a = num(now), c = num(first);
      if (a && c && *a == *c) return;
      if (f == kTarget) {
        const std::string nl = to_lower(now), fl = to_lower(first);
        if (nl == fl) return;
      }
    }
    invalid(b, reader->line(),
            fmt::format("column '{}': '{}' differs from '{}' on the trial's first row (line {}) "
                        "(trial-level fields must be constant within a trial)",
                        cols.name[f], now, first, b.trial.line));
  }

  void add_row(Builder& b) {
    const std::uint64_t line = reader->line();
    ++b.trial.rows;
    if (!b.error.empty()) return;  // lenient: already rejected; just count its rows
    if (reader->fields().size() != cols.width) {
      invalid(b, line, fmt::format("{} fields where the header has {}", reader->fields().size(),
                                   cols.width));
      return;
    }
    Trial& t = b.trial;
    if (!t.times.empty()) {
      check_constant(b, kTarget, get(kTarget), b.target_text, true);
      check_constant(b, kStrategy, get(kStrategy), b.strategy_text, false);
      check_constant(b, kVariant, get(kVariant), b.variant_text, false);
      if (!options.pad_speed && cols.index[kPadSpeed] >= 0) {
        check_constant(b, kPadSpeed, get(kPadSpeed), b.pad_speed_text, true);
      }
    }
    if (samples_index >= 0) {
      add_json_samples(b, line);
      return;
    }
    const std::string_view ts = get(kT);
    const std::string_view ps = get(kPad);
    const auto tv = num(ts);
    if (!tv && is_missing(ts) && is_missing(ps)) {
      // Padding of a fixed-length array: dropped if nothing but padding follows in this trial.
      if (b.padding++ == 0) b.padding_line = line;
      return;
    }
    if (!tv) {
      invalid(b, line, ts.empty() ? fmt::format("column '{}': empty (expected a time in {})",
                                                cols.name[kT], unit_name)
                                  : fmt::format("column '{}': '{}' is not a number (expected a "
                                                "time in {}{}){}", cols.name[kT], shown_cell(ts), unit_name,
                                                mark == ',' ? ", decimal comma" : ", decimal point",
                                                mark_hint(ts)));
      return;
    }
    const auto pv = num(ps);
    if (!pv) {
      invalid(b, line, ps.empty() ? fmt::format("column '{}': empty (expected a pad position in "
                                                "[0, 1])", cols.name[kPad])
                                  : fmt::format("column '{}': '{}' is not a number (expected a pad "
                                                "position in [0, 1]){}", cols.name[kPad], shown_cell(ps),
                                                mark_hint(ps)));
      return;
    }
    add_sample(b, line, ts, *tv, ps, *pv);
  }

  void add_sample(Builder& b, std::uint64_t line, std::string_view ts, double tv,
                  std::string_view ps, double pv) {
    Trial& t = b.trial;
    if (b.padding > 0) {
      invalid(b, b.padding_line,
              fmt::format("columns '{}' and '{}': no value, but a sample follows at line {} (only "
                          "trailing rows without t and pad, the padding of fixed-length arrays, "
                          "are dropped; a gap inside a trial is invalid)",
                          cols.name[kT], cols.name[kPad], line));
      return;
    }
    if (pv < 0 || pv > 1) {
      invalid(b, line, fmt::format("column '{}': {} is outside [0, 1]", cols.name[kPad], ps));
      return;
    }
    const double seconds = options.time_divisor == 1 ? tv : tv / options.time_divisor;
    if (!t.times.empty() && !(seconds > t.times.back())) {
      invalid(b, line, fmt::format("column '{}': {} is not after the previous sample's {} (line "
                                   "{}; times must strictly increase)", cols.name[kT], ts,
                                   format_double(t.times.back() * options.time_divisor),
                                   b.last_line));
      return;
    }
    if (cols.index[kRobotX] >= 0 && !read_robot(b, line)) return;
    t.times.push_back(seconds);
    t.pads.push_back(pv);
    b.last_line = line;
  }

  // TraceOptions::samples_column: the row's cell holds the trial's samples as JSON.
  void add_json_samples(Builder& b, std::uint64_t line) {
    const auto idx = static_cast<std::size_t>(samples_index);
    const std::string_view cell = idx < row->size() ? trim_fast((*row)[idx]) : std::string_view{};
    const std::string& tk = cols.name[kT];
    const std::string& pk = cols.name[kPad];
    std::string error;
    if (!detail::parse_json_samples(cell, tk, pk, json_t, json_pad, error)) {
      invalid(b, line, fmt::format("column '{}': {}", reader->header()[idx], error));
      return;
    }
    for (std::size_t k = 0; k < json_t.size() && b.error.empty(); ++k) {
      const double tv = json_t[k], pv = json_pad[k];
      if (std::isnan(tv) && std::isnan(pv)) {
        if (b.padding++ == 0) b.padding_line = line;
        continue;
      }
      const std::string ts = format_double(tv), ps = format_double(pv);
      if (std::isnan(tv) || std::isnan(pv)) {
        invalid(b, line, fmt::format("column '{}': sample {}: \"{}\" is null", reader->header()[idx],
                                     k + 1, std::isnan(tv) ? tk : pk));
        return;
      }
      add_sample(b, line, ts, tv, ps, pv);
    }
  }

  // The robot's position on this row (both columns present): finite numbers in metres.
  bool read_robot(Builder& b, std::uint64_t line) {
    for (const Field f : {kRobotX, kRobotY}) {
      const std::string_view s = get(f);
      const auto v = num(s);  // the file's decimal mark
      if (!v) {
        invalid(b, line, s.empty() ? fmt::format("column '{}': empty (expected the robot's "
                                                 "position in metres on every row)", cols.name[f])
                                   : fmt::format("column '{}': '{}' is not a number (expected the "
                                                 "robot's position in metres)", cols.name[f], s));
        return false;
      }
      (f == kRobotX ? b.trial.robot_x : b.trial.robot_y).push_back(*v);
    }
    return true;
  }

  // Ends a trial: true when it is valid (then it is in b.trial), false when rejected.
  bool finish(Builder& b) {
    if (b.error.empty() && b.trial.times.size() < 2) {
      const std::string what = fmt::format(
          "{} valid sample(s); a trial needs at least 2 (metrics.md)", b.trial.times.size());
      if (strict()) throw_at(b.file, b.trial.line, what, b.label());
      b.error = fmt::format("{}:{}: {} (trial {})", names[b.file], b.trial.line, what, b.label());
      b.error_line = b.trial.line;
      b.error_file = b.file;
    }
    if (b.error.empty()) {
      rows_ok += b.trial.rows;
      b.trial.padding_rows = b.padding;
      if (b.padding > 0) {
        rows_padding += b.padding;
        ++trials_padded;
      }
      return true;
    }
    rows_bad += b.trial.rows;
    ++trials_bad;
    Rejection r;
    r.file = names[b.error_file];
    r.line = b.error_line;
    r.participant = b.participant;
    r.condition = b.condition;
    r.iteration = b.iteration;
    r.rows = b.trial.rows;
    r.reason = b.error;
    options.on_reject(r);
    return false;
  }

  // The iteration is a number: `1`, `01` and `+1` are one iteration. A text that is not a whole
  // number keys by itself (the trial is rejected for it anyway).
  std::string iteration_scratch;
  std::string_view iteration_key(std::string_view it) {
    if (const auto v = parse_integer(it)) {
      iteration_scratch = std::to_string(*v);
      return iteration_scratch;
    }
    return it;
  }

  // Same trial as `b`? Text equality first: a log writes a trial's key the same way on every row.
  bool same_trial(const Builder& b, std::string_view p, std::string_view c, std::string_view it) {
    if (p != b.participant || c != b.condition) return false;
    return it == b.iteration || iteration_key(it) == b.iteration_key;
  }

  void make_key(std::string_view p, std::string_view c, std::string_view it) {
    const std::string_view ik = iteration_key(it);
    key_scratch.clear();
    key_scratch.append(p).push_back('\x1f');
    key_scratch.append(c).push_back('\x1f');
    key_scratch.append(ik);
  }

  // Streaming: the next valid trial into `out`.
  bool next_streaming(Trial& out) {
    for (;;) {
      if (!reader) {
        if (!open_next_file()) {
          if (!have_cur) return false;
          have_cur = false;
          if (finish(cur)) {
            std::swap(out, cur.trial);
            return true;
          }
          continue;
        }
      }
      if (!reader->next()) {
        // A trial never continues into the next file: end it here.
        bytes_done += reader->bytes_consumed();
        reader.reset();
        if (have_cur) {
          have_cur = false;
          if (finish(cur)) {
            std::swap(out, cur.trial);
            return true;
          }
        }
        continue;
      }
      ++rows_read;
      const std::string_view p = get(kParticipant), c = get(kCondition), it = get(kIteration);
      if (have_cur && same_trial(cur, p, c, it)) {
        add_row(cur);
        continue;
      }
      bool emitted = false;
      if (have_cur) emitted = finish(cur);
      if (emitted) std::swap(out, cur.trial);
      have_cur = true;
      start(cur, p, c, it);
      make_key(p, c, it);
      const auto [pos, inserted] = seen.try_emplace(key_scratch, Location{file_index, reader->line()});
      if (!inserted) {
        const Location& before = pos->second;
        invalid(cur, reader->line(),
                fmt::format("rows of this trial already appeared at {}:{}{} (a trial's rows must "
                            "be contiguous and in one file; --unsorted buffers and groups them)",
                            names[before.file], before.line,
                            before.file != file_index ? " (it spans two files)" : ""));
      }
      add_row(cur);
      if (emitted) return true;
    }
  }

  // Unsorted: read everything, group by key (first appearance order), then hand out.
  void buffer_all() {
    buffered = true;
    while (open_next_file()) {
      while (reader->next()) {
        ++rows_read;
        const std::string_view p = get(kParticipant), c = get(kCondition), it = get(kIteration);
        make_key(p, c, it);
        auto [pos, inserted] = group_index.try_emplace(key_scratch, groups.size());
        if (inserted) {
          groups.emplace_back();
          start(groups.back(), p, c, it);
        }
        add_row(groups[pos->second]);
      }
    }
    group_index.clear();
  }

  bool next_buffered(Trial& out) {
    if (!buffered) buffer_all();
    while (next_group < groups.size()) {
      Builder& b = groups[next_group++];
      const bool ok = finish(b);
      if (ok) {
        out = std::move(b.trial);
        b = Builder{};
        return true;
      }
      b = Builder{};
    }
    return false;
  }
};

TraceReader::TraceReader(std::vector<std::string> files, TraceOptions options)
    : impl_(std::make_unique<Impl>()) {
  for (const auto& [field, column] : options.column_map) {
    if (std::find(kFieldNames.begin(), kFieldNames.end(), field) == kFieldNames.end()) {
      throw UsageError(fmt::format("--map {}={}: unknown field '{}' (known: {})", field, column,
                                   field, fmt::join(kFieldNames, ", ")));
    }
    if (trim(column).empty()) {
      throw UsageError(fmt::format("--map {}=: the column name is empty", field));
    }
  }
  if (options.pad_speed && !(*options.pad_speed > 0 && *options.pad_speed < 1e300)) {
    throw UsageError(fmt::format("--pad-speed: {} must be a number > 0 (pad units per second)",
                                 *options.pad_speed));
  }
  if (!(options.time_divisor > 0 && std::isfinite(options.time_divisor))) {
    throw UsageError(fmt::format("time divisor {} must be a number > 0", options.time_divisor));
  }
  if (files.empty()) throw UsageError("no input files given");
  if (options.decimal != 0 && options.decimal != '.' && options.decimal != ',') {
    throw UsageError(fmt::format("--decimal '{}': expected . or ,", options.decimal));
  }
  if (options.decimal == ',' && options.delimiter == ',') {
    throw UsageError("--decimal , needs another field separator than the comma (e.g. --delimiter ';')");
  }
  if (options.iteration_base < -1 || options.iteration_base > 1) {
    throw UsageError(fmt::format("--iteration-base {}: expected 0 or 1", options.iteration_base));
  }
  if (options.no_header && options.column_names.empty() && options.column_map.empty()) {
    throw UsageError("--no-header needs the columns' names: --columns NAME,NAME,... (in order) or "
                     "--map FIELD=N (N = column number from 1)");
  }
  const auto& rule = options.participant_from_path;
  if (!rule.empty() && std::find(files.begin(), files.end(), "-") != files.end()) {
    throw UsageError("--participant-from-path cannot name the participant of standard input "
                     "(give the files by name)");
  }
  if (!rule.empty() && rule != "filename" && rule != "dirname") {
    try {
      impl_->path_regex = std::regex(rule, std::regex::ECMAScript);
    } catch (const std::regex_error& e) {
      throw UsageError(fmt::format("--participant-from-path '{}': not a regular expression ({})",
                                   rule, e.what()));
    }
    if (impl_->path_regex.mark_count() < 1) {
      throw UsageError(fmt::format("--participant-from-path '{}': the expression needs a group "
                                   "(...) that captures the id, e.g. 'sub-([0-9]+)'", rule));
    }
  }
  impl_->unit_name = options.time_divisor == 1      ? "seconds"
                     : options.time_divisor == 1000 ? "milliseconds"
                                                    : fmt::format("units of 1/{} s", options.time_divisor);
  impl_->files = std::move(files);
  for (const auto& f : impl_->files) impl_->names.push_back(display_name(f));
  impl_->options = std::move(options);
}

TraceReader::~TraceReader() = default;

bool TraceReader::next(Trial& trial) {
  return impl_->options.unsorted ? impl_->next_buffered(trial) : impl_->next_streaming(trial);
}

std::uint64_t TraceReader::rows_read() const noexcept { return impl_->rows_read; }
std::uint64_t TraceReader::rows_in_trials() const noexcept { return impl_->rows_ok; }
std::uint64_t TraceReader::rows_rejected() const noexcept { return impl_->rows_bad; }
std::uint64_t TraceReader::trials_rejected() const noexcept { return impl_->trials_bad; }
std::uint64_t TraceReader::bytes_consumed() const noexcept {
  return impl_->bytes_done + (impl_->reader ? impl_->reader->bytes_consumed() : 0);
}
std::size_t TraceReader::files_read() const noexcept { return impl_->next_file; }
std::uint64_t TraceReader::rows_padding() const noexcept { return impl_->rows_padding; }
std::uint64_t TraceReader::trials_padded() const noexcept { return impl_->trials_padded; }

std::vector<Diagnostic> TraceReader::diagnostics() const {
  const Impl& m = *impl_;
  std::vector<Diagnostic> out;
  if (m.comma_files > 0) {
    Diagnostic d = m.first_comma;
    d.message += m.comma_files > 1 ? fmt::format(", and so were {} more file(s)", m.comma_files - 1)
                                   : std::string();
    d.message += "; give --decimal . or --decimal , to set the decimal mark instead of detecting it";
    out.push_back(std::move(d));
  }
  if (m.rows_padding > 0) {
    out.push_back({"nan-padding", "", 0, "",
                   fmt::format("dropped {} trailing row(s) without t and pad (NaN, NA or empty: the "
                               "padding of fixed-length arrays) at the end of {} trial(s); they are "
                               "counted with their trials, not rejected",
                               m.rows_padding, m.trials_padded)});
  }
  if (m.options.iteration_base == -1 && m.min_iteration == 0) {
    out.push_back({"iteration-base-0", "", 0, "",
                   fmt::format("iterations start at 0 ({}; iterations {} to {}), as a 0-based loop "
                               "counter (PsychoPy) writes them: kept as written; give "
                               "--iteration-base 0 to number them from 1 as the paper does, or "
                               "--iteration-base 1 to declare them 1-based",
                               m.min_iteration_at, m.min_iteration, m.max_iteration)});
  }
  return out;
}

}  // namespace feint::io

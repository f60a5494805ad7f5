// Logs of K targets and a pointer (see feint/io/pointer_trace.hpp and docs/formats.md).
#include "feint/io/pointer_trace.hpp"

#include <cmath>
#include <optional>
#include <set>
#include <string_view>
#include <utility>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

namespace feint::io {

namespace {

constexpr long long kMaxIteration = 1000000000;

std::string display_name(const std::string& path) { return path == "-" ? "<stdin>" : path; }

std::string column_name(const TraceOptions& o, const std::string& field) {
  const auto it = o.column_map.find(field);
  return it == o.column_map.end() ? field : it->second;
}

// "target12_x" -> (12, 'x'); nullopt for any other name.
std::optional<std::pair<std::size_t, char>> target_column(std::string_view name) {
  const std::string n = to_lower(trim(name));
  if (n.size() < 9 || n.compare(0, 6, "target") != 0) return std::nullopt;
  const char axis = n.back();
  if ((axis != 'x' && axis != 'y') || n[n.size() - 2] != '_') return std::nullopt;
  const std::string digits = n.substr(6, n.size() - 8);
  if (digits.empty() || digits.size() > 6 || digits.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  return std::pair{static_cast<std::size_t>(std::stoul(digits)), axis};
}

// The columns of one file.
struct Columns {
  int participant = -1, condition = -1, iteration = -1, strategy = -1, variant = -1, target = -1, t = -1;
  int belief_x = -1, belief_y = -1, start_x = -1, start_y = -1, robot_x = -1, robot_y = -1;
  std::vector<int> tx, ty;  // target k's columns
};

// A trial being read.
struct Building {
  Trial trial;
  std::vector<std::string> fixed;  // trial-level cells as first written (target, strategy, variant, layout)
  std::string error;
  std::uint64_t error_line = 0;
  bool open = false;
  std::string key;  // participant, condition and the iteration as written (before --iteration-base)
};

}  // namespace

struct PointerTraceReader::Impl {
  std::vector<std::string> files;
  TraceOptions options;
  std::unique_ptr<CsvReader> csv;
  Columns cols;
  std::vector<std::string> fixed_names;  // names of the trial-level columns, in Building::fixed order
  std::vector<int> fixed_cols;
  std::size_t next_file = 0, k = 0;
  std::uint64_t rows = 0, rows_ok = 0, rows_bad = 0, trials_bad = 0, bytes_done = 0;
  std::set<std::string> seen;  // keys of finished trials
  Building b;
  std::optional<Trial> ready;

  std::string name() const { return display_name(csv->path()); }

  [[noreturn]] void fail_header(const std::string& what) const {
    throw InvalidData(fmt::format("{}:1: {}", name(), what));
  }

  void invalid(std::uint64_t line, const std::string& what) {
    const std::string msg = fmt::format("{}:{}: {} (trial {})", name(), line, what, b.trial.label());
    if (!options.on_reject) throw InvalidData(msg);
    if (b.error.empty()) {
      b.error = msg;
      b.error_line = line;
    }
  }

  int find(const std::string& field, bool required) {
    const std::string col = column_name(options, field);
    const int i = csv->column(col, fmt::format("name one exactly with --map {}=COLUMN", field));
    if (i < 0 && required)
      fail_header(fmt::format("no column '{}' (a log of K targets needs {}; give --map {}=COLUMN)", col, field,
                              field));
    return i;
  }

  // Without a condition column every trial is in one condition: refused when the study has several
  // or a column looks like the condition (as TraceReader does), unless --single-condition.
  void check_pooling() {
    if (options.single_condition) return;
    if (options.expected_conditions.size() >= 2)
      fail_header(fmt::format("no condition column '{}', but the study has {} conditions ({}): name the column with "
                              "--map condition=COLUMN; trials would otherwise be pooled into one condition",
                              column_name(options, "condition"), options.expected_conditions.size(),
                              fmt::join(options.expected_conditions, ", ")));
    const auto& header = csv->header();
    for (std::size_t i = 0; i < header.size(); ++i)
      if (detail::looks_like_condition(header[i]))
        fail_header(fmt::format("column '{}' (column {}) looks like the condition, but the condition is read from a "
                                "column named '{}': name it with --map condition={}, or give --single-condition to "
                                "pool every trial into one condition",
                                header[i], i + 1, column_name(options, "condition"), trim(header[i])));
  }

  void read_layout_columns() {
    std::vector<int> xs, ys;
    std::size_t highest = 0;
    bool any = false;
    const auto& header = csv->header();
    for (std::size_t i = 0; i < header.size(); ++i) {
      const auto tc = target_column(header[i]);
      if (!tc) continue;
      any = true;
      highest = std::max(highest, tc->first);
      auto& v = tc->second == 'x' ? xs : ys;
      if (v.size() <= tc->first) v.resize(tc->first + 1, -1);
      v[tc->first] = static_cast<int>(i);
    }
    xs.resize(any ? highest + 1 : 0, -1);
    ys.resize(any ? highest + 1 : 0, -1);
    for (std::size_t j = 0; j < xs.size(); ++j) {
      if (xs[j] < 0 && ys[j] < 0)
        fail_header(fmt::format("column 'target{}_x': missing (targets are numbered 0 to K-1 without gaps; "
                                "the header has target{}_x)",
                                j, highest));
      if (xs[j] < 0 || ys[j] < 0)
        fail_header(fmt::format("column '{}': without '{}' (each target needs both coordinates)",
                                header[static_cast<std::size_t>(xs[j] < 0 ? ys[j] : xs[j])],
                                fmt::format("target{}_{}", j, xs[j] < 0 ? 'x' : 'y')));
    }
    if (xs.size() < 2)
      fail_header(fmt::format("column 'target{}_x': missing: a log of K targets needs K >= 2 (columns target0_x, "
                              "target0_y, target1_x, target1_y, ...); the header has {}",
                              xs.size(), xs.size()));
    if (k != 0 && xs.size() != k)
      fail_header(fmt::format("{} targets, but the files before have {}: one data set has one K", xs.size(), k));
    k = xs.size();
    cols.tx = std::move(xs);
    cols.ty = std::move(ys);
  }

  void find_columns() {
    cols = Columns{};
    cols.participant = find("participant", true);
    cols.condition = find("condition", false);
    if (cols.condition < 0) check_pooling();
    cols.iteration = find("iteration", true);
    cols.strategy = find("strategy", false);
    cols.variant = find("variant", false);
    cols.target = find("target", true);
    cols.t = find("t", true);
    cols.belief_x = find("belief_x", true);
    cols.belief_y = find("belief_y", true);
    cols.start_x = find("start_x", true);
    cols.start_y = find("start_y", true);
    cols.robot_x = find("robot_x", false);
    cols.robot_y = find("robot_y", false);
    if ((cols.robot_x < 0) != (cols.robot_y < 0))
      fail_header(cols.robot_x < 0 ? "column 'robot_y' without 'robot_x' (both or neither)"
                                   : "column 'robot_x' without 'robot_y' (both or neither)");
    read_layout_columns();
    fixed_cols.clear();
    fixed_names.clear();
    auto fix = [&](int c) {
      if (c < 0) return;
      fixed_cols.push_back(c);
      fixed_names.push_back(csv->header()[static_cast<std::size_t>(c)]);
    };
    fix(cols.target);
    fix(cols.strategy);
    fix(cols.variant);
    fix(cols.start_x);
    fix(cols.start_y);
    for (std::size_t j = 0; j < k; ++j) {
      fix(cols.tx[j]);
      fix(cols.ty[j]);
    }
  }

  bool open_next_file() {
    if (csv) bytes_done += csv->bytes_consumed();
    csv.reset();
    if (next_file >= files.size()) return false;
    CsvOptions co;
    co.delimiter = options.delimiter;
    csv = std::make_unique<CsvReader>(files[next_file++], co);
    find_columns();
    return true;
  }

  std::string_view cell(int c) const {
    return c < 0 ? std::string_view() : trim(csv->field(static_cast<std::size_t>(c)));
  }

  // A finite number from column c, or nullopt after reporting it.
  std::optional<double> number(int c) {
    const std::string_view s = cell(c);
    const auto v = parse_double(s);
    if (v && std::isfinite(*v)) return v;
    const std::string& col = csv->header()[static_cast<std::size_t>(c)];
    invalid(csv->line(), s.empty() ? fmt::format("column '{}': empty (expected a finite number)", col)
                                   : fmt::format("column '{}': '{}' is not a finite number", col, s));
    return std::nullopt;
  }

  void start_trial(std::string_view p, std::string_view c, std::string_view it) {
    b = Building{};
    b.open = true;
    b.key = key(p, c, it);
    Trial& t = b.trial;
    t.participant = std::string(p);
    t.condition = std::string(c);
    t.file = name();
    t.line = csv->line();
    t.pad_speed = options.pad_speed;
    const auto i = parse_integer(it);
    // --iteration-base as for pad logs: 0-based iterations are shifted to 1-based; with 1, 0 is invalid.
    if (i && *i == 0 && options.iteration_base == 1) {
      t.iteration = 0;
      invalid(csv->line(), fmt::format("column '{}': iteration 0, but the iterations are 1-based (--iteration-base 1)",
                                       csv->header()[static_cast<std::size_t>(cols.iteration)]));
    } else if (i && *i >= 0 && *i <= kMaxIteration - (options.iteration_base == 0 ? 1 : 0)) {
      t.iteration = options.iteration_base == 0 ? *i + 1 : *i;
    } else {
      t.iteration = 0;
      invalid(csv->line(), fmt::format("column '{}': '{}' is not an iteration (a whole number from 0 to 1e9)",
                                       csv->header()[static_cast<std::size_t>(cols.iteration)], it));
    }
    if (seen.count(key(p, c, it)) != 0)
      invalid(csv->line(), "the trial's rows are not contiguous: it appeared before (rows of a trial follow each "
                           "other, in one file)");
    for (int col : fixed_cols) b.fixed.emplace_back(cell(col));
    read_trial_fields();
  }

  static std::string key(std::string_view p, std::string_view c, std::string_view it) {
    const auto i = parse_integer(it);
    return fmt::format("{}\x1f{}\x1f{}", p, c, i ? std::to_string(*i) : std::string(it));
  }

  // The trial-level fields from the trial's first row.
  void read_trial_fields() {
    Trial& t = b.trial;
    t.strategy = std::string(cell(cols.strategy));
    t.variant = std::string(cell(cols.variant));
    const std::string_view target = cell(cols.target);
    const auto idx = parse_integer(target);
    if (idx && *idx >= 0 && static_cast<std::size_t>(*idx) < k) {
      t.target_index = static_cast<std::size_t>(*idx);
    } else {
      invalid(csv->line(), fmt::format("column '{}': '{}' is not a target index (expected 0 to {}: the log has K = "
                                       "{} targets)",
                                       csv->header()[static_cast<std::size_t>(cols.target)], target, k - 1, k));
    }
    t.target = static_cast<double>(t.target_index);
    t.start_x = number(cols.start_x).value_or(0);
    t.start_y = number(cols.start_y).value_or(0);
    for (std::size_t j = 0; j < k; ++j) {
      t.targets_x.push_back(number(cols.tx[j]).value_or(0));
      t.targets_y.push_back(number(cols.ty[j]).value_or(0));
    }
  }

  void add_row() {
    Trial& t = b.trial;
    ++t.rows;
    for (std::size_t f = 0; f < fixed_cols.size(); ++f) {
      const std::string_view v = cell(fixed_cols[f]);
      if (v != b.fixed[f])
        invalid(csv->line(), fmt::format("column '{}': '{}' differs from '{}' on line {} (a trial-level field, "
                                         "constant within a trial)",
                                         fixed_names[f], v, b.fixed[f], t.line));
    }
    const auto time = number(cols.t);
    const auto bx = number(cols.belief_x);
    const auto by = number(cols.belief_y);
    if (time) {
      const double s = *time / options.time_divisor;
      if (!t.times.empty() && !(s > t.times.back()))
        invalid(csv->line(), fmt::format("column '{}': {} is not after the previous time (t must increase)",
                                         csv->header()[static_cast<std::size_t>(cols.t)], cell(cols.t)));
      t.times.push_back(s);
    }
    if (bx) t.belief_x.push_back(*bx);
    if (by) t.belief_y.push_back(*by);
    if (cols.robot_x >= 0) {
      const auto rx = number(cols.robot_x);
      const auto ry = number(cols.robot_y);
      if (rx) t.robot_x.push_back(*rx);
      if (ry) t.robot_y.push_back(*ry);
    }
  }

  // Trial-level checks once the trial's rows are in: size and the layout (validate(layout, 0, 0)).
  void check_trial() {
    Trial& t = b.trial;
    if (t.rows < 2 && b.error.empty())
      invalid(t.line, fmt::format("column '{}': {} sample(s); a trial needs at least 2",
                                  csv ? csv->header()[static_cast<std::size_t>(cols.t)] : "t", t.rows));
    for (std::size_t j = 0; j < t.targets_x.size() && b.error.empty(); ++j) {
      if (t.targets_x[j] == t.start_x && t.targets_y[j] == t.start_y)
        invalid(t.line, fmt::format("column 'target{}_x': target {} is at the start ({}, {}); a layout's points are "
                                    "distinct",
                                    j, j, format_double(t.start_x), format_double(t.start_y)));
      for (std::size_t i = 0; i < j && b.error.empty(); ++i) {
        if (t.targets_x[i] == t.targets_x[j] && t.targets_y[i] == t.targets_y[j])
          invalid(t.line, fmt::format("column 'target{}_x': targets {} and {} are at one point ({}, {}); a layout's "
                                      "points are distinct",
                                      j, i, j, format_double(t.targets_x[j]), format_double(t.targets_y[j])));
      }
    }
  }

  // Ends the open trial: ready (valid) or rejected.
  void finish(const std::string& file_name) {
    if (!b.open) return;
    b.open = false;
    check_trial();
    Trial& t = b.trial;
    seen.insert(b.key);
    if (b.error.empty()) {
      rows_ok += t.rows;
      ready = std::move(t);
      return;
    }
    ++trials_bad;
    rows_bad += t.rows;
    Rejection r;
    r.file = file_name;
    r.line = b.error_line;
    r.participant = t.participant;
    r.condition = t.condition;
    r.iteration = std::to_string(t.iteration);
    r.rows = t.rows;
    r.reason = b.error;
    options.on_reject(r);
  }

  bool next(Trial& out) {
    while (true) {
      if (!csv && !open_next_file()) {
        return take(out);
      }
      if (!csv->next()) {
        finish(name());
        open_next_file();
        if (take(out)) return true;
        continue;
      }
      ++rows;
      const auto p = cell(cols.participant), c = cell(cols.condition), it = cell(cols.iteration);
      if (!b.open || b.trial.participant != p || b.trial.condition != c || key(p, c, it) != b.key) {
        finish(name());
        start_trial(p, c, it);
      }
      add_row();
      if (take(out)) return true;
    }
  }

  bool take(Trial& out) {
    if (!ready) return false;
    out = std::move(*ready);
    ready.reset();
    return true;
  }
};

bool is_pointer_log(const std::string& file, const TraceOptions& options) {
  if (file == "-" || options.no_header) return false;
  // A file that cannot be opened or has no header is left to TraceReader, whose messages say why.
  try {
    CsvOptions co;
    co.delimiter = options.delimiter;
    const CsvReader csv(file, co);
    return csv.column(column_name(options, "belief_x")) >= 0 && csv.column(column_name(options, "pad")) < 0;
  } catch (const std::exception&) {
    return false;
  }
}

PointerTraceReader::PointerTraceReader(std::vector<std::string> files, TraceOptions options)
    : impl_(std::make_unique<Impl>()) {
  if (options.unsorted || options.no_header || !options.samples_column.empty() || options.decimal == ',' ||
      !options.participant_from_path.empty())
    throw UsageError("logs of K targets are read as written: unsorted rows, headerless files, JSON samples, "
                     "decimal commas and participants named by the path are not supported for them (name the "
                     "columns with --map; --time-unit, --iteration-base, --delimiter and --single-condition apply)");
  if (options.require_pad_speed && !options.pad_speed)
    throw UsageError("the confusion normalisation 'speed' needs the pointer's speed, which logs of K targets do "
                     "not hold: give --pad-speed V (layout scales per second) or --confusion-norm raw");
  impl_->files = std::move(files);
  impl_->options = std::move(options);
}

PointerTraceReader::~PointerTraceReader() = default;
bool PointerTraceReader::next(Trial& trial) { return impl_->next(trial); }
std::uint64_t PointerTraceReader::rows_read() const noexcept { return impl_->rows; }
std::uint64_t PointerTraceReader::rows_in_trials() const noexcept { return impl_->rows_ok; }
std::uint64_t PointerTraceReader::rows_rejected() const noexcept { return impl_->rows_bad; }
std::uint64_t PointerTraceReader::trials_rejected() const noexcept { return impl_->trials_bad; }
std::uint64_t PointerTraceReader::bytes_consumed() const noexcept {
  return impl_->bytes_done + (impl_->csv ? impl_->csv->bytes_consumed() : 0);
}
std::size_t PointerTraceReader::files_read() const noexcept { return impl_->next_file; }
std::vector<Diagnostic> PointerTraceReader::diagnostics() const { return {}; }
std::size_t PointerTraceReader::targets() const noexcept { return impl_->k; }

}  // namespace feint::io

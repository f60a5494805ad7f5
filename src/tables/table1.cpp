#include "feint/tables/table1.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/stats/bayes_factor.hpp"
#include "feint/stats/effect_size.hpp"
#include "feint/stats/ttest.hpp"

namespace feint::tables {

std::vector<MetricSpec> default_metrics() {
  return {{"error", 0.5, ""}, {"confusion", 0.95, "raw"}};
}

namespace {

// "0.95@raw" -> scale "raw", text "0.95"; only confusion has scales.
std::string take_scale(std::string_view text, std::string_view name, std::string_view& value) {
  const auto at = value.find('@');
  if (at == std::string_view::npos) return "";
  const std::string scale = io::to_lower(io::trim(value.substr(at + 1)));
  value = value.substr(0, at);
  if (scale != "raw" && scale != "speed") {
    throw UsageError(fmt::format("--metric '{}': scale '{}' is not a confusion normalisation; "
                                 "expected raw or speed, e.g. confusion=0.95@raw",
                                 text, scale));
  }
  if (io::to_lower(name) != "confusion") {
    throw UsageError(fmt::format("--metric '{}': only confusion has scales (raw, speed); give {}={}",
                                 text, name, io::trim(value)));
  }
  return scale;
}

}  // namespace

MetricSpec parse_metric_spec(std::string_view text) {
  const auto eq = text.find('=');
  const std::string name(io::trim(text.substr(0, eq)));
  if (name.empty()) {
    throw UsageError(fmt::format("--metric '{}': expected NAME=REFERENCE, e.g. error=0.5", text));
  }
  if (eq == std::string_view::npos) {
    for (const auto& d : default_metrics()) {
      if (io::to_lower(name) == d.column) return {name, d.reference, d.scale};
    }
    throw UsageError(fmt::format(
        "--metric '{}': no default reference mean for '{}'; give one as {}=REFERENCE", text, name,
        name));
  }
  std::string_view value = text.substr(eq + 1);
  std::string scale = take_scale(text, name, value);
  const auto ref = io::parse_double(value);
  if (!ref) {
    throw UsageError(fmt::format("--metric '{}': reference '{}' is not a number", text, value));
  }
  return {name, *ref, std::move(scale)};
}

std::string scores_scale(const io::ScoresProvenance& provenance) {
  const std::string norm = io::to_lower(provenance.confusion_normalisation);
  for (const char* s : {"raw", "speed"}) {
    if (norm.rfind(s, 0) == 0) return s;
  }
  return "";
}

void check_reference_scales(const std::vector<MetricSpec>& metrics, std::string_view scale,
                            std::string_view source) {
  for (const auto& m : metrics) {
    if (m.scale.empty() || scale.empty() || m.scale == scale) continue;
    throw UsageError(fmt::format(
        "{}: {} is on the {} scale but its reference {:g} is a value of the {} scale, so a test "
        "against it would say nothing. Score on the reference's scale (--confusion-norm {}), or "
        "give a reference on the scores' scale (--metric {}=VALUE@{}; docs/metrics.md \"One "
        "scale\")",
        source, m.column, scale, m.reference, m.scale, m.scale, m.column, scale));
  }
}

namespace {

bool two_sample(const Table1Options& o) { return o.compare.has_value(); }

std::string label_for(const Table1Options& o, const stats::TestResult& diff,
                      const stats::TestResult* tost) {
  return two_sample(o) ? two_sample_label(diff, o.alpha, tost) : one_sample_label(diff, o.alpha, tost);
}

// p.adjust within a family of row indices (one metric column of one block).
void adjust_family(std::vector<TidyRow>& rows, const std::vector<std::size_t>& family,
                   stats::PAdjustMethod method) {
  if (method == stats::PAdjustMethod::none || family.empty()) return;
  std::vector<std::optional<double>> p;
  p.reserve(family.size());
  for (auto i : family) {
    p.push_back(rows[i].result.computed ? rows[i].result.p_value : std::nullopt);
  }
  const auto adjusted = stats::p_adjust(p, method);
  for (std::size_t k = 0; k < family.size(); ++k) rows[family[k]].result.p_adjusted = adjusted[k];
}

// A paired test needs participants who were measured in both conditions. With none (a
// between-subjects design) every cell would be "not computable": say what is wrong instead.
void require_pairs(const io::ScoresTable& scores, const std::string& a, const std::string& b) {
  std::set<std::string> in_a;
  for (const auto& r : scores.records) {
    if (r.condition == a) in_a.insert(r.participant);
  }
  for (const auto& r : scores.records) {
    if (r.condition == b && in_a.count(r.participant) != 0) return;
  }
  throw UsageError(fmt::format(
      "{}: --paired: no participant occurs in both conditions {} and {} (a between-subjects "
      "design); the paired t-test needs the same participants in both. Leave out --paired for "
      "Welch's t-test of independent groups",
      scores.path, a, b));
}

// Options no data can make right: rejected before the scores are looked at.
void check_options(const Table1Options& o) {
  if (!(o.alpha > 0.0 && o.alpha < 1.0)) {
    throw UsageError(fmt::format("--alpha {}: expected a number in (0, 1)", o.alpha));
  }
  if (!(o.test.conf_level > 0.0 && o.test.conf_level < 1.0)) {
    throw UsageError(fmt::format("--conf-level {}: expected a number in (0, 1)", o.test.conf_level));
  }
  if (o.equivalence && !(std::isfinite(*o.equivalence) && *o.equivalence > 0.0)) {
    throw UsageError(fmt::format("--equivalence {}: expected a margin > 0", *o.equivalence));
  }
  if (o.metrics.empty()) throw UsageError("no metric to tabulate (--metric NAME=REFERENCE)");
  if (!two_sample(o) && (o.paired || o.var_equal)) {
    throw UsageError("--paired and --var-equal need --compare A,B");
  }
  if (o.paired && o.var_equal) throw UsageError("--paired and --var-equal exclude each other");
  if (o.omnibus_permutations == 0) throw UsageError("omnibus_permutations: the maxF family needs at least one");
}

// Position of each metric of the table among the loaded metric columns.
std::vector<int> metric_columns(const io::ScoresTable& scores, const Table1Options& o) {
  std::vector<int> metric_index;
  for (const auto& m : o.metrics) {
    const int i = scores.metric_index(m.column);
    if (i < 0) throw InvalidData(fmt::format("{}: metric column '{}' was not loaded", scores.path, m.column));
    metric_index.push_back(i);
  }
  return metric_index;
}

void require_condition(const io::ScoresTable& scores, const std::vector<std::string>& conditions,
                       const std::string& c, std::string_view option) {
  // The data are valid; the command names a condition they do not have: a usage error (64),
  // as in feint likert and feint analyze.
  if (!scores.has_condition) {
    throw UsageError(fmt::format("{}: {} '{}': the file has no condition column", scores.path,
                                 option, c));
  }
  if (std::find(conditions.begin(), conditions.end(), c) == conditions.end()) {
    std::string conditions_text;
    for (const auto& name : conditions) conditions_text += (conditions_text.empty() ? "" : ", ") + name;
    throw UsageError(fmt::format(
        "{}: {}: condition '{}' does not occur in column 'condition' (conditions: {})",
        scores.path, option, c, conditions_text));
  }
}

// The blocks of the table, each over every iteration: A against B (two-sample mode), or one per
// condition tested against the reference means.
std::vector<Table1Block> table_blocks(const io::ScoresTable& scores, const Table1Options& o) {
  const auto conditions = scores.conditions();
  const auto iterations = scores.iterations();
  std::vector<Table1Block> blocks;
  if (two_sample(o)) {
    const auto& [a, b] = *o.compare;
    require_condition(scores, conditions, a, "--compare");
    require_condition(scores, conditions, b, "--compare");
    if (a == b) {
      throw UsageError(fmt::format("--compare {},{}: a condition cannot be compared with itself", a, b));
    }
    if (o.paired) require_pairs(scores, a, b);
    Table1Block blk;
    blk.group1 = a;
    blk.group2 = b;
    blk.iterations = iterations;
    blocks.push_back(std::move(blk));
  } else {
    std::vector<std::string> chosen = conditions;
    if (!o.condition.empty()) {
      require_condition(scores, conditions, o.condition, "--condition");
      chosen = {o.condition};
    }
    for (const auto& c : chosen) {
      Table1Block blk;
      blk.title = c;
      blk.group1 = c;
      blk.iterations = iterations;
      blocks.push_back(std::move(blk));
    }
  }
  return blocks;
}

// The records of each (condition, iteration), indexed once.
class TrialRecords {
 public:
  explicit TrialRecords(const io::ScoresTable& scores) {
    for (const auto& r : scores.records) cells_[{r.condition, r.iteration}].push_back(&r);
  }
  std::vector<const io::ScoreRecord*> of(const std::string& condition, long long iteration) const {
    const auto f = cells_.find({condition, iteration});
    return f == cells_.end() ? std::vector<const io::ScoreRecord*>{} : f->second;
  }

 private:
  std::map<std::pair<std::string, long long>, std::vector<const io::ScoreRecord*>> cells_;
};

// What the tests of one metric in one block left out, for the warnings.
struct Excluded {
  std::size_t missing = 0;                  // empty cells
  std::vector<std::string> unpaired_notes;  // per iteration: participants without a pair
};

// The difference test of one cell and, with --equivalence, its TOST.
struct CellTests {
  stats::TestResult difference, tost;
};

// The metric's values in the records; empty cells are counted as missing.
std::vector<double> metric_values(const std::vector<const io::ScoreRecord*>& records,
                                  std::size_t mi, std::size_t& missing) {
  std::vector<double> x;
  for (const auto* r : records) {
    if (r->values[mi]) x.push_back(*r->values[mi]);
    else ++missing;
  }
  return x;
}

// The metric's value per participant (the last record wins); empty cells count as missing.
std::map<std::string, double> values_by_participant(
    const std::vector<const io::ScoreRecord*>& records, std::size_t mi, std::size_t& missing) {
  std::map<std::string, double> values;
  for (const auto* r : records) {
    if (r->values[mi]) values[r->participant] = *r->values[mi];
    else ++missing;
  }
  return values;
}

CellTests test_against_reference(const Table1Options& o, const MetricSpec& spec,
                                 const std::vector<double>& x) {
  CellTests tests;
  tests.difference = stats::t_test_one_sample(x, spec.reference, o.test);
  if (o.equivalence) tests.tost = stats::tost_one_sample(x, spec.reference, *o.equivalence, o.test);
  return tests;
}

// Pairs are matched by participant; participants measured in one condition only are left out and
// named in the warnings.
CellTests test_paired(const Table1Options& o, const TrialRecords& records, const Table1Block& blk,
                      long long it, std::size_t mi, Excluded& excluded) {
  const auto xa = values_by_participant(records.of(blk.group1, it), mi, excluded.missing);
  const auto yb = values_by_participant(records.of(blk.group2, it), mi, excluded.missing);
  std::vector<double> x, y;
  std::vector<std::string> lone;
  for (const auto& [p, v] : xa) {
    const auto f = yb.find(p);
    if (f == yb.end()) {
      lone.push_back(p);
      continue;
    }
    x.push_back(v);
    y.push_back(f->second);
  }
  for (const auto& [p, v] : yb) {
    if (!xa.count(p)) lone.push_back(p);
  }
  if (!lone.empty()) {
    std::sort(lone.begin(), lone.end());
    std::string who;
    for (const auto& p : lone) who += (who.empty() ? "" : ", ") + p;
    excluded.unpaired_notes.push_back(fmt::format("iteration {}: {}", it, who));
  }
  CellTests tests;
  tests.difference = stats::t_test_paired(x, y, o.test);
  if (o.equivalence) tests.tost = stats::tost_paired(x, y, *o.equivalence, o.test);
  return tests;
}

CellTests test_independent(const Table1Options& o, const std::vector<double>& x,
                           const std::vector<double>& y) {
  CellTests tests;
  tests.difference =
      o.var_equal ? stats::t_test_student(x, y, o.test) : stats::t_test_welch(x, y, o.test);
  if (o.equivalence) {
    tests.tost = stats::tost_two_sample(x, y, *o.equivalence, o.var_equal, o.test);
  }
  return tests;
}

// The tests of one metric (column mi) at one iteration of a block.
CellTests test_cell(const Table1Options& o, const MetricSpec& spec, const TrialRecords& records,
                    const Table1Block& blk, long long it, std::size_t mi, Excluded& excluded) {
  if (!two_sample(o)) {
    const auto x = metric_values(records.of(blk.group1, it), mi, excluded.missing);
    return test_against_reference(o, spec, x);
  }
  if (o.paired) return test_paired(o, records, blk, it, mi, excluded);
  const auto x = metric_values(records.of(blk.group1, it), mi, excluded.missing);
  const auto y = metric_values(records.of(blk.group2, it), mi, excluded.missing);
  return test_independent(o, x, y);
}

// Appends the tidy row of one test of a cell; returns its index.
std::size_t add_row(std::vector<TidyRow>& rows, const MetricSpec& spec, long long it,
                    const Table1Block& blk, stats::TestResult result) {
  TidyRow row;
  row.metric = spec.column;
  row.iteration = static_cast<int>(it);
  row.group1 = blk.group1;
  row.group2 = blk.group2;
  row.result = std::move(result);
  rows.push_back(std::move(row));
  return rows.size() - 1;
}

void warn_about_exclusions(std::vector<std::string>& warnings, const Table1Block& blk,
                           const MetricSpec& spec, const Excluded& excluded) {
  const std::string where = blk.group2.empty()
                                ? (blk.group1.empty() ? std::string() : " (" + blk.group1 + ")")
                                : " (" + blk.group1 + ", " + blk.group2 + ")";
  const std::size_t missing = excluded.missing;
  if (missing > 0) {
    warnings.push_back(fmt::format("{}{}: {} empty cell{} excluded as missing.", spec.column,
                                   where, missing, missing == 1 ? "" : "s"));
  }
  if (!excluded.unpaired_notes.empty()) {
    std::string s;
    for (const auto& u : excluded.unpaired_notes) s += (s.empty() ? "" : "; ") + u;
    warnings.push_back(fmt::format(
        "{}{}: participants without a pair excluded from the paired test: {}.", spec.column,
        where, s));
  }
}

// One metric column of one block: a test (and TOST) per iteration, each kind adjusted as one
// family within the column.
void tabulate_metric(Table1& t, Table1Block& blk, const Table1Options& o, std::size_t m,
                     std::size_t mi, const TrialRecords& records) {
  const auto& spec = o.metrics[m];
  std::vector<std::size_t> family, tost_family;
  Excluded excluded;
  for (std::size_t ii = 0; ii < blk.iterations.size(); ++ii) {
    const long long it = blk.iterations[ii];
    CellTests tests = test_cell(o, spec, records, blk, it, mi, excluded);
    stats::add_effect_size_intervals(tests.difference);
    stats::add_bayes_factor(tests.difference, o.bf_prior_r);
    Table1Cell& cell = blk.cells[ii][m];
    cell.difference_row = add_row(t.rows, spec, it, blk, std::move(tests.difference));
    family.push_back(cell.difference_row);
    if (o.equivalence) {
      cell.tost_row = add_row(t.rows, spec, it, blk, std::move(tests.tost));
      tost_family.push_back(*cell.tost_row);
    }
  }
  adjust_family(t.rows, family, o.p_adjust);
  adjust_family(t.rows, tost_family, o.p_adjust);
  warn_about_exclusions(t.warnings, blk, spec, excluded);
}

// Labels come after the adjustment (they use the adjusted p); a TOST row shares its difference
// row's label.
void label_rows(Table1& t, const Table1Options& o) {
  for (const auto& blk : t.blocks) {
    for (const auto& row_cells : blk.cells) {
      for (const auto& cell : row_cells) {
        TidyRow& d = t.rows[cell.difference_row];
        const stats::TestResult* tost = cell.tost_row ? &t.rows[*cell.tost_row].result : nullptr;
        d.label = label_for(o, d.result, tost);
        if (cell.tost_row) t.rows[*cell.tost_row].label = d.label;
      }
    }
  }
  if (o.apa) {
    for (auto& r : t.rows) r.apa = apa_string(r.result);
  }
}

}  // namespace

Table1 build_table1(const io::ScoresTable& scores, const Table1Options& options) {
  const Table1Options& o = options;
  check_options(o);

  Table1 t;
  t.options = o;
  t.source = scores.path;
  t.provenance = io::read_scores_provenance(scores.path);
  check_reference_scales(o.metrics, scores_scale(t.provenance), scores.path);

  const std::vector<int> metric_index = metric_columns(scores, o);
  t.blocks = table_blocks(scores, o);
  const TrialRecords records(scores);

  for (auto& blk : t.blocks) {
    blk.cells.assign(blk.iterations.size(), std::vector<Table1Cell>(o.metrics.size()));
  }
  for (std::size_t m = 0; m < o.metrics.size(); ++m) {
    const auto mi = static_cast<std::size_t>(metric_index[m]);
    for (auto& blk : t.blocks) tabulate_metric(t, blk, o, m, mi, records);
  }
  label_rows(t, o);
  if (!two_sample(o) && o.condition.empty() && scores.has_condition && scores.conditions().size() >= 3)
    t.conditions = build_table1_conditions(scores, o);
  return t;
}

}  // namespace feint::tables

// study_findings(): see feint/analysis/study_findings.hpp.
#include "feint/analysis/study_findings.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Dense>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "condition_effect.hpp"
#include "exposure_findings.hpp"
#include "finding_words.hpp"
#include "observer_stage.hpp"
#include "omnibus_findings.hpp"
#include "questionnaire_findings.hpp"
#include "feint/error.hpp"
#include "feint/models/model_relabelling.hpp"
#include "feint/stats/p_adjust.hpp"
#include "feint/stats/permutation.hpp"

namespace feint::analysis {

namespace {

using detail::is_t_test;
using detail::one_sided_words;

const models::AnovaTerm* find_term(const models::MixedModelFit& fit, const std::string& name) {
  for (const auto& t : fit.anova)
    if (t.term == name) return &t;
  return nullptr;
}

/// An F test as a TestResult for classify(): no Bayes factor, no interval.
stats::TestResult f_as_test(const models::AnovaTerm& t) {
  stats::TestResult r;
  r.test = "lmm_f";
  r.computed = t.computed;
  if (t.computed) {
    r.statistic = t.f;
    r.df = t.num_df;
    r.df2 = t.den_df;
    r.p_value = t.p;
  } else {
    r.note = t.note;
  }
  return r;
}

std::string evidence_text(Strength s, Grade g) {
  const std::string grade = to_string(g);
  return grade.empty() ? to_string(s) : grade + " " + to_string(s);
}

std::string p_text(double p) {
  if (p < 0.001) return "p < .001";
  std::string s = fmt::format("{:.3f}", p);
  if (s.rfind("0.", 0) == 0) s.erase(0, 1);
  return "p = " + s;
}

std::string thousands(std::uint64_t n) {  // 10000 -> "10,000"
  std::string s = std::to_string(n);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(static_cast<std::size_t>(i), ",");
  return s;
}

/// The adjusted p-values of `m` into the tests, when its statistics are the table's own t (else
/// the data differ from the tests' and `why_not` says so).
bool take_maxt(const stats::MaxTResult& m, const std::vector<long long>& iterations,
               std::vector<stats::TestResult>& tests, std::string& why_not) {
  for (std::size_t j = 0; j < tests.size(); ++j) {
    const auto& t = tests[j];
    const bool both = t.computed && t.statistic && m.statistic[j];
    if ((t.computed && t.statistic) != m.statistic[j].has_value() ||
        (both && std::fabs(*t.statistic - *m.statistic[j]) > 1e-8 * std::max(1.0, std::fabs(*t.statistic)))) {
      why_not = fmt::format("iteration {}'s t could not be reproduced from the participants' values", iterations[j]);
      return false;
    }
  }
  for (std::size_t j = 0; j < tests.size(); ++j) tests[j].p_adjusted = m.p_adjusted[j];
  return true;
}

/// The paired per-iteration contrasts (conditions within participants) adjusted by maxT over sign
/// flips: each participant's two conditions swapped with all of their iterations
/// (stats::maxt_step_down_paired). Participants without a pair at an iteration are left out of
/// that iteration, as the paired tests leave them out.
std::string maxt_paired(const StudyResults& r, const tables::Table1& comparison, const std::string& metric,
                        const std::vector<long long>& iterations, std::vector<stats::TestResult>& tests,
                        std::string& why_not) {
  const auto& o = comparison.options;
  const int k = r.scores.metric_index(metric);
  if (k < 0 || tests.empty()) return {};
  std::map<long long, std::size_t> column;
  for (std::size_t j = 0; j < iterations.size(); ++j) column[iterations[j]] = j;
  const std::size_t columns = iterations.size();
  // participant -> (A, B) per column; the last record wins, as the paired table takes it.
  std::map<std::string, std::vector<std::pair<double, double>>> pairs;
  const double none = std::nan("");
  for (const auto& rec : r.scores.records) {
    const bool a = rec.condition == o.compare->first, b = rec.condition == o.compare->second;
    const auto c = column.find(rec.iteration);
    const auto& v = rec.values[static_cast<std::size_t>(k)];
    if ((!a && !b) || c == column.end() || !v) continue;
    auto& row = pairs.try_emplace(rec.participant, columns, std::pair{none, none}).first->second;
    (a ? row[c->second].first : row[c->second].second) = *v;
  }
  std::vector<double> differences;
  for (const auto& [_, row] : pairs)
    for (const auto& [x, y] : row) differences.push_back(x - y);  // NaN where either is missing
  if (differences.empty()) return {};
  stats::MaxTOptions mo;
  mo.alternative = o.test.alternative;
  mo.permutations = kIterationPermutations;
  const stats::MaxTResult m = stats::maxt_step_down_paired(differences, columns, mo);
  if (!take_maxt(m, iterations, tests, why_not)) return {};
  return m.exact ? fmt::format("Westfall\u2013Young maxT-adjusted over {} iterations, all {} sign flips of "
                               "the participants' pairs", iterations.size(), thousands(m.labellings))
                 : fmt::format("Westfall\u2013Young maxT-adjusted over {} iterations, {} sign flips of the "
                               "participants' pairs drawn at random", iterations.size(), thousands(m.labellings));
}

/// The per-iteration contrasts' multiplicity correction (docs/findings.md, "Per-iteration
/// contrasts: the maxT correction"): Westfall–Young step-down maxT over the iterations, each
/// participant relabelled between the two conditions with all of their iterations. Fills the
/// tests' p_adjusted and returns the words for the sentence; returns "" (Holm then) where the
/// design does not allow relabelling whole participants, with the reason in `why_not`.
std::string maxt_over_iterations(const StudyResults& r, const tables::Table1& comparison, const std::string& metric,
                                 const std::vector<long long>& iterations, std::vector<stats::TestResult>& tests,
                                 std::string& why_not) {
  const auto& o = comparison.options;
  if (!o.compare) return {};
  if (o.paired) return maxt_paired(r, comparison, metric, iterations, tests, why_not);
  const int k = r.scores.metric_index(metric);
  if (k < 0 || tests.empty()) return {};
  const std::string& a = o.compare->first;
  const std::string& b = o.compare->second;
  std::map<long long, std::size_t> column;
  for (std::size_t j = 0; j < iterations.size(); ++j) column[iterations[j]] = j;
  const std::size_t columns = iterations.size();
  std::map<std::string, std::size_t> row;
  std::vector<int> group;
  std::vector<double> values;  // participant-major, as maxt_step_down takes them
  for (const auto& rec : r.scores.records) {
    if (rec.condition != a && rec.condition != b) continue;
    const auto c = column.find(rec.iteration);
    if (c == column.end()) continue;
    const int g = rec.condition == a ? 1 : 0;
    auto [it, added] = row.emplace(rec.participant, group.size());
    if (added) {
      group.push_back(g);
      values.resize(values.size() + columns, std::nan(""));
    } else if (group[it->second] != g) {
      why_not = fmt::format("participant {} is in both conditions", rec.participant);
      return {};
    }
    double& cell = values[it->second * columns + c->second];
    if (!std::isnan(cell)) {
      why_not = fmt::format("participant {} has two rows for iteration {}", rec.participant, rec.iteration);
      return {};
    }
    const auto& v = rec.values[static_cast<std::size_t>(k)];
    cell = v ? *v : std::nan("");
  }
  stats::MaxTOptions mo;
  mo.alternative = o.test.alternative;
  mo.var_equal = o.var_equal;
  mo.permutations = kIterationPermutations;
  const stats::MaxTResult m = stats::maxt_step_down(values, columns, group, mo);
  // The relabelled statistic must be the table's own t: else the data differ from the tests'.
  if (!take_maxt(m, iterations, tests, why_not)) return {};
  return m.exact ? fmt::format("Westfall\u2013Young maxT-adjusted over {} iterations, all {} labellings of "
                               "the participants", iterations.size(), m.labellings)
                 : fmt::format("Westfall\u2013Young maxT-adjusted over {} iterations, {} labellings of the "
                               "participants drawn at random", iterations.size(), thousands(m.labellings));
}

// H1, per metric: the per-iteration contrasts between the two conditions as one family (maxT over
// the iterations where the design allows it, else Holm); three or more conditions and no pair: the
// omnibus tests per iteration (maxF); with one condition only, a finding that says so.
void add_iteration_findings(std::vector<Finding>& out, const StudyResults& r, const tables::MetricSpec& m,
                            const std::vector<std::string>& conditions, const WordingRules& rules) {
  const std::string question =
      fmt::format("Does {} differ between the conditions, iteration by iteration?", m.column);
  if (r.comparison) {
    // A confirmatory H1 with a direction: its one-sided tests (and maxT over their one-sided t).
    const tables::Table1& comparison = r.comparison_one_sided ? *r.comparison_one_sided : *r.comparison;
    std::vector<stats::TestResult> tests;
    std::vector<long long> iterations;
    std::string g1, g2;
    for (const auto& row : comparison.rows) {
      if (row.metric != m.column || !is_t_test(row.result.test)) continue;
      tests.push_back(row.result);
      iterations.push_back(row.iteration.value_or(0));
      g1 = row.group1;
      g2 = row.group2;
    }
    if (!tests.empty()) {
      std::string why_not;
      const std::string correction = maxt_over_iterations(r, comparison, m.column, iterations, tests, why_not);
      Finding f = family_finding("H1-iterations-" + m.column, "H1", question,
                                 fmt::format("per-iteration contrasts of {}, {} vs {}{}", m.column, g1, g2,
                                             one_sided_words(comparison.options.test.alternative, g1, g2)),
                                 std::move(tests), "comparison", rules, correction);
      f.measure = m.column;
      detail::name_conditions(f, g1, g2);
      if (correction.empty() && !why_not.empty())
        f.warnings.push_back(fmt::format("The per-iteration contrasts of {} are Holm-corrected, not "
                                         "maxT-adjusted: {}.", m.column, why_not));
      out.push_back(std::move(f));
    }
  } else if (conditions.size() > 2) {  // no pair named: the omnibus tests per iteration (maxF)
    if (auto f = detail::omnibus_iteration_finding(r, m.column, rules)) out.push_back(std::move(*f));
  } else if (conditions.size() < 2) {
    out.push_back(one_condition_only("H1-iterations-" + m.column, "H1", question,
                                     conditions.empty() ? std::string() : conditions.front(), "table1"));
  }
}

// Reference plausibility over every participant and iteration: a finding only when the metric's
// reference lies outside the data (the tests against it would then say little).
void add_reference_finding(std::vector<Finding>& out, const StudyResults& r, const tables::MetricSpec& m) {
  const int k = r.scores.metric_index(m.column);
  if (k < 0) return;
  std::map<long long, std::vector<double>> per_iteration;
  for (const auto& rec : r.scores.records) {
    const auto& v = rec.values[static_cast<std::size_t>(k)];
    per_iteration[rec.iteration].push_back(v ? *v : std::nan(""));
  }
  std::vector<std::vector<double>> values;
  for (auto& [it, v] : per_iteration) values.push_back(std::move(v));
  const ReferenceCheck c = check_reference(m.column, m.reference, values);
  if (!c.outside) return;
  Finding f;
  f.id = "reference-" + m.column;
  f.hypothesis = "H1";
  f.question = fmt::format("Is the reference {} = {:g} a plausible value of the metric?", m.column, m.reference);
  f.sentence = c.warning;
  f.evidence = "reference outside the data";
  f.strength = Strength::not_computable;
  f.source = "table1";
  f.warnings.push_back(c.warning);
  out.push_back(std::move(f));
}

// One test of a metric's mixed-model family: the two F tests of the factor model and the slope
// difference(s) of the trend model.
struct ModelTest {
  std::string id, question, what, source, formula, apa;
  stats::TestResult test;
  bool is_f = false;
  bool singular = false;  // the model's fit is on the boundary (lme4: isSingular)
  enum class Kind { interaction, condition, slope } kind = Kind::interaction;
  std::size_t level = 0;  // a slope's condition (its index in the group levels; 0 = the reference)
};

const tables::MetricModel* model_of(const tables::ModelAnalysis* a, const std::string& metric) {
  if (!a) return nullptr;
  for (const auto& m : a->models)
    if (m.metric == metric) return &m;
  return nullptr;
}

// The metrics of either model, the factor model's first (the findings' order).
std::vector<std::string> modelled_metrics(const tables::ModelAnalysis* model, const tables::ModelAnalysis* trend) {
  std::vector<std::string> metrics;
  if (model)
    for (const auto& m : model->models) metrics.push_back(m.metric);
  if (trend)
    for (const auto& m : trend->models)
      if (std::find(metrics.begin(), metrics.end(), m.metric) == metrics.end()) metrics.push_back(m.metric);
  return metrics;
}

// The factor model's tests: the condition x iteration interaction and condition's main effect.
void add_factor_model_tests(std::vector<ModelTest>& family, const tables::MetricModel& m,
                            const std::string& metric) {
  const auto& spec = m.fit.spec;
  const std::string inter = spec.group + ":" + spec.time;
  if (const auto* t = find_term(m.fit, inter)) {
    family.push_back({"H1-model-interaction-" + metric,
                      fmt::format("Does the course of {} over the iterations differ between the conditions?", metric),
                      fmt::format("Condition \u00d7 iteration interaction of {}", metric), "model", m.formula + " (iteration as a factor)",
                      tables::anova_apa(*t), f_as_test(*t), true, m.fit.singular, ModelTest::Kind::interaction, 0});
  }
  if (const auto* t = find_term(m.fit, spec.group)) {
    family.push_back({"H1-model-condition-" + metric,
                      fmt::format("Does {} differ between the conditions, over all iterations?", metric),
                      fmt::format("Main effect of condition on {}", metric), "model", m.formula + " (iteration as a factor)",
                      tables::anova_apa(*t), f_as_test(*t), true, m.fit.singular, ModelTest::Kind::condition, 0});
  }
}

// The trend model's tests: each condition's slope against the first condition's.
void add_trend_model_tests(std::vector<ModelTest>& family, const tables::MetricModel& m,
                           const std::string& metric, double conf_level) {
  const auto& fit = m.fit;
  for (std::size_t k = 1; k < fit.group_levels.size(); ++k) {
    const std::string name = fit.spec.group + fit.group_levels[k] + ":" + fit.spec.time;
    const auto it = std::find(fit.coef_names.begin(), fit.coef_names.end(), name);
    if (it == fit.coef_names.end()) continue;
    Eigen::VectorXd L = Eigen::VectorXd::Zero(fit.beta.size());
    L(static_cast<Eigen::Index>(it - fit.coef_names.begin())) = 1;
    const models::Contrast c = models::contrast(fit, L, conf_level);
    family.push_back({"H1-model-trend-" + metric + (fit.group_levels.size() > 2 ? "-" + fit.group_levels[k] : ""),
                      fmt::format("Does {} change over the iterations at a different rate in the two conditions?", metric),
                      fmt::format("Difference of the linear slopes of {} over the iterations, {} minus {} ({})",
                                  metric, fit.group_levels[k], fit.group_levels[0], name),
                      "model-trend", m.formula + " (iteration as a linear trend)", "", c.test, false,
                      fit.singular, ModelTest::Kind::slope, k});
  }
}

// The relabelling p-values of a family, or why there are none (then the models' own p-values).
struct Relabelling {
  std::string why_not;                     // "" when p holds the relabelling p-values
  std::vector<std::optional<double>> p;    // per test of the family
  std::vector<std::string> words;          // per test: how many labellings, for the sentences
};

// How test k's relabelling p-value was counted (docs/findings.md): over every labelling, over the
// drawn ones until h of them reached the statistic (p = h / drawn), or over all that were drawn.
std::string labelling_words(const models::RelabelledConditionTests& rt, std::uint64_t counted, bool stopped,
                            bool within) {
  const char* what = within ? "labellings (conditions swapped within participants)" : "labellings of the participants";
  if (rt.exact) return fmt::format(" over all {} {}", thousands(counted), what);
  if (stopped)
    return fmt::format(" (sequential: {} of {} {} drawn at random reached the statistic)", rt.exceedances,
                       thousands(counted - 1), what);
  return fmt::format(" over {} {} drawn at random", thousands(counted), what);
}

// Whether some participant has trials in two conditions (conditions within participants).
bool conditions_within(const models::LongData& d) {
  std::map<std::string, const std::string*> first;
  for (std::size_t i = 0; i < d.y.size(); ++i) {
    const auto [it, added] = first.emplace(d.participant[i], &d.group[i]);
    if (!added && *it->second != d.group[i]) return true;
  }
  return false;
}

// Test `mb`'s relabelled statistic, p-value and how it was counted.
struct RelabelledTest {
  const std::optional<double>& statistic;
  const std::optional<double>& p;
  std::string words;
};

RelabelledTest relabelled_test(const models::RelabelledConditionTests& rt, const ModelTest& mb, bool within) {
  using K = ModelTest::Kind;
  static const std::optional<double> none;
  if (mb.kind == K::interaction)
    return {rt.interaction_f, rt.p_interaction,
            labelling_words(rt, rt.labellings_interaction, rt.stopped_interaction, within)};
  if (mb.kind == K::condition)
    return {rt.condition_f, rt.p_condition, labelling_words(rt, rt.labellings_condition, rt.stopped_condition, within)};
  const std::size_t k = mb.level - 1;  // the slope family: one per condition but the first
  if (mb.level == 0 || k >= rt.slope_differences_t.size()) return {none, none, ""};
  return {rt.slope_differences_t[k], rt.p_slope_differences[k],
          labelling_words(rt, rt.labellings_slopes[k], rt.stopped_slopes[k], within)};
}

// Relabelling p-values (docs/findings.md, "Mixed models: relabelling p-values"): whole
// participants permuted between the conditions, or (conditions within participants) each
// participant's conditions swapped, both models refitted each time.
Relabelling relabel_family(const tables::MetricModel* any, const std::vector<ModelTest>& family) {
  Relabelling rl;
  rl.p.resize(family.size());
  rl.words.resize(family.size());
  if (!any || any->data.y.empty()) {
    rl.why_not = "the trials were not given to relabel";
  } else if (any->fit.group_levels.size() < 2) {
    rl.why_not = "one condition (relabelling needs two or more)";
  } else if (!family.empty()) {
    try {
      models::RelabellingOptions ro;
      ro.permutations = kModelPermutations;
      ro.within = conditions_within(any->data);
      const models::RelabelledConditionTests rt =
          models::relabel_condition_tests(any->data, any->fit.group_levels, ro);
      // The relabelled statistics must be the models' own (else the data differ from the fits').
      for (std::size_t i = 0; i < family.size() && rl.why_not.empty(); ++i) {
        const ModelTest& mb = family[i];
        const RelabelledTest t = relabelled_test(rt, mb, ro.within);
        rl.words[i] = t.words;
        if (!mb.test.computed || !mb.test.statistic) continue;
        const std::optional<double>& s = t.statistic;
        if (!s || std::fabs(*s - *mb.test.statistic) > 1e-6 * std::max(1.0, std::fabs(*mb.test.statistic)))
          rl.why_not = fmt::format("the {} could not be reproduced from the trials",
                                   mb.kind == ModelTest::Kind::slope ? "slope difference's t" : "F");
        else
          rl.p[i] = t.p;
      }
    } catch (const Error& e) {  // InvalidData or UsageError: the data cannot be relabelled
      rl.why_not = e.what();
    }
  }
  return rl;
}

// The finding of test i of a metric's family, its p_adjusted already Holm-adjusted over the family.
Finding model_test_finding(const ModelTest& mb, std::size_t i, std::size_t family_size, const std::string& metric,
                           const Relabelling& rl, const WordingRules& rules, Finding f) {
  f.id = mb.id;
  f.hypothesis = "H1";
  f.question = mb.question;
  f.source = mb.source;
  f.strength = classify(mb.test, nullptr, rules, &f.grade);
  f.evidence = evidence_text(f.strength, f.grade);
  if (mb.singular)
    f.warnings.push_back(fmt::format(
        "The mixed model {} is a singular fit: a variance between participants is estimated at "
        "(or near) zero (lme4: isSingular), so its tests rest on the trials' residual variance "
        "alone, as lmerTest's do; the model table says which component.{}",
        mb.formula,
        rl.why_not.empty() ? " The relabelling p-value does not rest on that estimate: each relabelling is "
                             "refitted, boundary and all."
                           : ""));
  if (f.strength == Strength::not_computable) {
    f.sentence = fmt::format("{} in the mixed model {}: not computable ({}).", mb.what, mb.formula,
                             mb.test.note.empty() ? std::string("no test result") : mb.test.note);
    return f;
  }
  if (!rl.why_not.empty())
    f.warnings.push_back(fmt::format(
        "The model tests of {} are Holm-adjusted on the models' own p-values, not on relabelling "
        "p-values ({}): where a participant's trials are correlated in time, the model's F can be "
        "too liberal (docs/findings.md).",
        metric, rl.why_not));
  const std::string holm =
      rl.why_not.empty()
          ? fmt::format("relabelling {}{}; Holm-adjusted over the {} model tests of {}: {}",
                        p_text(*rl.p[i]), rl.words[i], family_size, metric, p_text(*mb.test.p_adjusted))
          : fmt::format("Holm-adjusted over the {} model tests of {}: {}", family_size, metric,
                        p_text(*mb.test.p_adjusted));
  const std::string no_bf =
      mb.test.log_bf10 ? fmt::format("{}, {} t test on the participants' mean scores",
                                     tables::apa_bayes_factor(*mb.test.log_bf10),
                                     f.bf_note.find("paired t test") != std::string::npos ? "paired" : "Welch")
      : f.strength == Strength::evidence_for_difference
          ? "no Bayes factor is available for this test"
          : "no Bayes factor is available for this test, so a non-significant result is not evidence "
            "for no difference";
  if (mb.is_f) {
    f.statistics = mb.apa;
    const std::string numbers = detail::effect_words(f);
    f.sentence = fmt::format("{} in the mixed model {}: {} ({}{}{}; {}; {}).", mb.what, mb.formula, f.evidence,
                             numbers, numbers.empty() ? "" : "; ", mb.apa, holm, no_bf);
  } else {
    const auto& t = mb.test;
    f.statistics = fmt::format("t({}) = {:.2f}, {}", tables::apa_model_df(*t.df), *t.statistic, p_text(*t.p_value));
    f.sentence = fmt::format("{} in the mixed model {}: {} (b = {:.4f} per iteration, {:g}% CI [{:.4f}, "
                             "{:.4f}], {}; {}; {}).",
                             mb.what, mb.formula, f.evidence, *t.estimate, 100 * t.conf_level, *t.conf_low,
                             *t.conf_high, f.statistics, holm, no_bf);
  }
  return f;
}

}  // namespace

std::vector<Finding> study_findings(const StudyResults& r, const std::vector<tables::MetricSpec>& metrics,
                                    const WordingRules& rules) {
  std::vector<Finding> out;
  const auto conditions = r.scores.conditions();
  for (const auto& m : metrics) {
    add_iteration_findings(out, r, m, conditions, rules);
    add_reference_finding(out, r, m);
  }
  // H1 from the mixed models (condition x iteration, the linear trend).
  for (auto& f : mixed_model_findings(r.model ? &*r.model : nullptr,
                                      r.trend_model ? &*r.trend_model : nullptr, rules,
                                      r.table1.options.bf_prior_r))
    out.push_back(std::move(f));
  detail::add_exposure_findings(out, r, metrics, rules);
  for (auto& f : detail::observer_findings(r, rules)) out.push_back(std::move(f));
  // H2 after every H1 finding.
  detail::add_questionnaire_findings(out, r, rules);
  return out;
}

std::vector<Finding> mixed_model_findings(const tables::ModelAnalysis* model, const tables::ModelAnalysis* trend,
                                          const WordingRules& rules, double bf_prior_r) {
  std::vector<Finding> out;
  for (const auto& metric : modelled_metrics(model, trend)) {
    const tables::MetricModel* fm = model_of(model, metric);
    const tables::MetricModel* tm = model_of(trend, metric);
    std::vector<ModelTest> family;
    if (fm) add_factor_model_tests(family, *fm, metric);
    if (tm) add_trend_model_tests(family, *tm, metric, trend->options.conf_level);
    const Relabelling rl = relabel_family(fm ? fm : tm, family);
    // Holm over the family, on the relabelling p-values when there are any.
    std::vector<std::optional<double>> p;
    for (std::size_t i = 0; i < family.size(); ++i) {
      const auto& f = family[i];
      p.push_back(!f.test.computed ? std::nullopt : rl.why_not.empty() ? rl.p[i] : f.test.p_value);
    }
    const auto adj = stats::p_adjust(p, stats::PAdjustMethod::holm);
    for (std::size_t i = 0; i < family.size(); ++i) {
      family[i].test.p_adjusted = adj[i];
      Finding numbers;
      numbers.measure = metric;
      if (fm && family[i].kind == ModelTest::Kind::condition) {
        // Which way and how much, and a Bayes factor that the strength then uses.
        family[i].test.log_bf10 =
            detail::describe_condition_effect(numbers, *fm, model->options.conf_level, bf_prior_r);
      }
      Finding f = model_test_finding(family[i], i, family.size(), metric, rl, rules, std::move(numbers));
      f.test = family[i].is_f ? "F test (mixed model)" : "t test (mixed model)";
      f.p = family[i].test.p_value;
      f.p_adjusted = family[i].test.p_adjusted;
      if (!family[i].is_f && tm && tm->fit.group_levels.size() == 2)  // the slope of B minus A's
        set_test_fields(f, family[i].test, tm->fit.group_levels[1], tm->fit.group_levels[0]);
      if (f.bf_note.empty() && !f.bf10) f.bf_note = "no Bayes factor for this model term";
      detail::add_model_effect_size(f, family[i].test, model ? model->options.conf_level : 0.95);
      if (f.contrast.empty() && family[i].kind == ModelTest::Kind::interaction)
        f.contrast = "condition \u00d7 iteration";  // an F of several df: a contrast, no direction
      out.push_back(std::move(f));
    }
    // Three or more conditions: which of them differ, after the omnibus F.
    if (fm) {
      const Finding* omnibus = nullptr;
      for (const auto& f : out)
        if (f.id == "H1-model-condition-" + metric) omnibus = &f;
      const std::optional<Finding> omnibus_copy = omnibus ? std::optional<Finding>(*omnibus) : std::nullopt;
      for (auto& f : detail::pairwise_condition_findings(*fm, model->options.conf_level, bf_prior_r, rules,
                                                          omnibus_copy ? &*omnibus_copy : nullptr))
        out.push_back(std::move(f));
    }
  }
  return out;
}

}  // namespace feint::analysis

// Table 1's omnibus comparison of three or more conditions: its numbers (see
// feint/tables/table1_conditions.hpp); rendered in table1_conditions_render.cpp.
#include "feint/tables/table1_conditions.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/models/condition_design.hpp"
#include "feint/models/within_anova.hpp"
#include "feint/stats/anova.hpp"
#include "feint/stats/effect_size.hpp"
#include "feint/stats/maxf.hpp"
#include "feint/stats/rank_tests.hpp"
#include "feint/tables/anova.hpp"
#include "feint/tables/table1.hpp"

namespace feint::tables {

namespace {

/// A metric's values in the layout the relabelling takes: participant-major, NaN = missing; between,
/// one value per iteration and the participant's condition; within, one per condition and iteration.
struct MetricValues {
  std::vector<std::string> participants;  // order of first appearance
  std::vector<int> group;                 // between: the participant's condition
  std::vector<double> values;
};

std::size_t index_of(const std::vector<long long>& v, long long x) {
  return static_cast<std::size_t>(std::lower_bound(v.begin(), v.end(), x) - v.begin());
}

std::size_t index_of(const std::vector<std::string>& v, const std::string& x) {
  return static_cast<std::size_t>(std::find(v.begin(), v.end(), x) - v.begin());
}

MetricValues metric_values(const io::ScoresTable& scores, const Table1Conditions& c, std::size_t mi) {
  MetricValues out;
  const std::size_t J = c.iterations.size(), K = c.conditions.size();
  const std::size_t per_participant = c.within ? K * J : J;
  std::map<std::string, std::size_t> row;
  for (const auto& r : scores.records) {
    const auto [at, added] = row.emplace(r.participant, out.participants.size());
    if (added) {
      out.participants.push_back(r.participant);
      out.group.push_back(static_cast<int>(index_of(c.conditions, r.condition)));
      out.values.resize(out.values.size() + per_participant, std::nan(""));
    }
    const std::size_t j = index_of(c.iterations, r.iteration);
    const std::size_t cell = c.within ? index_of(c.conditions, r.condition) * J + j : j;
    if (r.values[mi]) out.values[at->second * per_participant + cell] = *r.values[mi];
  }
  return out;
}

OmnibusRow omnibus_row(const std::string& metric, long long it, const Table1Conditions& c, stats::TestResult r) {
  OmnibusRow o;
  o.row.metric = metric;
  o.row.iteration = static_cast<int>(it);
  for (const auto& name : c.conditions) o.row.group1 += (o.row.group1.empty() ? "" : ", ") + name;
  o.row.result = std::move(r);
  return o;
}

// effectsize's omega squared of a one-way ANOVA, max(0, (F - 1) df1 / (F df1 + df2 + 1)), and its
// interval: effectsize (.F_to_pve) takes every proportion of variance through the pseudo-F of the
// estimate, (es / df1) / ((1 - es) / df2), and its noncentral-F interval, which is what
// stats::generalized_eta2 does for ges.
void add_omega_squared(OmnibusRow& o, double conf_level) {
  const auto& r = o.row.result;
  if (!r.computed || !r.statistic || !r.df || !r.df2) return;
  const double f = *r.statistic, df1 = *r.df, df2 = *r.df2;
  const double omega = std::max(0.0, (f - 1) * df1 / (f * df1 + df2 + 1));
  const auto e = stats::generalized_eta2(omega, df1, df2, conf_level, stats::Alternative::greater);
  o.omega_squared = omega;
  o.omega_squared_low = e.low;
  o.omega_squared_high = e.high;
}

// Between: Welch's F (primary), the one-way ANOVA with eta and omega squared, Kruskal–Wallis.
void between_tests(Table1Conditions& c, const Table1Options& opt, const std::string& metric,
                   const MetricValues& v, std::size_t j) {
  const std::size_t J = c.iterations.size();
  std::vector<std::vector<double>> groups(c.conditions.size());
  for (std::size_t i = 0; i < v.participants.size(); ++i)
    if (const double x = v.values[i * J + j]; !std::isnan(x)) groups[static_cast<std::size_t>(v.group[i])].push_back(x);
  const long long it = c.iterations[j];
  OmnibusRow welch = omnibus_row(metric, it, c, stats::welch_anova(groups));
  welch.primary = true;
  c.rows.push_back(std::move(welch));
  stats::TestResult anova = stats::one_way_anova(groups);
  anova.conf_level = opt.test.conf_level;
  stats::add_effect_size_intervals(anova);
  OmnibusRow a = omnibus_row(metric, it, c, std::move(anova));
  add_omega_squared(a, opt.test.conf_level);
  c.rows.push_back(std::move(a));
  c.rows.push_back(omnibus_row(metric, it, c, stats::kruskal_wallis(groups)));
}

// ges's interval as effectsize gives it on an afex model: the df uncorrected for sphericity
// (stats::generalized_eta2). ges = 1 (no error variance) has none.
void add_ges_interval(OmnibusRow& o, const models::AnovaEffect& e, double conf_level) {
  if (!(e.ges < 1) || e.num_df <= 0 || e.den_df <= 0) return;
  const auto ci = stats::generalized_eta2(e.ges, e.num_df, e.den_df, conf_level);
  o.ges_low = ci.low;
  o.ges_high = ci.high;
}

// The repeated-measures F of one iteration as a test result (afex's table under GG).
stats::TestResult repeated_measures(const std::vector<models::Observation>& observations, const std::string& metric,
                                    const std::string& source, double conf_level, OmnibusRow& o) {
  const std::string method = "One-way repeated-measures ANOVA (Greenhouse-Geisser corrected)";
  try {
    const models::WithinDesign d = models::make_within_design(observations, metric, source);
    const models::MixedAnova a = models::within_anova(d, models::SphericityCorrection::GG);
    const models::AnovaEffect& e = a.effects.front();
    stats::TestResult r;
    r.test = "rm_anova";
    r.method = e.report_eps ? method : "One-way repeated-measures ANOVA (sphericity assumed)";
    r.statistic_name = "F";
    r.n1 = d.n();
    r.statistic = e.f;
    r.df = e.report_num_df;
    r.df2 = e.report_den_df;
    r.p_value = e.report_p;
    r.note = e.correction_note;
    if (!d.excluded.empty())
      r.note += fmt::format("{}{} participant(s) without every condition left out", r.note.empty() ? "" : "; ",
                            d.excluded.size());
    o.ges = e.ges;
    o.sphericity_epsilon = e.report_eps;
    add_ges_interval(o, e, conf_level);
    return r;
  } catch (const InvalidData& e) {
    return stats::TestResult::not_computable("rm_anova", method, e.what());
  }
}

// Within: the repeated-measures F (primary) and Friedman's test with Kendall's W.
void within_tests(Table1Conditions& c, const Table1Options& opt, const std::vector<models::Observation>& all,
                  const std::string& source, const std::string& metric, const MetricValues& v, std::size_t j) {
  const std::size_t J = c.iterations.size(), K = c.conditions.size();
  const long long it = c.iterations[j];
  std::vector<models::Observation> here;
  std::copy_if(all.begin(), all.end(), std::back_inserter(here),
               [&](const models::Observation& o) { return o.iteration == it; });
  OmnibusRow rm = omnibus_row(metric, it, c, {});
  rm.row.result = repeated_measures(here, metric, source, opt.test.conf_level, rm);
  rm.primary = true;
  c.rows.push_back(std::move(rm));
  std::vector<std::vector<double>> blocks;  // participants with a value here; friedman_test drops incomplete ones
  for (std::size_t i = 0; i < v.participants.size(); ++i) {
    std::vector<double> b(K);
    bool any = false;
    for (std::size_t k = 0; k < K; ++k) {
      b[k] = v.values[(i * K + k) * J + j];
      any = any || !std::isnan(b[k]);
    }
    if (any) blocks.push_back(std::move(b));
  }
  OmnibusRow fr = omnibus_row(metric, it, c, stats::friedman_test(blocks));
  fr.kendalls_w = stats::kendalls_w(fr.row.result);
  c.rows.push_back(std::move(fr));
}

// The maxF family of one metric: its p-values into the primary rows, once the relabelled statistics
// are seen to be the table's own.
void add_family(Table1Conditions& c, const Table1Options& opt, std::size_t m, const MetricValues& v) {
  OmnibusFamily fam;
  fam.metric = c.metrics[m];
  const std::size_t J = c.iterations.size();
  stats::MaxFOptions mo;
  mo.permutations = opt.omnibus_permutations;
  mo.seed = opt.omnibus_seed;
  const stats::MaxTResult r = c.within ? stats::maxf_step_down_within(v.values, c.conditions.size(), J, mo)
                                       : stats::maxf_step_down_between(v.values, J, v.group, mo);
  for (std::size_t j = 0; j < J; ++j) {
    const auto& t = c.primary(j, m).row.result;
    const bool ours = t.computed && t.statistic;
    if (ours != r.statistic[j].has_value() ||
        (ours && std::fabs(*t.statistic - *r.statistic[j]) > 1e-8 * std::max(1.0, std::fabs(*t.statistic)))) {
      fam.note = fmt::format("iteration {}'s F could not be reproduced from the participants' values",
                             c.iterations[j]);
      c.families.push_back(std::move(fam));
      return;
    }
  }
  for (std::size_t j = 0; j < J; ++j)
    c.rows[(m * J + j) * c.rows_per_cell()].p_maxf = r.p_adjusted[j];
  fam.labellings = r.labellings;
  fam.exact = r.exact;
  c.families.push_back(std::move(fam));
}

// --p-adjust: each kind of test of a metric is one family over the iterations, as in Table 1.
void adjust_and_label(Table1Conditions& c, const Table1Options& opt) {
  const std::size_t J = c.iterations.size(), per = c.rows_per_cell();
  for (std::size_t m = 0; m < c.metrics.size() && opt.p_adjust != stats::PAdjustMethod::none; ++m)
    for (std::size_t k = 0; k < per; ++k) {
      std::vector<std::optional<double>> p;
      for (std::size_t j = 0; j < J; ++j) {
        const auto& r = c.rows[(m * J + j) * per + k].row.result;
        p.push_back(r.computed ? r.p_value : std::nullopt);
      }
      const auto adjusted = stats::p_adjust(p, opt.p_adjust);
      for (std::size_t j = 0; j < J; ++j) c.rows[(m * J + j) * per + k].row.result.p_adjusted = adjusted[j];
    }
  for (auto& o : c.rows) {
    const auto& r = o.row.result;
    const auto p = decision_p(r);
    o.row.label = !r.computed ? std::string(kNotComputable)
                  : p && *p < opt.alpha ? std::string("differ")
                                        : std::string(kNotSignificant);
    if (!opt.apa) continue;
    // apa_string knows an F test by its statistic's name when the test has none of its names.
    stats::TestResult f = r;
    if (f.test == "rm_anova") f.test.clear();
    o.row.apa = apa_string(f);
  }
}

// Within: who was left out of an iteration's tests for lacking a condition there.
void warn_incomplete(Table1Conditions& c, const std::string& metric, const MetricValues& v) {
  const std::size_t J = c.iterations.size(), K = c.conditions.size();
  std::string notes;
  for (std::size_t j = 0; j < J; ++j) {
    std::string who;
    for (std::size_t i = 0; i < v.participants.size(); ++i) {
      std::size_t present = 0;
      for (std::size_t k = 0; k < K; ++k) present += std::isnan(v.values[(i * K + k) * J + j]) ? 0 : 1;
      if (present > 0 && present < K) who += (who.empty() ? "" : ", ") + v.participants[i];
    }
    if (!who.empty()) notes += fmt::format("{}iteration {}: {}", notes.empty() ? "" : "; ", c.iterations[j], who);
  }
  if (!notes.empty())
    c.warnings.push_back(fmt::format("{}: participants without every condition at an iteration left out of its "
                                     "repeated-measures F and Friedman test: {}.",
                                     metric, notes));
}

// Undeclared, with every participant in several conditions but not all in every one: the design is
// unclear. Said here, because models::check_condition_design names a participant "in one only"
// for it, and there is none.
std::string unclear_design(const io::ScoresTable& scores, std::size_t conditions) {
  std::map<std::string, std::set<std::string>> seen;
  for (const auto& r : scores.records) seen[r.participant].insert(r.condition);
  for (const auto& [who, in] : seen)
    if (in.size() < 2) return {};
  for (const auto& [who, in] : seen)
    if (in.size() < conditions)
      return fmt::format(
          "{}: participant '{}' has trials in {} of the {} conditions while others saw every condition: declare "
          "the design (design = \"within\" in feint.toml, or --design within) when every participant was meant "
          "to see every condition",
          scores.path, who, in.size(), conditions);
  return {};
}

}  // namespace

Table1Conditions build_table1_conditions(const io::ScoresTable& scores, const Table1Options& o) {
  Table1Conditions c;
  c.conditions = scores.conditions();
  c.iterations = scores.iterations();
  for (const auto& m : o.metrics) c.metrics.push_back(m.column);
  if (!o.design) c.not_computed = unclear_design(scores, c.conditions.size());
  if (!c.not_computed.empty()) return c;
  try {
    const auto design = models::check_condition_design(observations(scores, o.metrics.front().column), o.design,
                                                       scores.path);
    c.within = design.design == models::ConditionDesign::within;
    c.design_note = design.note;
  } catch (const InvalidData& e) {
    c.not_computed = e.what();
    return c;
  }
  for (std::size_t m = 0; m < o.metrics.size(); ++m) {
    const int mi = scores.metric_index(o.metrics[m].column);
    const MetricValues v = metric_values(scores, c, static_cast<std::size_t>(mi));
    const auto all = c.within ? observations(scores, o.metrics[m].column) : std::vector<models::Observation>{};
    for (std::size_t j = 0; j < c.iterations.size(); ++j) {
      if (c.within) within_tests(c, o, all, scores.path, c.metrics[m], v, j);
      else between_tests(c, o, c.metrics[m], v, j);
    }
    add_family(c, o, m, v);
    if (c.within) warn_incomplete(c, c.metrics[m], v);
  }
  adjust_and_label(c, o);
  return c;
}

}  // namespace feint::tables

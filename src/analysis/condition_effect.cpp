#include "condition_effect.hpp"

#include <cmath>
#include <map>
#include <vector>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/models/emmeans.hpp"
#include "feint/stats/bayes_factor.hpp"
#include "feint/stats/effect_size.hpp"
#include "feint/stats/ttest.hpp"

namespace feint::analysis::detail {

namespace {

const models::AnovaTerm* term_of(const models::MixedModelFit& fit, const std::string& name) {
  for (const auto& t : fit.anova)
    if (t.term == name) return &t;
  return nullptr;
}

// The participants' mean scores in each of the two conditions: each person one number per
// condition, so that the t test and its Bayes factor are on independent units (Welch between
// participants). `paired` when some participant saw both (conditions within participants): then
// only those who saw both, in the same order in both vectors (a paired t test).
struct ParticipantMeans {
  std::vector<double> a, b;
  bool paired = false;
};

ParticipantMeans participant_means(const models::LongData& d, const std::string& a, const std::string& b) {
  std::map<std::pair<std::string, std::string>, std::pair<double, std::size_t>> per;  // (participant, group)
  for (std::size_t i = 0; i < d.y.size(); ++i) {
    auto& sum = per[{d.participant[i], d.group[i]}];
    sum.first += d.y[i];
    ++sum.second;
  }
  auto mean_of = [&](const std::string& p, const std::string& g) -> std::optional<double> {
    const auto it = per.find({p, g});
    if (it == per.end()) return std::nullopt;
    return it->second.first / static_cast<double>(it->second.second);
  };
  ParticipantMeans out;
  for (const auto& [key, _] : per)
    if (key.second == a && mean_of(key.first, b)) out.paired = true;
  for (const auto& [key, _] : per) {
    const auto& [p, g] = key;
    if (out.paired) {
      if (g != a) continue;
      if (const auto y = mean_of(p, b)) {
        out.a.push_back(*mean_of(p, a));
        out.b.push_back(*y);
      }
    } else if (g == a) {
      out.a.push_back(*mean_of(p, g));
    } else if (g == b) {
      out.b.push_back(*mean_of(p, g));
    }
  }
  return out;
}

std::string two(double v) { return fmt::format("{:.2f}", v); }

// APA: a proportion has no leading zero (".13").
std::string proportion(double v) {
  std::string s = fmt::format("{:.2f}", v);
  if (s.rfind("0.", 0) == 0) s.erase(0, 1);
  return s;
}

}  // namespace

std::optional<double> describe_condition_effect(Finding& f, const tables::MetricModel& m, double conf_level,
                                                double bf_prior_r) {
  const auto& fit = m.fit;
  f.measure = m.metric;
  f.conf_level = conf_level;
  if (const auto* t = term_of(fit, fit.spec.group); t && t->computed) {
    const auto e = stats::f_to_eta2(t->f, t->num_df, t->den_df, conf_level);
    f.effect_size = EffectSize{"eta2_p", e.estimate, e.low, e.high};
  }
  f.omnibus = fit.group_levels.size() > 2;
  if (fit.group_levels.size() != 2) return std::nullopt;
  const std::string& a = fit.group_levels[0];
  const std::string& b = fit.group_levels[1];
  try {
    const auto c = models::emm_contrasts(fit, models::EmmFamily::pairwise_condition, models::EmmAdjust::none,
                                         conf_level);
    if (c.size() == 1 && c[0].computed) {
      // emmeans' label is "first - second" in the levels' order.
      f.contrast = fmt::format("{} - {}", a, b);
      f.estimate = c[0].estimate;
      f.ci_low = c[0].conf_low;
      f.ci_high = c[0].conf_high;
      f.direction = fmt::format("{} {} {}", a, c[0].estimate > 0 ? ">" : c[0].estimate < 0 ? "<" : "=", b);
    }
    const auto means = models::estimated_means(fit, models::EmmTerm::condition, conf_level);
    if (means.size() == 2) f.means = {means[0].estimate, means[1].estimate};
  } catch (const Error&) {
    // emmeans needs iteration as a factor; a model without it keeps its F test alone.
  }
  const auto log_bf10 = participant_means_bf(m.data, a, b, conf_level, bf_prior_r, f.bf_note);
  if (log_bf10 && std::isfinite(std::exp(*log_bf10))) f.bf10 = std::exp(*log_bf10);
  return log_bf10;
}

std::optional<double> participant_means_bf(const models::LongData& data, const std::string& a, const std::string& b,
                                           double conf_level, double bf_prior_r, std::string& note) {
  const ParticipantMeans pm = participant_means(data, a, b);
  stats::TestOptions o;
  o.conf_level = conf_level;
  stats::TestResult t = pm.paired ? stats::t_test_paired(pm.a, pm.b, o) : stats::t_test_welch(pm.a, pm.b, o);
  stats::add_bayes_factor(t, bf_prior_r);
  if (!t.computed || !t.log_bf10) {
    note = "no Bayes factor: the participants' mean scores cannot be compared";
    return std::nullopt;
  }
  note = pm.paired ? fmt::format("JZS Bayes factor of a paired t test on the participants' mean scores in the "
                                 "two conditions ({} participants who saw both; docs/findings.md)",
                                 pm.a.size())
                   : fmt::format("JZS Bayes factor of a Welch t test on the participants' mean scores "
                                 "({} and {} participants; docs/findings.md)",
                                 pm.a.size(), pm.b.size());
  return t.log_bf10;
}

void protect_by_omnibus(Finding& f, const Finding* omnibus, const std::string& measure) {
  if (f.strength != Strength::evidence_for_difference || !omnibus ||
      omnibus->strength == Strength::evidence_for_difference)
    return;
  f.strength = Strength::no_evidence_either_way;
  f.grade = Grade::none;
  const std::string was = f.evidence;
  f.evidence = to_string(f.strength);
  if (const auto at = f.sentence.find(": " + was); at != std::string::npos)
    f.sentence.replace(at + 2, was.size(), f.evidence);
  f.warnings.push_back(fmt::format(
      "The omnibus test of condition on {} did not show a difference ({}), so no pair is claimed to "
      "differ (the pairwise contrasts are interpreted only after the omnibus test: docs/findings.md).",
      measure, omnibus->evidence));
}

std::vector<Finding> pairwise_condition_findings(const tables::MetricModel& m, double conf_level, double bf_prior_r,
                                                 const WordingRules& rules, const Finding* omnibus) {
  const auto& fit = m.fit;
  const std::size_t k = fit.group_levels.size();
  if (k < 3) return {};
  std::vector<models::EmmRow> pairs, means;
  try {
    pairs = models::emm_contrasts(fit, models::EmmFamily::pairwise_condition, models::EmmAdjust::tukey, conf_level);
    means = models::estimated_means(fit, models::EmmTerm::condition, conf_level);
  } catch (const Error&) {
    return {};  // emmeans needs iteration as a factor
  }
  std::map<std::string, double> mean_of;
  for (const auto& e : means) mean_of[e.label] = e.estimate;
  std::vector<Finding> out;
  for (const auto& row : pairs) {
    const auto dash = row.label.find(" - ");
    if (dash == std::string::npos) continue;
    const std::string a = row.label.substr(0, dash), b = row.label.substr(dash + 3);
    stats::TestResult t;
    t.test = "lmm_contrast";
    t.computed = row.computed;
    t.note = row.note;
    t.estimate = row.estimate;
    t.statistic = row.statistic;
    t.df = row.df;
    t.p_value = row.p_unadjusted;
    t.p_adjusted = row.p_value;  // Tukey over the pairs: the finding's p
    t.conf_level = conf_level;
    t.conf_low = row.conf_low;  // Tukey-adjusted interval, as emmeans prints it
    t.conf_high = row.conf_high;
    if (mean_of.count(a) && mean_of.count(b)) {
      t.mean1 = mean_of[a];
      t.mean2 = mean_of[b];
    }
    std::string note;
    t.log_bf10 = participant_means_bf(m.data, a, b, conf_level, bf_prior_r, note);
    Finding f = difference_finding(
        fmt::format("H1-model-pair-{}-{}-{}", m.metric, a, b), "H1",
        fmt::format("Which conditions differ in {}, over all iterations?", m.metric),
        fmt::format("{}, {} against {}, over all iterations (mixed model, emmeans pairwise contrast, "
                    "Tukey-adjusted over the {} pairs of {} conditions)",
                    m.metric, a, b, k * (k - 1) / 2, k),
        t, nullptr, "model", rules);
    f.measure = m.metric;
    name_conditions(f, a, b);
    protect_by_omnibus(f, omnibus, m.metric);
    f.bf_note = note;
    f.test = "t test (mixed model contrast)";
    out.push_back(std::move(f));
  }
  return out;
}

std::string effect_words(const Finding& f) {
  std::vector<std::string> parts;
  if (f.means) parts.push_back(fmt::format("M = {} vs {}", two(f.means->first), two(f.means->second)));
  if (f.estimate && f.ci_low && f.ci_high)
    parts.push_back(fmt::format("difference {}, {:g}% CI [{}, {}]", two(*f.estimate), 100 * f.conf_level,
                                two(*f.ci_low), two(*f.ci_high)));
  if (f.effect_size && f.effect_size->name == "eta2_p") {
    const auto& e = *f.effect_size;
    parts.push_back(fmt::format("\u03b7p\u00b2 = {}{}", proportion(e.value),
                                e.ci_low && e.ci_high ? fmt::format(" [{}, {}]", proportion(*e.ci_low),
                                                                    proportion(*e.ci_high))
                                                      : std::string()));
  }
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : "; ") + p;
  return out;
}

void add_model_effect_size(Finding& f, const stats::TestResult& test, double conf_level) {
  if (f.effect_size || !test.computed || !test.statistic || !test.df) return;
  const bool is_f = test.df2.has_value();
  const double stat = is_f ? *test.statistic : *test.statistic * *test.statistic;
  const double df1 = is_f ? *test.df : 1.0, df2 = is_f ? *test.df2 : *test.df;
  if (!std::isfinite(stat) || !(df1 > 0) || !(df2 > 0)) return;
  const auto e = stats::f_to_eta2(stat, df1, df2, conf_level);
  f.effect_size = EffectSize{"eta2_p", e.estimate, e.low, e.high};
}

void name_conditions(Finding& f, const std::string& a, const std::string& b) {
  auto swap = [&](std::string& s) {
    if (s.size() < 5 || s[0] != 'A' || s[1] != ' ') return;
    const auto pos = s.rfind(" B");
    if (pos == std::string::npos || pos + 2 != s.size()) return;
    s = a + s.substr(1, pos - 1) + " " + b;
  };
  swap(f.contrast);
  swap(f.direction);
}

}  // namespace feint::analysis::detail

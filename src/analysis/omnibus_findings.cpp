// The per-iteration omnibus family of three or more conditions: see omnibus_findings.hpp.
#include "omnibus_findings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "feint/stats/p_adjust.hpp"
#include "feint/tables/table1_conditions.hpp"
#include "feint/tables/writers.hpp"

namespace feint::analysis::detail {

namespace {

using tables::Table1Conditions;

std::string thousands(std::uint64_t n) {  // 10000 -> "10,000"
  std::string s = std::to_string(n);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(static_cast<std::size_t>(i), ",");
  return s;
}

std::string proportion(double v) {  // APA: no leading zero for a value that cannot exceed 1
  std::string s = fmt::format("{:.2f}", v);
  if (s.rfind("0.", 0) == 0) s.erase(0, 1);
  return s;
}

std::string listed(const std::vector<std::string>& names) {  // "a, b and c"
  std::string s;
  for (std::size_t k = 0; k < names.size(); ++k)
    s += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") + names[k];
  return s;
}

/// The conditions' means of metric k at iteration `it` (nullopt: no value). Within participants
/// only the participants with every condition there, as the repeated-measures F takes them.
std::vector<std::optional<double>> condition_means(const io::ScoresTable& scores, const Table1Conditions& c,
                                                   int k, long long it) {
  const std::size_t K = c.conditions.size();
  std::map<std::string, std::vector<std::optional<double>>> values;
  for (const auto& rec : scores.records) {
    const auto& v = rec.values[static_cast<std::size_t>(k)];
    const auto at = std::find(c.conditions.begin(), c.conditions.end(), rec.condition);
    if (rec.iteration != it || !v || std::isnan(*v) || at == c.conditions.end()) continue;
    values.try_emplace(rec.participant, K).first->second[static_cast<std::size_t>(at - c.conditions.begin())] = *v;
  }
  std::vector<double> sum(K, 0.0);
  std::vector<int> n(K, 0);
  for (const auto& [who, row] : values) {
    if (c.within && std::any_of(row.begin(), row.end(), [](const auto& x) { return !x; })) continue;
    for (std::size_t q = 0; q < K; ++q)
      if (row[q]) sum[q] += *row[q], ++n[q];
  }
  std::vector<std::optional<double>> out(K);
  for (std::size_t q = 0; q < K; ++q)
    if (n[q] > 0) out[q] = sum[q] / n[q];
  return out;
}

/// "Westfall–Young maxF-adjusted over 20 iterations, 10,000 relabellings of ... drawn at random, seed S".
std::string correction_words(const Table1Conditions& c, const tables::OmnibusFamily& fam, std::uint64_t seed) {
  const char* what = c.within ? "permutations of the conditions within each participant"
                              : "relabellings of the participants between the conditions";
  const std::string head = fmt::format("Westfall\u2013Young maxF-adjusted over {} iterations", c.iterations.size());
  return fam.exact ? fmt::format("{}, all {} {}", head, thousands(fam.labellings), what)
                   : fmt::format("{}, {} {} drawn at random, seed {}", head, thousands(fam.labellings), what, seed);
}

/// The effect size of iteration i's omnibus test: ω² of the one-way ANOVA beside Welch's F
/// (between), the generalized η² of the repeated-measures F with effectsize's interval (within).
std::optional<EffectSize> member_effect(const Table1Conditions& c, std::size_t i, std::size_t m) {
  const tables::OmnibusRow& p = c.primary(i, m);
  if (!c.within) {
    const tables::OmnibusRow& anova = (&p)[1];
    if (!anova.omega_squared) return std::nullopt;
    return EffectSize{"omega2", *anova.omega_squared, anova.omega_squared_low, anova.omega_squared_high};
  }
  if (!p.ges || p.row.result.n1 < 2) return std::nullopt;
  // The table's interval (effectsize's, with the df uncorrected for sphericity).
  return EffectSize{"eta2_G", *p.ges, p.ges_low, p.ges_high};
}

std::string effect_text(const EffectSize& e, double conf_level) {
  std::string s = fmt::format("{} = {}", e.name == "omega2" ? "\u03c9\u00b2" : "generalized \u03b7\u00b2",
                              proportion(e.value));
  if (e.ci_low && e.ci_high)
    s += fmt::format(", one-sided {:g}% CI [{}, {}]", 100 * conf_level, proportion(*e.ci_low), proportion(*e.ci_high));
  return s;
}

/// Which way: each condition's mean over the iterations `at` (of its per-iteration means), the
/// highest and the lowest named with how often each was highest or lowest there.
std::string ranking_words(const std::vector<std::vector<std::optional<double>>>& means, const std::vector<std::size_t>& at,
                          const Table1Conditions& c, const std::string& where) {
  const std::size_t K = c.conditions.size();
  std::vector<double> sum(K, 0.0);
  std::vector<int> n(K, 0), top(K, 0), bottom(K, 0);
  for (const std::size_t j : at) {
    std::optional<std::size_t> hi, lo;
    for (std::size_t q = 0; q < K; ++q) {
      if (!means[j][q]) continue;
      sum[q] += *means[j][q], ++n[q];
      if (!hi || *means[j][q] > *means[j][*hi]) hi = q;
      if (!lo || *means[j][q] < *means[j][*lo]) lo = q;
    }
    if (hi) ++top[*hi], ++bottom[*lo];
  }
  std::optional<std::size_t> hi, lo;
  for (std::size_t q = 0; q < K; ++q) {
    if (n[q] == 0) continue;
    if (!hi || sum[q] / n[q] > sum[*hi] / n[*hi]) hi = q;
    if (!lo || sum[q] / n[q] < sum[*lo] / n[*lo]) lo = q;
  }
  if (!hi || *hi == *lo) return {};
  return fmt::format(" {}, {} was highest on average (M = {:.2f}; highest at {} of {}) and {} lowest (M = {:.2f}; "
                     "lowest at {} of {}).",
                     where, c.conditions[*hi], sum[*hi] / n[*hi], top[*hi], at.size(), c.conditions[*lo],
                     sum[*lo] / n[*lo], bottom[*lo], at.size());
}

/// The finding of a conditions table that could not be computed.
Finding not_computed(const Table1Conditions& c, const std::string& metric, const std::string& question) {
  Finding f;
  f.id = "H1-iterations-" + metric;
  f.hypothesis = "H1";
  f.question = question;
  f.source = "table1";
  f.measure = metric;
  f.strength = Strength::not_computable;
  f.evidence = to_string(f.strength);
  f.sentence = fmt::format("Per-iteration omnibus tests of {} across the {} conditions: not computable ({}).", metric,
                           c.conditions.size(), c.not_computed);
  return f;
}

/// The member with the smallest adjusted p (family_finding's "test k"): its F, effect size and the
/// conditions' means, the order of those means as the direction, and which way the conditions lie
/// over the iterations with evidence (over all when none has).
void describe_member(Finding& f, const StudyResults& r, const Table1Conditions& c, std::size_t m,
                     const std::vector<stats::TestResult>& tests, const WordingRules& rules) {
  if (f.member.rfind("test ", 0) != 0) return;
  const double conf = r.table1.options.test.conf_level;
  const std::size_t J = c.iterations.size();
  const std::size_t member = static_cast<std::size_t>(std::stoul(f.member.substr(5))) - 1;
  std::vector<std::vector<std::optional<double>>> means;
  std::vector<std::size_t> evidence, computed;
  const int k = r.scores.metric_index(c.metrics[m]);
  if (k < 0) return;  // the table's metrics are the scores' (build_table1 refuses others)
  for (std::size_t j = 0; j < J; ++j) {
    means.push_back(condition_means(r.scores, c, k, c.iterations[j]));
    if (!tests[j].computed) continue;
    computed.push_back(j);
    if (classify(tests[j], nullptr, rules) == Strength::evidence_for_difference) evidence.push_back(j);
  }
  f.effect_size = member_effect(c, member, m);
  std::vector<std::size_t> order;  // the member's conditions, highest mean first
  for (std::size_t q = 0; q < c.conditions.size(); ++q)
    if (means[member][q]) order.push_back(q);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return *means[member][a] > *means[member][b]; });
  std::vector<std::string> names;
  for (const std::size_t q : order) names.push_back(c.conditions[q]);
  f.direction = fmt::format("{}", fmt::join(names, " > "));
  std::vector<std::string> ms;
  for (std::size_t q = 0; q < c.conditions.size(); ++q)
    if (means[member][q]) ms.push_back(fmt::format("{:.2f} ({})", *means[member][q], c.conditions[q]));
  f.sentence += fmt::format(" Test {} (iteration {}): {}{}; M = {}.", member + 1, c.iterations[member],
                            tables::apa_string(tests[member]),
                            f.effect_size ? ", " + effect_text(*f.effect_size, conf) : std::string(),
                            fmt::join(ms, ", "));
  f.sentence += evidence.empty()
                    ? ranking_words(means, computed, c, fmt::format("Over all {} iterations", computed.size()))
                    : ranking_words(means, evidence, c,
                                    fmt::format("Over the {} iteration{} with evidence", evidence.size(),
                                                evidence.size() == 1 ? "" : "s"));
}

}  // namespace

std::optional<Finding> omnibus_iteration_finding(const StudyResults& r, const std::string& metric,
                                                 const WordingRules& rules) {
  if (!r.table1.conditions) return std::nullopt;
  const Table1Conditions& c = *r.table1.conditions;
  const auto mi = std::find(c.metrics.begin(), c.metrics.end(), metric);
  if (mi == c.metrics.end()) return std::nullopt;
  const std::string question = fmt::format("Do the conditions differ in {}, iteration by iteration?", metric);
  if (!c.not_computed.empty()) return not_computed(c, metric, question);
  const auto m = static_cast<std::size_t>(mi - c.metrics.begin());
  const std::size_t J = c.iterations.size();
  if (m >= c.families.size() || c.rows.size() < (m + 1) * J * c.rows_per_cell()) return std::nullopt;
  const tables::OmnibusFamily& fam = c.families[m];
  std::vector<stats::TestResult> tests;
  for (std::size_t j = 0; j < J; ++j) {
    stats::TestResult t = c.primary(j, m).row.result;
    t.p_adjusted = c.primary(j, m).p_maxf;
    if (t.test == "rm_anova") t.test.clear();  // apa_string then knows it by its F
    tests.push_back(std::move(t));
  }
  if (!fam.note.empty()) {  // no maxF family: Holm over the iterations, as the two-condition contrasts fall back
    std::vector<std::optional<double>> p;
    for (const auto& t : tests) p.push_back(t.computed ? t.p_value : std::nullopt);
    const auto adjusted = stats::p_adjust(p, stats::PAdjustMethod::holm);
    for (std::size_t j = 0; j < J; ++j) tests[j].p_adjusted = adjusted[j];
  }
  const std::string correction = fam.note.empty() ? correction_words(c, fam, r.table1.options.omnibus_seed) : "";
  Finding f = family_finding(
      "H1-iterations-" + metric, "H1", question,
      fmt::format("per-iteration {} of {} across {}", c.within ? "repeated-measures F tests (Greenhouse\u2013Geisser)"
                                                               : "Welch F tests", metric, listed(c.conditions)),
      tests, "table1", rules, correction);
  f.measure = metric;
  f.test = c.within ? "repeated-measures F test (Greenhouse-Geisser corrected)" : "Welch F test";
  f.contrast = "condition";
  f.means.reset();
  if (!fam.note.empty())
    f.warnings.push_back(fmt::format("The per-iteration omnibus tests of {} are Holm-corrected, not "
                                     "maxF-adjusted: {}.", metric, fam.note));
  if (f.strength == Strength::not_computable) return f;
  describe_member(f, r, c, m, tests, rules);
  return f;
}

}  // namespace feint::analysis::detail

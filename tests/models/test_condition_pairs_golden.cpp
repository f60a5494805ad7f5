// The pairs of three or more conditions on the mixed model (models::emm_contrasts with
// EmmFamily::pairwise_condition, which the findings' pairs of conditions use) against emmeans 1.8.4
// on lmer (tests/golden/models/condition_pairs_golden.R): unadjusted, Holm and Tukey, Satterthwaite
// and Kenward-Roger df, on six data sets: two between participants (balanced; four unbalanced
// conditions with missing trials) and four within (complete; missing trials and a participant in
// one condition only; four conditions with missing trials; a strong effect), each within set with
// (1 | participant) and (1 + condition | participant).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "accuracy.hpp"
#include "feint/models/emmeans.hpp"
#include "feint/models/mixed_model.hpp"
#include "golden_csv.hpp"

namespace {

using namespace feint::models;

// g[dataset|model|ddf][quantity][name]
using Golden = std::map<std::string, std::map<std::string, std::map<std::string, double>>>;
const Golden& golden() {
  static const Golden g = [] {
    Golden m;
    const auto rows = feint::test::read_csv(feint::test::kModelGoldenDir + "condition_pairs_golden.csv");
    for (std::size_t r = 1; r < rows.size(); ++r)
      m[rows[r][0] + "|" + rows[r][1] + "|" + rows[r][2]][rows[r][3]][rows[r][4]] = std::stod(rows[r][5]);
    return m;
  }();
  return g;
}

LongData load(const std::string& dataset) {
  static const auto rows = feint::test::read_csv(feint::test::kModelGoldenDir + "condition_pairs_data.csv");
  LongData d;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    if (rows[r][0] != dataset) continue;
    d.participant.push_back(rows[r][1]);
    d.group.push_back(rows[r][2]);
    d.time.push_back(std::stod(rows[r][3]));
    d.y.push_back(std::stod(rows[r][4]));
  }
  return d;
}

void expect_close(double got, double want, const std::string& family, const std::string& what, double tol) {
  feint::test::record("condition pairs on lmer (emmeans) " + family, got, want, what);
  EXPECT_LE(std::abs(got - want), tol) << what << " " << family << ": feint " << got << ", R " << want;
}

// The fit is iterative: R stops at bobyqa's rhoend 1e-12 where the REML criterion is flat (as in
// test_mixed_model_within_golden.cpp): SE, df and t within 5e-7 relative, estimates within 5e-7 SE,
// p within 5e-7 max(1, |t|) relative (a small p magnifies t's error). R's Tukey p is 1 - ptukey
// (0 below 1e-16, 7.6e-9 off at p = 6.4e-7): 1e-8 absolute more, and to the upper tail integrated
// from its definition as closely as the rest, plus 1e-15 absolute (feint's Tukey p is the upper
// tail itself, ptukey_upper, so even p = 4.3e-24 in w3_strong agrees; the margin is for the fit's
// t, not for the tail); R's Tukey bounds use qtukey (|dq| < 1e-4): 2e-8
// absolute more, and to the bounds from the root of R's ptukey as closely as the rest.
constexpr double kRel = 5e-7;

void check(const std::string& dataset, const std::string& model, DdfMethod ddf, bool within) {
  const bool kr = ddf == DdfMethod::kenward_roger;
  const std::string key = dataset + "|" + model + "|" + (kr ? "Kenward-Roger" : "Satterthwaite");
  SCOPED_TRACE(key);
  const auto& g = golden().at(key);
  ModelSpec spec;
  spec.response = "y";
  spec.ddf = ddf;
  spec.time_scale = TimeScale::factor;
  spec.random_group_slope = model == "f_slope";
  const MixedModelFit fit = fit_mixed_model(load(dataset), spec, !within);
  const double crit = golden().at(dataset + "|" + model + "|").at("REMLcrit").at("");
  EXPECT_LE(fit.reml_criterion, crit + 1e-9);  // feint's optimum is never worse than lme4's
  expect_close(fit.reml_criterion, crit, "REMLcrit", key, 1e-10 * std::abs(crit));
  for (const auto& [adj, name] : {std::pair{EmmAdjust::none, "none"}, {EmmAdjust::holm, "holm"},
                                  {EmmAdjust::tukey, "tukey"}}) {
    const std::string a = name;
    const auto rows = emm_contrasts(fit, EmmFamily::pairwise_condition, adj, 0.95);
    ASSERT_EQ(rows.size(), g.at(a + ".estimate").size()) << a;
    for (const auto& r : rows) {
      const std::string w = key + " " + a + " " + r.label;
      ASSERT_TRUE(g.at(a + ".estimate").count(r.label)) << w;
      ASSERT_TRUE(r.computed) << w << ": " << r.note;
      auto want = [&](const std::string& q) { return g.at(a + "." + q).at(r.label); };
      const double se = want("SE"), t = want("t.ratio"), tt = std::max(1.0, std::abs(t));
      expect_close(r.estimate, want("estimate"), "estimate (in SE)", w, kRel * se);
      expect_close(r.std_error, se, "SE", w, kRel * se);
      expect_close(r.df, want("df"), "df", w, kRel * want("df"));
      expect_close(r.statistic, t, "t", w, kRel * tt);
      const bool tukey = adj == EmmAdjust::tukey;
      expect_close(r.p_value, want("p.value"), tukey ? "Tukey p (R's 1 - ptukey)" : "p", w,
                   kRel * tt * want("p.value") + (tukey ? 1e-8 : 0));
      if (tukey)
        expect_close(r.p_value, want("p_exact"), "Tukey p (its integral)", w, kRel * tt * want("p_exact") + 1e-15);
      // The bounds: estimate -+ a quantile times SE, each within the tolerances above.
      const double bound_tol = kRel * se * 5;
      expect_close(r.conf_low, want("lower.CL"), tukey ? "Tukey lower (qtukey)" : "lower", w,
                   bound_tol + (tukey ? 2e-8 : 0));
      expect_close(r.conf_high, want("upper.CL"), tukey ? "Tukey upper (qtukey)" : "upper", w,
                   bound_tol + (tukey ? 2e-8 : 0));
      if (!tukey) continue;
      expect_close(r.conf_low, want("lower_exact"), "Tukey lower (root of ptukey)", w, bound_tol);
      expect_close(r.conf_high, want("upper_exact"), "Tukey upper (root of ptukey)", w, bound_tol);
    }
  }
}

void check_all(const std::string& dataset, bool within) {
  for (const char* model : {"f_int", "f_slope"}) {
    if (!within && std::string(model) == "f_slope") continue;
    for (const auto ddf : {DdfMethod::satterthwaite, DdfMethod::kenward_roger}) check(dataset, model, ddf, within);
  }
}

}  // namespace

TEST(ConditionPairsGolden, BetweenThreeBalanced) { check_all("b3_balanced", false); }
TEST(ConditionPairsGolden, BetweenFourUnbalancedWithMissingTrials) { check_all("b4_unbalanced", false); }
TEST(ConditionPairsGolden, WithinThreeComplete) { check_all("w3_complete", true); }
TEST(ConditionPairsGolden, WithinThreeMissingTrialsAndAParticipantInOneCondition) { check_all("w3_missing", true); }
TEST(ConditionPairsGolden, WithinFourWithMissingTrials) { check_all("w4_unbalanced", true); }
TEST(ConditionPairsGolden, WithinThreeStrongEffect) { check_all("w3_strong", true); }

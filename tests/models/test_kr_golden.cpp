// Kenward-Roger df (and the new edge-case data sets under Satterthwaite) against lmerTest /
// pbkrtest / emmeans (tests/golden/models/kr_emm_golden.R): type-III F, NumDF, DenDF,
// p, Sum Sq of lmerTest::anova(m, ddf = "Kenward-Roger") and the contrasts of the conditions at
// each iteration of emmeans with lmer.df = "kenward-roger" / "satterthwaite".
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "feint/models/mixed_model.hpp"

#include "golden_csv.hpp"
#include "accuracy.hpp"

namespace {

using feint::models::DdfMethod;
using feint::models::LongData;
using feint::models::MixedModelFit;
using feint::models::ModelSpec;
using feint::models::TimeScale;

const std::string& kDir = feint::test::kModelGoldenDir;

using feint::test::read_csv;


// g[case|ddf][quantity][name]
using Golden = std::map<std::string, std::map<std::string, std::map<std::string, double>>>;
const Golden& golden() {
  static const Golden g = [] {
    Golden m;
    const auto rows = read_csv(kDir + "kr_emm_golden.csv");
    for (std::size_t r = 1; r < rows.size(); ++r)
      m[rows[r][0] + "|" + rows[r][1]][rows[r][2]][rows[r][3]] = std::stod(rows[r][4]);
    return m;
  }();
  return g;
}

void expect_rel(double got, double want, const std::string& what, double tol) {
  const bool kr = what.find("Kenward") != std::string::npos;
  const std::string quantity = what.substr(what.find(' ') + 1, what.find(' ', what.find(' ') + 1) - what.find(' ') - 1);
  feint::test::record((kr ? "Kenward-Roger (pbkrtest) " : "Satterthwaite (lmerTest) ") + quantity, got, want, what);
  EXPECT_LE(std::abs(got - want) / std::max(std::abs(want), 1e-12), tol)
      << what << ": got " << got << ", R " << want;
}

ModelSpec spec_of(const std::string& c, DdfMethod ddf) {
  ModelSpec s;
  s.ddf = ddf;
  if (c == "missing_cell" || c == "trend_slope") s.time_scale = TimeScale::linear;
  if (c == "trend_slope") s.random_slope = true;
  return s;
}

void check(const std::string& c, DdfMethod ddf) {
  const std::string key = c + "|" + (ddf == DdfMethod::kenward_roger ? "Kenward-Roger" : "Satterthwaite");
  const auto& g = golden().at(key);
  const MixedModelFit fit = feint::models::fit_mixed_model(feint::test::load_lmm(c), spec_of(c, ddf), true);
  // What the exact-derivative optimum reaches against lme4's (nloptwrap at 1e-14): measured
  // 1.8e-7 relative (a p of 4e-7: a small p magnifies the error of t), 1.1e-7 in the random
  // slope's t, else below 5e-8; bounds 7.8e-9 absolute with the random slope, else 7.6e-10.
  const double tol = 2e-7;
  const double bound = c == "trend_slope" ? 1e-8 : 1e-9;
  ASSERT_EQ(fit.anova.size(), g.at("F").size()) << key;
  for (const auto& a : fit.anova) {
    ASSERT_TRUE(a.computed) << key << " " << a.term;
    expect_rel(a.f, g.at("F").at(a.term), key + " F " + a.term, tol);
    expect_rel(a.num_df, g.at("NumDF").at(a.term), key + " NumDF " + a.term, tol);
    expect_rel(a.den_df, g.at("DenDF").at(a.term), key + " DenDF " + a.term, tol);
    expect_rel(a.p, g.at("p").at(a.term), key + " p " + a.term, tol);
    expect_rel(a.sum_sq, g.at("SumSq").at(a.term), key + " SumSq " + a.term, tol);
    expect_rel(a.mean_sq, g.at("MeanSq").at(a.term), key + " MeanSq " + a.term, tol);
  }
  // adaptive - random at each iteration.
  for (const double t : fit.time_levels) {
    const std::string it = std::to_string(static_cast<long long>(t));
    const std::string name = "adaptive - random|" + it;
    const auto r = feint::models::contrast(fit, fit.cell_row(0, t) - fit.cell_row(1, t));
    ASSERT_TRUE(r.test.computed) << key << " " << it;
    EXPECT_NEAR(*r.test.estimate, g.at("cond_by_it.estimate").at(name), 5e-10) << key << it;
    expect_rel(r.std_error, g.at("cond_by_it.SE").at(name), key + " SE " + it, tol);
    expect_rel(*r.test.df, g.at("cond_by_it.df").at(name), key + " df " + it, tol);
    expect_rel(*r.test.statistic, g.at("cond_by_it.t").at(name), key + " t " + it, tol);
    expect_rel(*r.test.p_value, g.at("cond_by_it.p").at(name), key + " p " + it, tol);
    feint::test::record(key + " bounds", *r.test.conf_low, g.at("cond_by_it.lower").at(name), it);
    feint::test::record(key + " bounds", *r.test.conf_high, g.at("cond_by_it.upper").at(name), it);
    EXPECT_NEAR(*r.test.conf_low, g.at("cond_by_it.lower").at(name), bound) << key << it;
    EXPECT_NEAR(*r.test.conf_high, g.at("cond_by_it.upper").at(name), bound) << key << it;
  }
}

TEST(KenwardRogerGolden, BalancedMatchesPbkrtest) { check("balanced5", DdfMethod::kenward_roger); }
TEST(KenwardRogerGolden, UnbalancedWithMissingTrialsMatchesPbkrtest) {
  check("unbalanced4_missing", DdfMethod::kenward_roger);
}
TEST(KenwardRogerGolden, ParticipantWithASingleTrialMatchesPbkrtest) {
  check("single_trial", DdfMethod::kenward_roger);
}
TEST(KenwardRogerGolden, TrendWithAnEmptyCellMatchesPbkrtest) {
  check("missing_cell", DdfMethod::kenward_roger);
}
TEST(KenwardRogerGolden, RandomSlopeMatchesPbkrtest) { check("trend_slope", DdfMethod::kenward_roger); }
// F p-values near 1e-8 and contrasts' p to 3e-15 (the other cases' are all above 0.12).
TEST(KenwardRogerGolden, StrongEffectMatchesPbkrtest) { check("strong_effect", DdfMethod::kenward_roger); }
TEST(SatterthwaiteGolden, StrongEffectMatchesLmerTest) { check("strong_effect", DdfMethod::satterthwaite); }

TEST(SatterthwaiteGolden, ParticipantWithASingleTrialMatchesLmerTest) {
  check("single_trial", DdfMethod::satterthwaite);
}
TEST(SatterthwaiteGolden, TrendWithAnEmptyCellMatchesLmerTest) {
  check("missing_cell", DdfMethod::satterthwaite);
}

// Kenward-Roger is scale-invariant too (computed in the normalised units).
TEST(KenwardRoger, ScaleInvariantFrom1e9To1e6) {
  LongData d = feint::test::load_lmm("unbalanced4_missing");
  const ModelSpec s = spec_of("unbalanced4_missing", DdfMethod::kenward_roger);
  const MixedModelFit ref = feint::models::fit_mixed_model(d, s, true);
  for (const double c : {1e-9, 1e-6, 1e6}) {
    LongData e = d;
    for (double& v : e.y) v *= c;
    const MixedModelFit f = feint::models::fit_mixed_model(e, s, true);
    for (std::size_t t = 0; t < f.anova.size(); ++t) {
      expect_rel(f.anova[t].f, ref.anova[t].f, "F", 1e-8);
      expect_rel(f.anova[t].den_df, ref.anova[t].den_df, "DenDF", 1e-8);
      expect_rel(f.anova[t].p, ref.anova[t].p, "p", 1e-8);
    }
  }
}

}  // namespace

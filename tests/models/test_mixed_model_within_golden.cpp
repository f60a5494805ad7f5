// The mixed model with the condition within participants against lme4 / lmerTest / pbkrtest /
// emmeans (tests/golden/models/lmm_within_golden.R): per data set
//   f_int    y ~ condition * factor(iteration) + (1 | participant)
//   f_slope  y ~ condition * factor(iteration) + (1 + condition | participant)
//   t_slope  y ~ condition * iteration         + (1 + condition | participant)
// fixef, diag(vcov), diag(vcovAdj), theta, sigma, REMLcrit, VarCorr, isSingular, the type-III
// anova (Satterthwaite and Kenward-Roger) and pairwise ~ condition | iteration (adjust = "none").
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/models/emmeans.hpp"
#include "feint/models/mixed_model.hpp"

#include "accuracy.hpp"
#include "golden_csv.hpp"

namespace {

using feint::models::DdfMethod;
using feint::models::LongData;
using feint::models::MixedModelFit;
using feint::models::ModelSpec;
using feint::models::TimeScale;

// g[dataset|model|ddf][quantity][name]
using Golden = std::map<std::string, std::map<std::string, std::map<std::string, double>>>;
const Golden& golden() {
  static const Golden g = [] {
    Golden m;
    const auto rows = feint::test::read_csv(feint::test::kModelGoldenDir + "lmm_within_golden.csv");
    for (std::size_t r = 1; r < rows.size(); ++r)
      m[rows[r][0] + "|" + rows[r][1] + "|" + rows[r][2]][rows[r][3]][rows[r][4]] =
          std::stod(rows[r][5]);
    return m;
  }();
  return g;
}

LongData load(const std::string& dataset) {
  static const auto rows =
      feint::test::read_csv(feint::test::kModelGoldenDir + "lmm_within_data.csv");
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

ModelSpec spec_of(const std::string& model, DdfMethod ddf) {
  ModelSpec s;
  s.response = "y";
  s.ddf = ddf;
  s.time_scale = model == "t_slope" ? TimeScale::linear : TimeScale::factor;
  s.random_group_slope = model != "f_int";
  return s;
}

// Agreement within `rel` relative, or `abs` absolute for values near 0 (a boundary theta, an
// estimate of 1e-17 that is 0 up to R's rounding).
void expect_close(double got, double want, const std::string& what, double rel, double abs = 0) {
  // The family: "within <quantity>" (what = "<dataset|model|ddf> <quantity> <name>").
  const std::size_t a = what.find(' ') + 1;
  feint::test::record("within " + what.substr(a, what.find(' ', a) - a), got, want, what);
  EXPECT_LE(std::abs(got - want), std::max(rel * std::abs(want), abs))
      << what << ": got " << got << ", R " << want;
}

// Just above what the exact-derivative optimum reaches against bobyqa at rhoend 1e-12 (measured:
// docs/mixed-model.md, "Conditions within participants"). The REML criteria agree to 4e-15; the
// criterion is so flat near the optimum (a theta step of 3e-7 moves it by 1e-13, lme4's rounding)
// that R stops up to 2.6e-7 away from the root of the exact gradient, where R's own numerical
// gradient is larger than at feint's theta (strong_effect t_slope: 1.4e-6 against 5e-7). That
// moves theta and the correlations by up to 2.6e-7 absolute (5e-6 relative for a theta of 0.017),
// df by 3.9e-7, the variances by 4.7e-7 relative and the rest by 2e-7 or less; a small p
// magnifies t's error by |t| (2.9e-6 at p = 1.3e-10, t = -9.7).
constexpr double kTight = 2e-7;  // vcov, vcovAdj, SE, sigma, F, Sum Sq
constexpr double kRel = 5e-7;    // df, t, estimates (in SE), variances
constexpr double kTheta = 5e-7;  // theta and correlations: absolute

void check_fit(const std::string& dataset, const std::string& model, const MixedModelFit& fit) {
  const std::string key = dataset + "|" + model;
  const auto& g = golden().at(key + "|");
  ASSERT_EQ(fit.coef_names.size(), g.at("beta").size()) << key;
  for (std::size_t i = 0; i < fit.coef_names.size(); ++i) {
    const std::string& nm = fit.coef_names[i];
    const auto k = static_cast<Eigen::Index>(i);
    // Coefficients: relative to their SE (an estimate near 0 has no relative precision).
    expect_close(fit.beta(k), g.at("beta").at(nm), key + " beta " + nm, 0,
                 kRel * std::sqrt(g.at("vcov").at(nm)));
    expect_close(fit.vcov_beta(k, k), g.at("vcov").at(nm), key + " vcov " + nm, kTight);
  }
  ASSERT_EQ(static_cast<std::size_t>(fit.theta.size()), g.at("theta").size()) << key;
  for (Eigen::Index i = 0; i < fit.theta.size(); ++i)
    expect_close(fit.theta(i), g.at("theta").at(std::to_string(i + 1)),
                 key + " theta " + std::to_string(i + 1), 0, kTheta);
  expect_close(fit.sigma, g.at("sigma").at(""), key + " sigma", kTight);
  // REML criteria: feint's optimum is never worse than lme4's (bobyqa stops at rhoend).
  EXPECT_LE(fit.reml_criterion, g.at("REMLcrit").at("") + 1e-9) << key;
  expect_close(fit.reml_criterion, g.at("REMLcrit").at(""), key + " REMLcrit", 1e-13);
  EXPECT_EQ(fit.singular, g.at("singular").at("") != 0) << key;
  const auto& var = g.at("variance");
  expect_close(fit.variance.participant, var.at("participant (Intercept)"), key + " var", kRel);
  expect_close(fit.variance.residual, var.at("Residual NA"), key + " residual", kTight);
  if (model == "f_int") {
    EXPECT_TRUE(fit.variance.group_slopes.empty());
    ASSERT_TRUE(fit.variance.icc.has_value());
    return;
  }
  EXPECT_FALSE(fit.variance.icc.has_value());
  ASSERT_EQ(fit.variance.group_slopes.size(), fit.group_levels.size() - 1) << key;
  for (std::size_t k = 1; k < fit.group_levels.size(); ++k)
    expect_close(fit.variance.group_slopes[k - 1],
                 var.at("participant condition" + fit.group_levels[k]),
                 key + " var " + fit.group_levels[k], kRel);
  std::vector<std::string> names = {"(Intercept)"};
  for (std::size_t k = 1; k < fit.group_levels.size(); ++k)
    names.push_back("condition" + fit.group_levels[k]);
  std::size_t c = 0;
  for (std::size_t j = 0; j < names.size(); ++j)
    for (std::size_t i = j + 1; i < names.size(); ++i, ++c)
      expect_close(fit.variance.group_correlations.at(c),
                   g.at("correlation").at(names[j] + " " + names[i]),
                   key + " cor " + names[j] + " " + names[i], 0, kTheta);
  EXPECT_EQ(c, fit.variance.group_correlations.size());
}

void check_tests(const std::string& dataset, const std::string& model, DdfMethod ddf) {
  const bool kr = ddf == DdfMethod::kenward_roger;
  const std::string key = dataset + "|" + model + "|" + (kr ? "Kenward-Roger" : "Satterthwaite");
  const auto& g = golden().at(key);
  const MixedModelFit fit = feint::models::fit_mixed_model(load(dataset), spec_of(model, ddf), false);
  if (!kr) check_fit(dataset, model, fit);
  if (kr) {
    const auto& va = golden().at(dataset + "|" + model + "|").at("vcov_adj");
    for (std::size_t i = 0; i < fit.coef_names.size(); ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      expect_close(fit.vcov_beta_adj(k, k), va.at(fit.coef_names[i]),
                   key + " vcovAdj " + fit.coef_names[i], kTight);
    }
  }
  ASSERT_EQ(fit.anova.size(), g.at("F").size()) << key;
  for (const auto& a : fit.anova) {
    ASSERT_TRUE(a.computed) << key << " " << a.term << ": " << a.note;
    expect_close(a.f, g.at("F").at(a.term), key + " F " + a.term, kTight);
    EXPECT_EQ(a.num_df, g.at("NumDF").at(a.term)) << key << " " << a.term;
    expect_close(a.den_df, g.at("DenDF").at(a.term), key + " DenDF " + a.term, kRel);
    expect_close(a.p, g.at("p").at(a.term), key + " p " + a.term,
                 kRel * std::max(1.0, std::sqrt(a.f)));  // as |t| for 1 df
    expect_close(a.sum_sq, g.at("SumSq").at(a.term), key + " SumSq " + a.term, kTight);
  }
  // pairwise ~ condition | iteration, every pair of conditions at every iteration.
  std::size_t n = 0;
  for (std::size_t a = 0; a < fit.group_levels.size(); ++a)
    for (std::size_t b = a + 1; b < fit.group_levels.size(); ++b)
      for (const double t : fit.time_levels) {
        const std::string it = std::to_string(static_cast<long long>(t));
        const std::string name = fit.group_levels[a] + " - " + fit.group_levels[b] + "|" + it;
        const auto r = feint::models::contrast(fit, fit.cell_row(a, t) - fit.cell_row(b, t));
        ASSERT_TRUE(r.test.computed) << key << " " << name;
        const double se = g.at("c.SE").at(name);
        expect_close(*r.test.estimate, g.at("c.estimate").at(name), key + " estimate " + name, 0,
                     kRel * se);
        const double t_r = g.at("c.t").at(name);
        expect_close(r.std_error, se, key + " SE " + name, kTight);
        expect_close(*r.test.df, g.at("c.df").at(name), key + " df " + name, kRel);
        expect_close(*r.test.statistic, t_r, key + " t " + name, 0,
                     kRel * std::max(1.0, std::abs(t_r)));
        expect_close(*r.test.p_value, g.at("c.p").at(name), key + " p " + name,
                     kRel * std::max(1.0, std::abs(t_r)));
        ++n;
      }
  EXPECT_EQ(n, g.at("c.p").size()) << key;
  if (model == "t_slope") return;
  // The same through emmeans' API (iteration as a factor).
  for (const auto& row : feint::models::emm_contrasts(
           fit, feint::models::EmmFamily::condition_at_iteration, feint::models::EmmAdjust::none)) {
    const std::string name = row.label + "|" + row.by;
    expect_close(row.std_error, g.at("c.SE").at(name), key + " emm SE " + name, kTight);
    expect_close(row.df, g.at("c.df").at(name), key + " emm df " + name, kRel);
    expect_close(row.p_value, g.at("c.p").at(name), key + " emm p " + name,
                 kRel * std::max(1.0, std::abs(g.at("c.t").at(name))));
  }
}

void check_all(const std::string& dataset) {
  for (const char* model : {"f_int", "f_slope", "t_slope"})
    for (const auto ddf : {DdfMethod::satterthwaite, DdfMethod::kenward_roger}) {
      SCOPED_TRACE(std::string(dataset) + " " + model);
      check_tests(dataset, model, ddf);
    }
}

TEST(MixedModelWithinGolden, TwoConditionsFiveIterationsBalanced) { check_all("balanced2x5"); }
TEST(MixedModelWithinGolden, ThreeConditionsFourIterations) { check_all("three3x4"); }
// Three conditions with 12 % of the trials missing; lme4 puts the last diagonal theta on 0.
TEST(MixedModelWithinGolden, UnbalancedWithMissingTrialsSingular) {
  check_all("unbalanced_missing");
}
TEST(MixedModelWithinGolden, ParticipantsWhoSawOnlyOneCondition) {
  check_all("one_condition_participant");
}
// No participant x condition variance in the simulation: a singular fit (theta 3 = 0).
TEST(MixedModelWithinGolden, SingularConditionSlope) { check_all("singular"); }
TEST(MixedModelWithinGolden, StrongEffect) { check_all("strong_effect"); }

TEST(MixedModelWithin, SingularFitSaysSo) {
  const MixedModelFit fit = feint::models::fit_mixed_model(
      load("singular"), spec_of("f_slope", DdfMethod::satterthwaite), false);
  EXPECT_TRUE(fit.singular);
  // On the boundary: the factor's last diagonal entry is 0 (lme4's theta 3 = 0 exactly), so the
  // two random effects are perfectly correlated (VarCorr's correlation 1).
  EXPECT_LT(fit.theta(2), 1e-12);
  EXPECT_NEAR(fit.variance.group_correlations.at(0), 1.0, 1e-12);
  EXPECT_GT(fit.variance.group_slopes.at(0), 0.0);
}

TEST(MixedModelWithin, RandomConditionSlopeNeedsConditionWithin) {
  ModelSpec s = spec_of("f_slope", DdfMethod::satterthwaite);
  EXPECT_THROW(feint::models::fit_mixed_model(load("balanced2x5"), s, true), feint::UsageError);
  s.time_scale = TimeScale::linear;
  s.random_slope = true;
  EXPECT_THROW(feint::models::fit_mixed_model(load("balanced2x5"), s, false), feint::UsageError);
}

TEST(MixedModelWithin, TooFewTrialsForTheRandomEffectsIsInvalidData) {
  // One trial per participant and condition: 2 m trials for 2 m random effects (lme4 refuses:
  // "number of observations (=2m) <= number of random effects (=2m)").
  LongData d;
  for (int p = 0; p < 6; ++p)
    for (const char* c : {"a", "b"}) {
      d.participant.push_back("P" + std::to_string(p));
      d.group.push_back(c);
      d.time.push_back(1.0 + (p % 2) + (c[0] == 'b' ? 1 : 0));
      d.y.push_back(0.1 * p + (c[0] == 'b' ? 0.3 : 0) + 0.01 * ((p * 7) % 5));
    }
  ModelSpec s;
  s.time_scale = TimeScale::linear;
  s.random_group_slope = true;
  try {
    feint::models::fit_mixed_model(d, s, false);
    FAIL() << "expected InvalidData";
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("not more than the 12 random effects of (1 + condition "
                                         "| participant)"),
              std::string::npos)
        << e.what();
  }
  s.random_group_slope = false;  // the intercept model identifies it
  EXPECT_NO_THROW(feint::models::fit_mixed_model(d, s, false));
}

}  // namespace

// The mixed model at the edges: degenerate designs give a clear InvalidData or the
// fit the data allow, and the fit is scale-invariant (F, df and p unchanged, estimates scaled)
// when the response is multiplied by any factor from 1e-9 to 1e6.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/models/mixed_model.hpp"

#include "mixed_model_normal.hpp"

namespace {

using feint::InvalidData;
using feint::models::LongData;
using feint::models::MixedModelFit;
using feint::models::ModelSpec;
using feint::models::TimeScale;

using feint::test::Normal;

// Two conditions (n_a, n_b participants), `iterations` iterations; a share `missing` of the trials
// dropped at random (never a whole condition x iteration cell in these sizes).
LongData simulate(int n_a, int n_b, int iterations, double missing, std::uint64_t seed,
                  double slope_sd = 0.0) {
  Normal rnorm{seed};
  LongData d;
  for (int k = 0; k < n_a + n_b; ++k) {
    const bool a = k < n_a;
    const double u = 0.3 * rnorm(), s = slope_sd * rnorm();
    for (int j = 1; j <= iterations; ++j) {
      const double y = 0.5 + (a ? 0.05 : -0.01 * j) + u + s * j + 0.2 * rnorm();
      if (rnorm.uniform() < missing) continue;
      d.participant.push_back("P" + std::to_string(k));
      d.group.push_back(a ? "adaptive" : "random");
      d.time.push_back(j);
      d.y.push_back(y);
    }
  }
  return d;
}

LongData scaled(LongData d, double c) {
  for (double& v : d.y) v *= c;
  return d;
}

double rel(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

void expect_scale_invariant(const LongData& d, const ModelSpec& spec, const std::string& what) {
  const MixedModelFit ref = feint::models::fit_mixed_model(d, spec, true);
  for (const double c : {1e-9, 1e-7, 1e-6, 1e-3, 0.37, 1e3, 1e6}) {
    const MixedModelFit f = feint::models::fit_mixed_model(scaled(d, c), spec, true);
    const std::string at = what + " at scale " + std::to_string(c);
    ASSERT_EQ(f.anova.size(), ref.anova.size()) << at;
    for (std::size_t t = 0; t < f.anova.size(); ++t) {
      ASSERT_TRUE(f.anova[t].computed) << at;
      EXPECT_LE(rel(f.anova[t].f, ref.anova[t].f), 1e-8) << at << " F " << f.anova[t].term;
      EXPECT_LE(rel(f.anova[t].den_df, ref.anova[t].den_df), 1e-8) << at << " df";
      EXPECT_LE(rel(f.anova[t].p, ref.anova[t].p), 1e-8) << at << " p";
      EXPECT_LE(rel(f.anova[t].sum_sq, c * c * ref.anova[t].sum_sq), 1e-8) << at << " SumSq";
    }
    const double bmax = ref.beta.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < f.beta.size(); ++i)
      EXPECT_LE(std::abs(f.beta(i) - c * ref.beta(i)) / (c * bmax), 1e-9) << at << " beta " << i;
    EXPECT_LE(rel(f.sigma, c * ref.sigma), 1e-9) << at << " sigma";
    for (Eigen::Index i = 0; i < f.theta.size(); ++i)
      EXPECT_NEAR(f.theta(i), ref.theta(i), 1e-8 * std::max(1.0, std::abs(ref.theta(i)))) << at;
    // A contrast: estimate scaled, t, df and p unchanged.
    const Eigen::VectorXd L = f.cell_row(0, f.time_levels.back()) - f.cell_row(1, f.time_levels.back());
    const auto cf = feint::models::contrast(f, L).test;
    const auto cr = feint::models::contrast(ref, L).test;
    ASSERT_TRUE(cf.computed && cr.computed) << at;
    EXPECT_LE(rel(*cf.df, *cr.df), 1e-8) << at << " contrast df";
    EXPECT_LE(rel(*cf.statistic, *cr.statistic), 1e-8) << at << " contrast t";
    EXPECT_LE(rel(*cf.p_value, *cr.p_value), 1e-8) << at << " contrast p";
    EXPECT_LE(rel(*cf.conf_low, c * *cr.conf_low), 1e-8) << at << " contrast CI";
  }
}

TEST(MixedModelScale, BalancedFactorDesignIsScaleInvariant) {
  expect_scale_invariant(simulate(12, 12, 5, 0.0, 41), ModelSpec{}, "balanced 2x12x5");
}

TEST(MixedModelScale, UnbalancedMissingFactorDesignIsScaleInvariant) {
  expect_scale_invariant(simulate(9, 15, 6, 0.12, 42), ModelSpec{}, "unbalanced 9/15x6, 12% missing");
}

TEST(MixedModelScale, PaperSizedDesignIsScaleInvariant) {
  expect_scale_invariant(simulate(30, 30, 20, 0.03, 43), ModelSpec{}, "2x30x20, 3% missing");
}

TEST(MixedModelScale, TrendAndRandomSlopeAreScaleInvariant) {
  ModelSpec trend;
  trend.time_scale = TimeScale::linear;
  expect_scale_invariant(simulate(11, 14, 8, 0.05, 44), trend, "trend");
  ModelSpec slope = trend;
  slope.random_slope = true;
  expect_scale_invariant(simulate(13, 12, 8, 0.05, 45, 0.05), slope, "random slope");
}

TEST(MixedModelScale, PowerOfTwoScalingIsBitIdentical) {
  const LongData d = simulate(10, 13, 5, 0.1, 46);
  const MixedModelFit a = feint::models::fit_mixed_model(d, ModelSpec{}, true);
  const MixedModelFit b = feint::models::fit_mixed_model(scaled(d, std::ldexp(1.0, -33)), ModelSpec{}, true);
  for (std::size_t t = 0; t < a.anova.size(); ++t) {
    EXPECT_EQ(a.anova[t].f, b.anova[t].f);
    EXPECT_EQ(a.anova[t].den_df, b.anova[t].den_df);
  }
  EXPECT_EQ(std::ldexp(a.sigma, -33), b.sigma);
}

// ---------------------------------------------------------------------------------------------
// Degenerate designs

LongData keep(const LongData& d, const std::function<bool(std::size_t)>& pred) {
  LongData o;
  for (std::size_t i = 0; i < d.y.size(); ++i) {
    if (!pred(i)) continue;
    o.participant.push_back(d.participant[i]);
    o.group.push_back(d.group[i]);
    o.time.push_back(d.time[i]);
    o.y.push_back(d.y[i]);
  }
  return o;
}

std::string error_of(const LongData& d, const ModelSpec& spec = ModelSpec{}) {
  try {
    (void)feint::models::fit_mixed_model(d, spec, true);
  } catch (const InvalidData& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(MixedModelEdge, OneIterationIsAClearError) {
  const LongData d = keep(simulate(6, 6, 4, 0, 50), [&](std::size_t) { return true; });
  const LongData one = keep(d, [&](std::size_t i) { return d.time[i] == 1; });
  const std::string e = error_of(one);
  EXPECT_NE(e.find("every participant has a single trial (one iteration, 1)"), std::string::npos) << e;
  EXPECT_NE(e.find("feint table"), std::string::npos) << e;
  ModelSpec trend;
  trend.time_scale = TimeScale::linear;
  EXPECT_NE(error_of(one, trend).find("single trial"), std::string::npos);
  // One condition and one iteration: the same message (it once crashed here).
  const LongData one_cond = keep(one, [&](std::size_t i) { return one.group[i] == "adaptive"; });
  EXPECT_NE(error_of(one_cond).find("single trial"), std::string::npos);
}

TEST(MixedModelEdge, EveryParticipantWithOneTrialIsAClearError) {
  const LongData d = simulate(6, 6, 2, 0, 51);
  // Participant k keeps only iteration 1 + k % 2: both iterations present, one trial each.
  const LongData s = keep(d, [&](std::size_t i) {
    return d.time[i] == 1.0 + static_cast<double>(std::stoi(d.participant[i].substr(1)) % 2);
  });
  EXPECT_NE(error_of(s).find("12 trials of 12 participants"), std::string::npos) << error_of(s);
}

TEST(MixedModelEdge, OneParticipantIsAClearError) {
  const LongData d = simulate(1, 0, 5, 0, 52);
  EXPECT_NE(error_of(d).find("1 participant (P0): the mixed model needs at least 2"),
            std::string::npos)
      << error_of(d);
}

TEST(MixedModelEdge, OneParticipantPerConditionIsAClearError) {
  const LongData d = simulate(1, 1, 5, 0, 53);
  ModelSpec trend;
  trend.time_scale = TimeScale::linear;
  trend.random_slope = true;
  EXPECT_NE(error_of(d, trend).find("condition is confounded with participant"), std::string::npos)
      << error_of(d, trend);
  EXPECT_NE(error_of(d).find("condition is confounded with participant"), std::string::npos);
}

TEST(MixedModelEdge, RandomSlopesWithTwoTrialsEachAreAClearError) {
  ModelSpec slope;
  slope.time_scale = TimeScale::linear;
  slope.random_slope = true;
  const std::string e = error_of(simulate(8, 8, 2, 0, 54), slope);
  EXPECT_NE(e.find("not more than the 32 random effects"), std::string::npos) << e;
}

TEST(MixedModelEdge, EmptyConditionIterationCellNamesItAndTheWayOut) {
  const LongData d = simulate(6, 6, 4, 0, 55);
  const LongData m = keep(d, [&](std::size_t i) { return !(d.group[i] == "adaptive" && d.time[i] == 3); });
  const std::string e = error_of(m);
  EXPECT_NE(e.find("no observation of condition 'adaptive' at iteration 3"), std::string::npos) << e;
  EXPECT_NE(e.find("--trend"), std::string::npos) << e;
  // As a trend the same data fit.
  ModelSpec trend;
  trend.time_scale = TimeScale::linear;
  const MixedModelFit f = feint::models::fit_mixed_model(m, trend, true);
  EXPECT_EQ(f.anova.size(), 3u);
  for (const auto& a : f.anova) EXPECT_TRUE(a.computed) << a.term;
}

TEST(MixedModelEdge, ParticipantWithASingleTrialIsKept) {
  const LongData d = simulate(8, 8, 4, 0, 56);
  const LongData s = keep(d, [&](std::size_t i) { return d.participant[i] != "P3" || d.time[i] == 2; });
  const MixedModelFit f = feint::models::fit_mixed_model(s, ModelSpec{}, true);
  EXPECT_EQ(f.participants.size(), 16u);
  EXPECT_EQ(f.n_obs, 61u);
  for (const auto& a : f.anova) EXPECT_TRUE(a.computed && std::isfinite(a.f) && a.den_df > 0);
}

}  // namespace

namespace {

TEST(MixedModelEdge, NoVariationWithinParticipantsIsAClearError) {
  LongData d;
  for (int k = 0; k < 6; ++k)
    for (int j = 1; j <= 3; ++j) {
      d.participant.push_back("P" + std::to_string(k));
      d.group.push_back(k % 2 ? "b" : "a");
      d.time.push_back(j);
      d.y.push_back(0.1 * k);
    }
  EXPECT_NE(error_of(d).find("no variation within any participant"), std::string::npos)
      << error_of(d);
}

}  // namespace

// The mixed model's invariants (split-plot ANOVA on balanced data), exposure counting and the
// errors for data that cannot identify the model.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/models/exposure.hpp"
#include "feint/models/mixed_model.hpp"

#include "mixed_model_normal.hpp"

namespace {

using feint::models::LongData;
using feint::models::ModelSpec;

using feint::test::Normal;

// a groups x n participants, b iterations, every trial present.
LongData balanced(int a, int n, int b, std::uint64_t seed, double participant_sd = 0.3) {
  Normal rnorm{seed};
  LongData d;
  for (int g = 0; g < a; ++g) {
    for (int k = 0; k < n; ++k) {
      const double u = participant_sd * rnorm();
      for (int j = 1; j <= b; ++j) {
        d.participant.push_back("P" + std::to_string(g) + "_" + std::to_string(k));
        d.group.push_back("c" + std::to_string(g));
        d.time.push_back(j);
        d.y.push_back(1.0 + 0.1 * g + 0.05 * j * g + u + 0.2 * rnorm());
      }
    }
  }
  return d;
}

struct SplitPlot {
  double f_group, f_time, f_inter, df_subjects, df_within;
};

// The uncorrected split-plot ANOVA from its sums of squares (Kirk, Experimental Design, ch. 12).
SplitPlot split_plot(const LongData& d, int a, int n, int b) {
  auto y = [&](int g, int k, int j) { return d.y[static_cast<std::size_t>((g * n + k) * b + j)]; };
  double grand = 0;
  for (double v : d.y) grand += v;
  grand /= a * n * b;
  std::vector<double> mg(a, 0), mj(b, 0);
  std::vector<std::vector<double>> mgj(a, std::vector<double>(b, 0)),
      ms(a, std::vector<double>(n, 0));
  for (int g = 0; g < a; ++g)
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < b; ++j) {
        mg[g] += y(g, k, j) / (n * b);
        mj[j] += y(g, k, j) / (a * n);
        mgj[g][j] += y(g, k, j) / n;
        ms[g][k] += y(g, k, j) / b;
      }
  double ss_a = 0, ss_s = 0, ss_b = 0, ss_ab = 0, ss_t = 0;
  for (int g = 0; g < a; ++g) ss_a += n * b * std::pow(mg[g] - grand, 2);
  for (int g = 0; g < a; ++g)
    for (int k = 0; k < n; ++k) ss_s += b * std::pow(ms[g][k] - mg[g], 2);
  for (int j = 0; j < b; ++j) ss_b += a * n * std::pow(mj[j] - grand, 2);
  for (int g = 0; g < a; ++g)
    for (int j = 0; j < b; ++j) ss_ab += n * std::pow(mgj[g][j] - mg[g] - mj[j] + grand, 2);
  for (double v : d.y) ss_t += std::pow(v - grand, 2);
  const double ss_e = ss_t - ss_a - ss_s - ss_b - ss_ab;
  const double df_s = a * (n - 1.0), df_e = (b - 1.0) * a * (n - 1.0);
  return {(ss_a / (a - 1)) / (ss_s / df_s), (ss_b / (b - 1)) / (ss_e / df_e),
          (ss_ab / ((a - 1.0) * (b - 1))) / (ss_e / df_e), df_s, df_e};
}

void expect_split_plot(int a, int n, int b, std::uint64_t seed) {
  const LongData d = balanced(a, n, b, seed);
  const auto fit = feint::models::fit_mixed_model(d, ModelSpec{}, true);
  const SplitPlot sp = split_plot(d, a, n, b);
  ASSERT_EQ(fit.anova.size(), 3u);
  ASSERT_FALSE(fit.singular);
  EXPECT_NEAR(fit.anova[0].f / sp.f_group, 1.0, 1e-7);
  EXPECT_NEAR(fit.anova[1].f / sp.f_time, 1.0, 1e-7);
  EXPECT_NEAR(fit.anova[2].f / sp.f_inter, 1.0, 1e-7);
  EXPECT_NEAR(fit.anova[0].den_df, sp.df_subjects, 1e-6 * sp.df_subjects);
  EXPECT_NEAR(fit.anova[1].den_df, sp.df_within, 1e-6 * sp.df_within);
  EXPECT_NEAR(fit.anova[2].den_df, sp.df_within, 1e-6 * sp.df_within);
  EXPECT_DOUBLE_EQ(fit.anova[0].num_df, a - 1.0);
  EXPECT_DOUBLE_EQ(fit.anova[2].num_df, (a - 1.0) * (b - 1.0));
}

TEST(MixedModel, BalancedCompleteDataGiveTheSplitPlotAnovaF) {
  expect_split_plot(2, 12, 5, 1);
  expect_split_plot(3, 5, 4, 2);
  expect_split_plot(2, 30, 20, 3);  // the paper's design
  expect_split_plot(2, 6, 2, 4);
}

TEST(MixedModel, IccIsTheShareOfParticipantVariance) {
  const auto fit = feint::models::fit_mixed_model(balanced(2, 20, 6, 9, 0.5), ModelSpec{}, true);
  ASSERT_TRUE(fit.variance.icc.has_value());
  EXPECT_NEAR(*fit.variance.icc,
              fit.variance.participant / (fit.variance.participant + fit.variance.residual), 1e-15);
  EXPECT_GT(*fit.variance.icc, 0.5);  // participant sd 0.5 against residual sd 0.2
}

TEST(MixedModel, WithoutParticipantVarianceTheFitIsSingularAtZero) {
  LongData d = balanced(2, 10, 4, 5, 0.0);
  // Remove the participant means entirely: no between-participant variation is left.
  for (std::size_t s = 0; s < d.y.size(); s += 4) {
    double m = 0;
    for (int j = 0; j < 4; ++j) m += d.y[s + static_cast<std::size_t>(j)] / 4;
    for (int j = 0; j < 4; ++j) d.y[s + static_cast<std::size_t>(j)] -= m;
  }
  const auto fit = feint::models::fit_mixed_model(d, ModelSpec{}, true);
  EXPECT_TRUE(fit.singular);
  EXPECT_EQ(fit.theta(0), 0.0);
}

TEST(MixedModel, ParticipantInTwoConditionsIsInvalidData) {
  LongData d = balanced(2, 4, 3, 6);
  d.group[1] = "c1";  // P0_0 at iteration 2 in the other condition
  try {
    feint::models::fit_mixed_model(d, ModelSpec{}, true);
    FAIL() << "no error";
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("participant P0_0 is in two conditions ('c0' and 'c1')"),
              std::string::npos)
        << e.what();
  }
}

TEST(MixedModel, MetricWithoutVarianceIsInvalidData) {
  LongData d = balanced(2, 4, 3, 7);
  for (auto& v : d.y) v = 0.5;
  try {
    feint::models::fit_mixed_model(d, ModelSpec{}, true);
    FAIL() << "no error";
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("has no variance (every value is 0.5)"), std::string::npos)
        << e.what();
  }
}

TEST(MixedModel, EmptyConditionByIterationCellIsInvalidData) {
  LongData d = balanced(2, 3, 3, 8);
  LongData e;
  for (std::size_t i = 0; i < d.y.size(); ++i) {
    if (d.group[i] == "c1" && d.time[i] == 2) continue;
    e.participant.push_back(d.participant[i]);
    e.group.push_back(d.group[i]);
    e.time.push_back(d.time[i]);
    e.y.push_back(d.y[i]);
  }
  try {
    feint::models::fit_mixed_model(e, ModelSpec{}, true);
    FAIL() << "no error";
  } catch (const feint::InvalidData& ex) {
    EXPECT_NE(std::string(ex.what()).find("no observation of condition 'c1' at iteration 2"),
              std::string::npos)
        << ex.what();
  }
}

TEST(MixedModel, RandomSlopeNeedsALinearTrend) {
  ModelSpec spec;
  spec.random_slope = true;
  EXPECT_THROW(feint::models::fit_mixed_model(balanced(2, 3, 3, 1), spec, true), feint::UsageError);
}

TEST(MixedModel, OneConditionFitsTheIterationEffectAlone) {
  LongData d = balanced(1, 15, 4, 10);
  const auto fit = feint::models::fit_mixed_model(d, ModelSpec{}, true);
  ASSERT_EQ(fit.anova.size(), 1u);
  EXPECT_EQ(fit.anova[0].term, "iteration");
  // One-way repeated measures: F = MS_time / MS_error, df (b-1), (b-1)(n-1).
  const int n = 15, b = 4;
  double grand = 0;
  for (double v : d.y) grand += v / (n * b);
  std::vector<double> mj(b, 0), ms(n, 0);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < b; ++j) {
      mj[j] += d.y[static_cast<std::size_t>(k * b + j)] / n;
      ms[k] += d.y[static_cast<std::size_t>(k * b + j)] / b;
    }
  double ss_b = 0, ss_s = 0, ss_t = 0;
  for (double m : mj) ss_b += n * (m - grand) * (m - grand);
  for (double m : ms) ss_s += b * (m - grand) * (m - grand);
  for (double v : d.y) ss_t += (v - grand) * (v - grand);
  const double f = (ss_b / (b - 1)) / ((ss_t - ss_b - ss_s) / ((b - 1) * (n - 1)));
  EXPECT_NEAR(fit.anova[0].f / f, 1.0, 1e-7);
  EXPECT_NEAR(fit.anova[0].den_df, (b - 1) * (n - 1), 1e-5);
}

TEST(Exposure, CountsEarlierTrialsOfTheSameStrategyPerParticipant) {
  const std::vector<std::string> p = {"B", "A", "A", "A", "A", "B"};
  const std::vector<double> it = {2, 3, 1, 2, 4, 1};
  const std::vector<std::string> s = {"x", "x", "x", "y", "x", "x"};
  const std::vector<double> e = feint::models::exposure_counts(p, it, s);
  // A: it1 x (0), it2 y (0), it3 x (1), it4 x (2); B: it1 x (0), it2 x (1).
  EXPECT_EQ(e, (std::vector<double>{1, 1, 0, 0, 2, 0}));
}

TEST(Exposure, TwoTrialsOfAParticipantAtOneIterationAreADataErrorThatSaysWhy) {
  // A participant in two conditions (a within-participants design): iteration 1 twice.
  const std::vector<std::string> p = {"A", "A", "A"};
  const std::vector<double> it = {1, 2, 1};
  const std::vector<std::string> s = {"x", "y", "x"};
  try {
    (void)feint::models::exposure_counts(p, it, s);
    FAIL() << "no error";
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("participant A has two trials at iteration 1 (a participant in more than "
                                         "one condition?)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace

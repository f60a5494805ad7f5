// Behaviour of the repeated-measures design and the mixed ANOVA beyond the R goldens: invariants
// and the precise errors of bad input (formats.md style, InvalidData = exit 65).
#include <gtest/gtest.h>

#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/models/mixed_anova.hpp"

namespace feint::models {
namespace {

std::vector<Observation> grid(std::size_t n_per_group, std::size_t k, std::size_t groups = 2) {
  std::vector<Observation> obs;
  std::uint64_t line = 1;
  for (std::size_t g = 0; g < groups; ++g) {
    for (std::size_t i = 0; i < n_per_group; ++i) {
      for (std::size_t j = 1; j <= k; ++j) {
        const double v = 0.5 + 0.01 * static_cast<double>((i * 7 + j * 3 + g * 5) % 11) +
                         0.02 * static_cast<double>(g * j);
        obs.push_back({"P" + std::to_string(g) + "_" + std::to_string(i),
                       g == 0 ? "adaptive" : "random", static_cast<long long>(j), v, ++line});
      }
    }
  }
  return obs;
}

std::string error_of(const std::vector<Observation>& obs) {
  try {
    make_wide_design(obs, "error", "scores.csv");
  } catch (const InvalidData& e) {
    return e.what();
  }
  return "";
}

TEST(WideDesign, ParticipantInTwoConditionsIsAnErrorNamingBothLines) {
  auto obs = grid(3, 4);
  obs[5].condition = "random";  // P0_1, iteration 2
  EXPECT_EQ(error_of(obs),
            "scores.csv:7: participant 'P0_1' is in condition 'random' but line 6 put it in "
            "'adaptive'; the mixed ANOVA needs each participant in exactly one condition "
            "(condition is between participants)");
}

TEST(WideDesign, IterationMissingForEverybodyIsAnError) {
  auto obs = grid(3, 4);
  for (auto& o : obs) {
    if (o.iteration == 3) o.value.reset();
  }
  EXPECT_EQ(error_of(obs),
            "scores.csv: metric 'error': iteration 3 has no value for any participant; drop the "
            "iteration or fill in its values");
}

TEST(WideDesign, MetricWithoutVarianceIsAnError) {
  auto obs = grid(3, 4);
  for (auto& o : obs) o.value = 0.25;
  EXPECT_EQ(error_of(obs),
            "scores.csv: metric 'error' has no variance: every value of the 6 complete "
            "participants is 0.25; an ANOVA of a constant is undefined");
}

TEST(WideDesign, SingleIterationIsAnError) {
  auto obs = grid(3, 1);
  EXPECT_NE(error_of(obs).find("only one iteration (1)"), std::string::npos);
}

TEST(WideDesign, IncompleteParticipantsAreExcludedAndNamedInFileOrder) {
  auto obs = grid(4, 3);
  obs[4].value.reset();         // P0_1 iteration 2: empty cell
  obs.erase(obs.begin() + 20);  // P1_2 iteration 3: row absent
  const WideDesign d = make_wide_design(obs, "error", "scores.csv");
  EXPECT_EQ(d.excluded, (std::vector<std::string>{"P0_1", "P1_2"}));
  EXPECT_EQ(d.n(), 6u);
  EXPECT_EQ(d.group_sizes(), (std::vector<std::size_t>{3, 3}));
}

TEST(MixedAnova, TwoIterationsInteractionFIsTheSquaredPooledTOfTheDifferences) {
  // With k = 2 the condition x iteration F is the squared pooled two-sample t of the differences.
  const WideDesign d = make_wide_design(grid(5, 2), "error", "s");
  const MixedAnova a = mixed_anova(d);
  std::vector<double> diff[2];
  for (std::size_t i = 0; i < d.n(); ++i) diff[d.group[i]].push_back(d.at(i, 1) - d.at(i, 0));
  auto mean = [](const std::vector<double>& x) {
    double s = 0;
    for (double v : x) s += v;
    return s / static_cast<double>(x.size());
  };
  auto ss = [&](const std::vector<double>& x) {
    double m = mean(x), s = 0;
    for (double v : x) s += (v - m) * (v - m);
    return s;
  };
  const double sp2 = (ss(diff[0]) + ss(diff[1])) / 8.0;
  const double t = (mean(diff[0]) - mean(diff[1])) / std::sqrt(sp2 * (1.0 / 5 + 1.0 / 5));
  ASSERT_EQ(a.effects.size(), 3u);
  EXPECT_NEAR(a.effects[2].f, t * t, 1e-10 * t * t);
  EXPECT_TRUE(a.sphericity.empty());
  EXPECT_FALSE(a.effects[1].gg_eps.has_value());
  EXPECT_EQ(a.effects[1].report_num_df, 1.0);  // no correction with one numerator df
}

TEST(MixedAnova, EpsilonsLieInTheirBoundsAndCorrectedPIsNotSmaller) {
  const MixedAnova a = mixed_anova(make_wide_design(grid(8, 6), "error", "s"));
  for (const auto& e : a.effects) {
    if (!e.within) continue;
    ASSERT_TRUE(e.gg_eps.has_value());
    EXPECT_GE(*e.gg_eps, 1.0 / 5 - 1e-12);
    EXPECT_LE(*e.gg_eps, 1.0 + 1e-12);
    EXPECT_GE(*e.hf_eps, *e.gg_eps);
    EXPECT_GE(e.report_p, e.p_value - 1e-15);
    EXPECT_NEAR(e.report_den_df, *e.gg_eps * e.den_df, 1e-12);
  }
}

TEST(MixedAnova, OneConditionGivesTheOneWayRepeatedMeasuresAnova) {
  const auto obs = grid(7, 4, 1);
  const MixedAnova a = mixed_anova(make_wide_design(obs, "error", "s"));
  ASSERT_EQ(a.effects.size(), 1u);
  EXPECT_EQ(a.effects[0].effect, "iteration");
  EXPECT_EQ(a.effects[0].num_df, 3.0);
  EXPECT_EQ(a.effects[0].den_df, 18.0);
  EXPECT_TRUE(a.one_way());
  // The closed form of the balanced one-way repeated-measures ANOVA, from the observations
  // themselves (n = 7 participants, k = 4 iterations): SS_iteration = n sum_j (mean_j - mean)^2,
  // SS_participant = k sum_i (mean_i - mean)^2, SS_error = SS_total - both;
  // F = (SS_iteration / (k - 1)) / (SS_error / ((n - 1)(k - 1))), p = P(F(3, 18) > F).
  const double n = 7, k = 4;
  double y[7][4] = {};
  for (const auto& o : obs) y[std::stoi(o.participant.substr(3))][o.iteration - 1] = *o.value;
  double grand = 0, row[7] = {}, col[4] = {};
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 4; ++j) {
      grand += y[i][j] / (n * k);
      row[i] += y[i][j] / k;
      col[j] += y[i][j] / n;
    }
  double ss_total = 0, ss_iteration = 0, ss_participant = 0;
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 4; ++j) ss_total += (y[i][j] - grand) * (y[i][j] - grand);
  for (int j = 0; j < 4; ++j) ss_iteration += n * (col[j] - grand) * (col[j] - grand);
  for (int i = 0; i < 7; ++i) ss_participant += k * (row[i] - grand) * (row[i] - grand);
  const double ss_error = ss_total - ss_iteration - ss_participant;
  const double f = (ss_iteration / 3) / (ss_error / 18);
  ASSERT_GT(f, 0.0);
  EXPECT_NEAR(a.effects[0].ss, ss_iteration, 1e-12);
  EXPECT_NEAR(a.effects[0].error_ss, ss_error, 1e-12);
  EXPECT_NEAR(a.effects[0].f, f, 1e-10 * f);
  const double p = boost::math::cdf(boost::math::complement(boost::math::fisher_f(3, 18), f));
  EXPECT_NEAR(a.effects[0].p_value, p, 1e-10 * p);
}

TEST(MixedAnova, TooFewParticipantsForTheCorrectionsSaysWhy) {
  const MixedAnova a = mixed_anova(make_wide_design(grid(3, 8), "error", "s"));
  EXPECT_NE(a.sphericity_note.find("singular"), std::string::npos);
  for (const auto& e : a.effects) {
    if (!e.within) continue;
    EXPECT_FALSE(e.gg_eps.has_value());
    EXPECT_NE(e.correction_note.find("not computable"), std::string::npos);
    EXPECT_EQ(e.report_p, e.p_value);
  }
}

TEST(MixedAnova, NoErrorDfIsAnError) {
  auto obs = grid(1, 3);
  EXPECT_THROW(mixed_anova(make_wide_design(obs, "error", "s")), InvalidData);
}

TEST(SphericityCorrection, ParsesAfexNamesCaseInsensitively) {
  EXPECT_EQ(parse_sphericity_correction("gg"), SphericityCorrection::GG);
  EXPECT_EQ(parse_sphericity_correction("HF"), SphericityCorrection::HF);
  EXPECT_EQ(parse_sphericity_correction("none"), SphericityCorrection::none);
  EXPECT_THROW(parse_sphericity_correction("lb"), UsageError);
}

}  // namespace
}  // namespace feint::models

namespace feint::models {
namespace {

// Every participant of one condition excluded (a missing value each). afex stops; so
// does feint, naming the condition and the way out, and the one-way analysis of the rest runs
// only when asked for.
TEST(WideDesign, ConditionWithEveryParticipantExcludedStops) {
  auto obs = grid(3, 4);
  for (auto& o : obs)
    if (o.condition == "random" && o.iteration == (o.participant == "P1_1" ? 3 : 1))
      o.value.reset();
  const std::string e = error_of(obs);
  EXPECT_NE(e.find("scores.csv: metric 'error': every participant of condition 'random' (P1_0, "
                   "P1_1, P1_2) lacks a value for some iteration"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("--drop-empty-conditions"), std::string::npos) << e;
  EXPECT_NE(e.find("feint model"), std::string::npos) << e;

  const WideDesign d = make_wide_design(obs, "error", "scores.csv", true);
  EXPECT_EQ(d.dropped_conditions, (std::vector<std::string>{"random"}));
  EXPECT_EQ(d.conditions, (std::vector<std::string>{"adaptive"}));
  const MixedAnova a = mixed_anova(d);
  EXPECT_TRUE(a.one_way());
  EXPECT_EQ(a.dropped_conditions, (std::vector<std::string>{"random"}));
  // The one-way analysis of the remaining condition: the same as its data alone.
  std::vector<Observation> only;
  for (const auto& o : obs)
    if (o.condition == "adaptive") only.push_back(o);
  const MixedAnova b = mixed_anova(make_wide_design(only, "error", "scores.csv"));
  ASSERT_EQ(a.effects.size(), b.effects.size());
  EXPECT_DOUBLE_EQ(a.effects[0].f, b.effects[0].f);
}

}  // namespace
}  // namespace feint::models

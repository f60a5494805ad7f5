// Relabelling p-values of the models' condition tests for the designs beyond two conditions
// between participants (models::relabel_condition_tests with options.within, or three
// conditions): the observed statistics are fit_mixed_model's own, the p-values equal a brute-force
// refit with fit_mixed_model of every labelling (swaps within participants; permutations of
// whole participants keeping the group sizes), ties reach, and on null studies whose trials are
// correlated in time they hold their level.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/models/mixed_model.hpp"
#include "feint/models/model_relabelling.hpp"
#include "mixed_model_normal.hpp"

namespace {

using feint::models::LongData;
using feint::models::ModelSpec;
using feint::models::relabel_condition_tests;
using feint::models::RelabellingOptions;
using feint::models::TimeScale;
using feint::test::Normal;

struct Study {
  int people = 4, conditions = 2, iterations = 3;
  bool within = true;          // else `people` per condition, between participants
  double participant_sd = 0.3, noise_sd = 0.5;
  double ar = 0.0;             // AR(1) correlation of a participant's successive trials (all blocks)
  double planted_shift = 0.0;  // extra level in condition "b"
  double missing = 0.0;        // share of trials left out
};

const std::vector<std::string> kLevels = {"a", "b", "c"};

std::vector<std::string> levels_of(const Study& s) {
  return {kLevels.begin(), kLevels.begin() + s.conditions};
}

// Within: each participant does every condition's block of `iterations` trials, in a rotated
// order, its trials one AR(1) series over the blocks. Between: `people` per condition.
LongData simulate(const Study& s, std::uint64_t seed) {
  Normal rnorm{seed};
  LongData d;
  const int persons = s.within ? s.people : s.people * s.conditions;
  for (int p = 0; p < persons; ++p) {
    const double u = s.participant_sd * rnorm();
    double e = s.noise_sd * rnorm();
    for (int b = 0; b < (s.within ? s.conditions : 1); ++b) {
      const int g = s.within ? (b + p) % s.conditions : p % s.conditions;
      for (int j = 1; j <= s.iterations; ++j) {
        e = s.ar * e + std::sqrt(1 - s.ar * s.ar) * s.noise_sd * rnorm();
        if (s.missing > 0 && rnorm.uniform() < s.missing) continue;
        d.participant.push_back("P" + std::to_string(p));
        d.group.push_back(kLevels[static_cast<std::size_t>(g)]);
        d.time.push_back(j);
        d.y.push_back(2.0 + 0.1 * j + u + e + (g == 1 ? s.planted_shift : 0.0));
      }
    }
  }
  return d;
}

// fit_mixed_model's statistics: interaction F, condition F, then each slope difference's t.
std::vector<double> fitted(const LongData& d, const std::vector<std::string>& levels, bool within) {
  ModelSpec spec;
  spec.group_levels = levels;
  spec.time_scale = TimeScale::factor;
  const auto factor = feint::models::fit_mixed_model(d, spec, !within);
  std::vector<double> s(2 + levels.size() - 1);
  for (const auto& t : factor.anova) {
    if (t.term == "condition:iteration") s[0] = t.f;
    if (t.term == "condition") s[1] = t.f;
  }
  spec.time_scale = TimeScale::linear;
  const auto trend = feint::models::fit_mixed_model(d, spec, !within);
  for (std::size_t k = 1; k < levels.size(); ++k) {
    const auto it = std::find(trend.coef_names.begin(), trend.coef_names.end(), "condition" + levels[k] + ":iteration");
    EXPECT_NE(it, trend.coef_names.end());
    Eigen::VectorXd L = Eigen::VectorXd::Zero(trend.beta.size());
    L(it - trend.coef_names.begin()) = 1;
    s[1 + k] = *feint::models::contrast(trend, L).test.statistic;
  }
  return s;
}

void expect_fits_own(const Study& s, std::uint64_t seed) {
  SCOPED_TRACE(::testing::Message() << "within " << s.within << ", " << s.conditions << " conditions, missing "
                                    << s.missing << ", seed " << seed);
  const LongData d = simulate(s, seed);
  const auto levels = levels_of(s);
  const auto f = fitted(d, levels, s.within);
  RelabellingOptions o;
  o.permutations = 1;
  o.within = s.within;
  const auto r = relabel_condition_tests(d, levels, o);
  ASSERT_TRUE(r.interaction_f && r.condition_f);
  ASSERT_EQ(r.slope_differences_t.size(), levels.size() - 1);
  EXPECT_NEAR(*r.interaction_f, f[0], 1e-6 * std::max(1.0, f[0]));
  EXPECT_NEAR(*r.condition_f, f[1], 1e-6 * std::max(1.0, f[1]));
  for (std::size_t k = 0; k + 1 < levels.size(); ++k) {
    ASSERT_TRUE(r.slope_differences_t[k]);
    EXPECT_NEAR(*r.slope_differences_t[k], f[2 + k], 1e-6 * std::max(1.0, std::fabs(f[2 + k])));
  }
  EXPECT_EQ(r.slope_difference_t, r.slope_differences_t[0]);
}

TEST(ModelRelabellingDesigns, ObservedStatisticsAreTheFitsOwnFAndT) {
  for (const bool within : {true, false})
    for (const int conditions : {2, 3})
      for (const double missing : {0.0, 0.15}) {
        if (!within && conditions == 2) continue;  // the fast path's own tests
        expect_fits_own({.people = 6, .conditions = conditions, .iterations = 4, .within = within,
                         .missing = missing},
                        7 + static_cast<std::uint64_t>(conditions));
      }
}

// Every labelling refitted by fit_mixed_model: `relabel(d, b)` gives labelling b's data. A
// labelling the models refuse (it empties a condition x iteration cell) reaches every statistic;
// the last entry counts them.
template <class Relabel>
std::vector<int> brute_force(const LongData& d, const std::vector<std::string>& levels, bool within, int labellings,
                             const Relabel& relabel) {
  const auto obs = fitted(d, levels, within);
  std::vector<int> reach(obs.size() + 1, 0);
  for (int b = 0; b < labellings; ++b) {
    try {
      const auto s = fitted(relabel(d, b), levels, within);
      for (std::size_t k = 0; k < s.size(); ++k) reach[k] += std::fabs(s[k]) >= std::fabs(obs[k]) * (1 - 1e-9);
    } catch (const feint::InvalidData&) {
      for (auto& r : reach) ++r;
    }
  }
  return reach;
}

void expect_p(const feint::models::RelabelledConditionTests& r, std::vector<int> reach, int total) {
  EXPECT_TRUE(r.exact);
  EXPECT_EQ(r.labellings, static_cast<std::uint64_t>(total));
  EXPECT_EQ(r.not_computable, static_cast<std::uint64_t>(reach.back()));
  reach.pop_back();
  EXPECT_DOUBLE_EQ(*r.p_interaction, reach[0] / double(total));
  EXPECT_DOUBLE_EQ(*r.p_condition, reach[1] / double(total));
  for (std::size_t k = 2; k < reach.size(); ++k) EXPECT_DOUBLE_EQ(*r.p_slope_differences[k - 2], reach[k] / double(total));
  EXPECT_EQ(r.p_slope_difference, r.p_slope_differences[0]);
}

// Within, two conditions: the 2^5 swaps (participant p swapped when bit p of b is set).
TEST(ModelRelabellingDesigns, WithinTwoConditionsEqualsABruteForceRefitOfEverySwap) {
  for (const std::uint64_t seed : {21u, 22u, 23u}) {
    SCOPED_TRACE(seed);
    const Study s{.people = 5, .conditions = 2, .iterations = 3, .missing = seed == 23 ? 0.1 : 0.0};
    const LongData d = simulate(s, seed);
    const auto reach = brute_force(d, {"a", "b"}, true, 32, [](LongData e, int b) {
      for (std::size_t r = 0; r < e.y.size(); ++r)
        if (b >> std::stoi(e.participant[r].substr(1)) & 1) e.group[r] = e.group[r] == "a" ? "b" : "a";
      return e;
    });
    RelabellingOptions o;
    o.within = true;
    expect_p(relabel_condition_tests(d, {"a", "b"}, o), reach, 32);
  }
}

// Within, three conditions, two participants: (3!)^2 = 36 labellings, each participant's three
// blocks permuted among its own three conditions.
TEST(ModelRelabellingDesigns, WithinThreeConditionsEqualsABruteForceRefitOfEveryPermutation) {
  const Study s{.people = 2, .conditions = 3, .iterations = 3};
  const LongData d = simulate(s, 31);
  std::vector<std::vector<int>> perms;
  std::vector<int> p = {0, 1, 2};
  do perms.push_back(p);
  while (std::next_permutation(p.begin(), p.end()));
  const auto reach = brute_force(d, {"a", "b", "c"}, true, 36, [&](LongData e, int b) {
    for (std::size_t r = 0; r < e.y.size(); ++r) {
      const auto& to = perms[static_cast<std::size_t>(e.participant[r] == "P0" ? b % 6 : b / 6)];
      e.group[r] = kLevels[static_cast<std::size_t>(to[static_cast<std::size_t>(e.group[r][0] - 'a')])];
    }
    return e;
  });
  RelabellingOptions o;
  o.within = true;
  expect_p(relabel_condition_tests(d, {"a", "b", "c"}, o), reach, 36);
}

// Between, three conditions of two participants: 6! / (2! 2! 2!) = 90 labellings.
TEST(ModelRelabellingDesigns, BetweenThreeConditionsEqualsABruteForceRefitOfEveryLabelling) {
  for (const std::uint64_t seed : {41u, 42u}) {
    SCOPED_TRACE(seed);
    const Study s{.people = 2, .conditions = 3, .iterations = 3, .within = false, .missing = seed == 42 ? 0.1 : 0.0};
    const LongData d = simulate(s, seed);
    std::vector<std::vector<int>> labels;
    std::vector<int> g = {0, 0, 1, 1, 2, 2};
    do labels.push_back(g);
    while (std::next_permutation(g.begin(), g.end()));
    ASSERT_EQ(labels.size(), 90u);
    const auto reach = brute_force(d, {"a", "b", "c"}, false, 90, [&](LongData e, int b) {
      for (std::size_t r = 0; r < e.y.size(); ++r)
        e.group[r] = kLevels[static_cast<std::size_t>(labels[static_cast<std::size_t>(b)][std::stoul(e.participant[r].substr(1))])];
      return e;
    });
    expect_p(relabel_condition_tests(d, {"a", "b", "c"}), reach, 90);
  }
}

// A within participant's conditions are swapped, never mixed: with a participant's two blocks
// equal trial by trial (condition b = condition a + a constant that is the same for everyone),
// every swap leaves the condition x iteration interaction at its observed value (0 up to
// rounding): p = 1, every labelling a tie. A relabelling that moved single trials would give
// interactions above it.
TEST(ModelRelabellingDesigns, WithinSwapsKeepABlocksTrialsTogetherAndTiesReach) {
  LongData d = simulate({.people = 6, .conditions = 2, .iterations = 4}, 51);
  std::map<std::pair<std::string, double>, double> a;
  for (std::size_t r = 0; r < d.y.size(); ++r)
    if (d.group[r] == "a") a[{d.participant[r], d.time[r]}] = d.y[r];
  for (std::size_t r = 0; r < d.y.size(); ++r)
    if (d.group[r] == "b") d.y[r] = a[{d.participant[r], d.time[r]}] + 0.7;
  RelabellingOptions o;
  o.within = true;
  const auto r = relabel_condition_tests(d, {"a", "b"}, o);
  ASSERT_TRUE(r.exact);
  EXPECT_EQ(r.labellings, 64u);
  EXPECT_DOUBLE_EQ(*r.p_interaction, 1.0);
  EXPECT_DOUBLE_EQ(*r.p_slope_difference, 1.0);
  // The condition F: only the all-kept and all-swapped labellings give the full shift.
  EXPECT_DOUBLE_EQ(*r.p_condition, 2.0 / 64);
}

// Sampled (20 participants: 2^20 swaps) with the seed: the same p-values on a rerun, the p-values
// within Monte Carlo error of a large draw, and the sequential stopping as between.
TEST(ModelRelabellingDesigns, SampledSwapsRepeatWithTheirSeedAndAgreeWithALargeDraw) {
  const LongData d = simulate({.people = 20, .conditions = 2, .iterations = 4, .planted_shift = 0.15}, 61);
  RelabellingOptions o;
  o.within = true;
  o.permutations = 499;
  o.exceedances = 0;
  const auto r1 = relabel_condition_tests(d, {"a", "b"}, o);
  const auto r2 = relabel_condition_tests(d, {"a", "b"}, o);
  EXPECT_FALSE(r1.exact);
  EXPECT_EQ(r1.labellings, 500u);
  EXPECT_EQ(r1.p_condition, r2.p_condition);
  EXPECT_EQ(r1.p_interaction, r2.p_interaction);
  o.permutations = 3999;
  o.seed = 7;
  const auto big = relabel_condition_tests(d, {"a", "b"}, o);
  for (const auto& [p, q] : {std::pair{r1.p_condition, big.p_condition}, {r1.p_interaction, big.p_interaction},
                             {r1.p_slope_difference, big.p_slope_difference}}) {
    const double se = std::sqrt(*q * (1 - *q) / 500) + 1e-3;
    EXPECT_NEAR(*p, *q, 4 * se);
  }
  o.exceedances = 10;
  o.permutations = 9999;
  const auto seq = relabel_condition_tests(d, {"a", "b"}, o);
  if (*seq.p_interaction > 0.05) {
    EXPECT_TRUE(seq.stopped_interaction);
    EXPECT_DOUBLE_EQ(*seq.p_interaction, 10.0 / static_cast<double>(seq.labellings_interaction - 1));
  }
}

// Null studies whose trials are AR(1)-correlated over each participant's whole session (0.6): the
// swaps keep each participant's series, so every test's relabelling p-value keeps its level.
TEST(ModelRelabellingDesigns, HoldsItsLevelOnCorrelatedNullStudies) {
  RelabellingOptions o;
  o.within = true;
  o.permutations = 199;
  o.exceedances = 10;
  int studies = 0;
  std::vector<int> rejected(3, 0), rejected3(4, 0);
  for (std::uint64_t seed = 1; seed <= 150; ++seed) {
    const auto r = relabel_condition_tests(simulate({.people = 10, .conditions = 2, .iterations = 5, .ar = 0.6}, 1000 + seed),
                                           {"a", "b"}, o);
    rejected[0] += *r.p_interaction <= 0.05;
    rejected[1] += *r.p_condition <= 0.05;
    rejected[2] += *r.p_slope_difference <= 0.05;
    ++studies;
  }
  RelabellingOptions b;
  b.permutations = 199;
  b.exceedances = 10;
  for (std::uint64_t seed = 1; seed <= 100; ++seed) {
    const auto r = relabel_condition_tests(
        simulate({.people = 4, .conditions = 3, .iterations = 5, .within = false, .ar = 0.6}, 2000 + seed),
        {"a", "b", "c"}, b);
    rejected3[0] += *r.p_interaction <= 0.05;
    rejected3[1] += *r.p_condition <= 0.05;
    rejected3[2] += *r.p_slope_differences[0] <= 0.05;
    rejected3[3] += *r.p_slope_differences[1] <= 0.05;
  }
  std::printf("null within (150, AR 0.6): p <= .05 in %d / %d / %d; between, 3 conditions (100): %d / %d / %d / %d\n",
              rejected[0], rejected[1], rejected[2], rejected3[0], rejected3[1], rejected3[2], rejected3[3]);
  // Binomial(150, 0.05): 7.5 expected, P(X >= 16) < 0.005; Binomial(100, 0.05): P(X >= 12) < 0.005.
  for (const int k : rejected) EXPECT_LE(k, 15) << "of " << studies;
  for (const int k : rejected3) EXPECT_LE(k, 11);
  // ... and not conservative to nothing: the counts over all tests are near their expectation.
  EXPECT_GE(rejected[0] + rejected[1] + rejected[2], 8);
  EXPECT_GE(rejected3[0] + rejected3[1] + rejected3[2] + rejected3[3], 7);
}

TEST(ModelRelabellingDesigns, FindsAPlantedShiftWithin) {
  RelabellingOptions o;
  o.within = true;
  o.permutations = 199;
  int found = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed)
    found += *relabel_condition_tests(simulate({.people = 10, .conditions = 2, .iterations = 5, .participant_sd = 1.0,
                                                .planted_shift = 0.8},
                                               3000 + seed),
                                      {"a", "b"}, o)
                  .p_condition < 0.05;
  EXPECT_GE(found, 9);
}

TEST(ModelRelabellingDesigns, RejectsWhatItCannotRelabel) {
  const LongData d = simulate({.people = 3, .conditions = 3, .iterations = 3, .within = false}, 71);
  EXPECT_THROW(relabel_condition_tests(d, {"a", "b", "x"}), feint::InvalidData);  // 'c' not named
  EXPECT_THROW(relabel_condition_tests(d, {"a", "b", "c", "d"}), feint::UsageError);  // 'd' empty
  const LongData w = simulate({.people = 3, .conditions = 3, .iterations = 3}, 72);
  EXPECT_THROW(relabel_condition_tests(w, {"a", "b", "c"}), feint::InvalidData);  // within, not declared
}

}  // namespace

// Relabelling p-values of the random-intercept models' condition tests
// (models::relabel_condition_tests): the observed statistics are the fits' own, the p-values equal
// a brute-force refit of every labelling with fit_mixed_model, and on a null whose trials are
// correlated in time (where the model's F is too liberal) they hold their level.
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
#include "golden_csv.hpp"
#include "mixed_model_normal.hpp"

namespace {

using feint::models::LongData;
using feint::models::ModelSpec;
using feint::models::relabel_condition_tests;
using feint::models::RelabellingOptions;
using feint::models::TimeScale;
using feint::test::Normal;

struct Design {
  int per_group = 6, iterations = 5;
  double participant_sd = 0.3, noise_sd = 0.5;
  double ar = 0.0;              // AR(1) correlation of a participant's successive trials
  double planted_slope = 0.0;   // extra slope per iteration in condition "b"
  double planted_shift = 0.0;   // extra level in condition "b"
  double missing = 0.0;         // share of trials left out
  double dropout = 0.0;         // share of participants who stop after a random iteration
};

LongData simulate(const Design& s, std::uint64_t seed) {
  Normal rnorm{seed};
  LongData d;
  for (int g = 0; g < 2; ++g) {
    for (int k = 0; k < s.per_group; ++k) {
      const double u = s.participant_sd * rnorm();
      double e = s.noise_sd * rnorm();
      int last = s.iterations;  // a dropout's last iteration: 2 .. iterations - 1
      if (s.dropout > 0 && rnorm.uniform() < s.dropout)
        last = 2 + static_cast<int>(rnorm.uniform() * (s.iterations - 2));
      for (int j = 1; j <= last; ++j) {
        if (j > 1) e = s.ar * e + std::sqrt(1 - s.ar * s.ar) * s.noise_sd * rnorm();
        if (s.missing > 0 && rnorm.uniform() < s.missing) continue;
        d.participant.push_back((g ? "B" : "A") + std::to_string(k));
        d.group.push_back(g ? "b" : "a");
        d.time.push_back(j);
        d.y.push_back(2.0 + 0.1 * j + u + e + g * (s.planted_shift + s.planted_slope * j));
      }
    }
  }
  return d;
}

struct FitStatistics {
  double interaction_f, condition_f, slope_t;
  double p_interaction, p_condition, p_slope;
};

FitStatistics fitted(const LongData& d) {
  ModelSpec spec;
  spec.response = "y";
  spec.time_scale = TimeScale::factor;
  spec.group_levels = {"a", "b"};
  const auto factor = feint::models::fit_mixed_model(d, spec, true);
  FitStatistics s{};
  for (const auto& t : factor.anova) {
    if (t.term == "condition:iteration") {
      s.interaction_f = t.f;
      s.p_interaction = t.p;
    }
    if (t.term == "condition") {
      s.condition_f = t.f;
      s.p_condition = t.p;
    }
  }
  spec.time_scale = TimeScale::linear;
  const auto trend = feint::models::fit_mixed_model(d, spec, true);
  const auto it = std::find(trend.coef_names.begin(), trend.coef_names.end(), "conditionb:iteration");
  EXPECT_NE(it, trend.coef_names.end());
  Eigen::VectorXd L = Eigen::VectorXd::Zero(trend.beta.size());
  L(it - trend.coef_names.begin()) = 1;
  const auto c = feint::models::contrast(trend, L);
  s.slope_t = *c.test.statistic;
  s.p_slope = *c.test.p_value;
  return s;
}

void expect_same_statistics(const LongData& d, const char* what) {
  SCOPED_TRACE(what);
  const FitStatistics f = fitted(d);
  RelabellingOptions o;
  o.permutations = 1;  // the observed statistics only
  const auto r = relabel_condition_tests(d, {"a", "b"}, o);
  ASSERT_TRUE(r.interaction_f && r.condition_f && r.slope_difference_t);
  EXPECT_NEAR(*r.interaction_f, f.interaction_f, 1e-6 * std::max(1.0, f.interaction_f));
  EXPECT_NEAR(*r.condition_f, f.condition_f, 1e-6 * std::max(1.0, f.condition_f));
  EXPECT_NEAR(*r.slope_difference_t, f.slope_t, 1e-6 * std::max(1.0, std::fabs(f.slope_t)));
}

TEST(ModelRelabelling, ObservedStatisticsAreTheFitsOwnFAndT) {
  expect_same_statistics(simulate({}, 1), "balanced, complete");
  expect_same_statistics(simulate({.per_group = 10, .iterations = 20, .ar = 0.6}, 2), "2 x 10 x 20, AR(1)");
  expect_same_statistics(simulate({.per_group = 8, .iterations = 6, .missing = 0.15}, 3), "15% of trials missing");
  expect_same_statistics(simulate({.per_group = 8, .iterations = 4, .participant_sd = 0.0}, 4),
                         "no participant variance (a singular fit)");
  expect_same_statistics(simulate({.per_group = 7, .iterations = 5, .planted_slope = 0.3}, 5), "planted slope");
  expect_same_statistics(simulate({.per_group = 12, .iterations = 10, .ar = 0.6, .missing = 0.03, .dropout = 0.3}, 8),
                         "dropouts and 3% lost trials (many trial patterns and sizes)");
  auto unequal = simulate({.per_group = 9, .iterations = 4}, 6);
  // Drop 3 participants of condition b: 9 against 6.
  LongData d;
  for (std::size_t r = 0; r < unequal.y.size(); ++r) {
    if (unequal.participant[r] == "B0" || unequal.participant[r] == "B4" || unequal.participant[r] == "B7") continue;
    d.participant.push_back(unequal.participant[r]);
    d.group.push_back(unequal.group[r]);
    d.time.push_back(unequal.time[r]);
    d.y.push_back(unequal.y[r]);
  }
  expect_same_statistics(d, "9 against 6 participants");
}

// Every labelling of 3 + 3 participants (20), each refitted by fit_mixed_model: the p-values are
// the shares of labellings whose statistic reaches the observed one.
TEST(ModelRelabelling, PValuesEqualABruteForceRefitOfEveryLabelling) {
  for (const std::uint64_t seed : {11u, 12u, 13u}) {
    const LongData d = simulate({.per_group = 3, .iterations = 4, .missing = seed == 13 ? 0.1 : 0.0}, seed);
    std::vector<std::string> people;
    for (const auto& p : d.participant)
      if (std::find(people.begin(), people.end(), p) == people.end()) people.push_back(p);
    ASSERT_EQ(people.size(), 6u);
    const FitStatistics obs = fitted(d);
    int reach_int = 0, reach_cond = 0, reach_slope = 0, total = 0;
    std::vector<int> pick = {0, 0, 0, 1, 1, 1};
    do {
      LongData e = d;
      for (std::size_t r = 0; r < e.y.size(); ++r) {
        const auto i = std::find(people.begin(), people.end(), e.participant[r]) - people.begin();
        e.group[r] = pick[static_cast<std::size_t>(i)] ? "b" : "a";
      }
      const FitStatistics s = fitted(e);
      reach_int += s.interaction_f >= obs.interaction_f * (1 - 1e-9);
      reach_cond += s.condition_f >= obs.condition_f * (1 - 1e-9);
      reach_slope += std::fabs(s.slope_t) >= std::fabs(obs.slope_t) * (1 - 1e-9);
      ++total;
    } while (std::next_permutation(pick.begin(), pick.end()));
    ASSERT_EQ(total, 20);
    const auto r = relabel_condition_tests(d, {"a", "b"});
    SCOPED_TRACE(seed);
    EXPECT_TRUE(r.exact);
    EXPECT_EQ(r.labellings, 20u);
    EXPECT_EQ(r.not_computable, 0u);
    EXPECT_DOUBLE_EQ(*r.p_interaction, reach_int / 20.0);
    EXPECT_DOUBLE_EQ(*r.p_condition, reach_cond / 20.0);
    EXPECT_DOUBLE_EQ(*r.p_slope_difference, reach_slope / 20.0);
    // Every labelling and its mirror image give the same F and |t|: p is a multiple of 2/20.
    EXPECT_EQ(reach_cond % 2, 0);
  }
}

// The worked example of docs/findings.md: 3 + 3 participants x 4 iterations, every labelling
// refitted by lme4/lmerTest in tests/golden/models/relabel_golden.R.
TEST(ModelRelabelling, WorkedExampleEqualsLmerTestRefitOverEveryLabelling) {
  const std::vector<double> y = {0.52, 0.61, 0.58, 0.70, 0.45, 0.49, 0.60, 0.66, 0.58, 0.63, 0.71, 0.69,
                                 0.50, 0.47, 0.52, 0.49, 0.41, 0.48, 0.44, 0.50, 0.55, 0.51, 0.58, 0.54};
  const std::vector<std::string> people = {"A1", "A2", "A3", "R1", "R2", "R3"};
  LongData d;
  for (std::size_t r = 0; r < y.size(); ++r) {
    d.participant.push_back(people[r / 4]);
    d.group.push_back(r < 12 ? "adaptive" : "random");
    d.time.push_back(static_cast<double>(r % 4 + 1));
    d.y.push_back(y[r]);
  }
  std::map<std::string, double> golden;
  for (const auto& row : feint::test::read_csv(feint::test::kModelGoldenDir + "relabel_golden.csv"))
    if (row.size() == 2 && row[0] != "quantity") golden[row[0]] = std::stod(row[1]);
  ASSERT_EQ(golden.size(), 9u);
  const auto r = relabel_condition_tests(d, {"adaptive", "random"});
  EXPECT_TRUE(r.exact);
  EXPECT_EQ(r.labellings, 20u);
  EXPECT_NEAR(*r.interaction_f, golden["interaction_f"], 1e-6 * golden["interaction_f"]);
  EXPECT_NEAR(*r.condition_f, golden["condition_f"], 1e-6 * golden["condition_f"]);
  EXPECT_NEAR(*r.slope_difference_t, golden["slope_t"], 1e-6 * std::fabs(golden["slope_t"]));
  EXPECT_DOUBLE_EQ(*r.p_interaction, golden["p_interaction"]);
  EXPECT_DOUBLE_EQ(*r.p_condition, golden["p_condition"]);
  EXPECT_DOUBLE_EQ(*r.p_slope_difference, golden["p_slope_difference"]);
  // The point of the example: the model's t (20 residual df) says p = .0014, but 3 + 3
  // participants allow no p below 2/20: a labelling and its mirror give the same |t|.
  EXPECT_LT(golden["slope_p_model"], 0.002);
  EXPECT_DOUBLE_EQ(*r.p_slope_difference, 0.1);
}

TEST(ModelRelabelling, SampledRelabellingsAgreeWithEnumerationAndRepeatWithTheirSeed) {
  const LongData d = simulate({.per_group = 6, .iterations = 5, .ar = 0.5}, 21);  // C(12, 6) = 924
  const auto exact = relabel_condition_tests(d, {"a", "b"});
  ASSERT_TRUE(exact.exact);
  EXPECT_EQ(exact.labellings, 924u);
  RelabellingOptions o;
  o.permutations = 599;
  o.exceedances = 0;  // every test counts all 599 draws
  const auto sampled = relabel_condition_tests(d, {"a", "b"}, o);
  EXPECT_FALSE(sampled.exact);
  EXPECT_EQ(sampled.labellings, 600u);
  EXPECT_EQ(sampled.labellings_interaction, 600u);
  EXPECT_EQ(sampled.labellings_slope, 600u);
  auto within = [](double p, double q) {
    EXPECT_NEAR(p, q, 4 * std::sqrt(q * (1 - q) / 600) + 1.0 / 600);
  };
  within(*sampled.p_interaction, *exact.p_interaction);
  within(*sampled.p_condition, *exact.p_condition);
  within(*sampled.p_slope_difference, *exact.p_slope_difference);
  const auto again = relabel_condition_tests(d, {"a", "b"}, o);
  EXPECT_EQ(*again.p_interaction, *sampled.p_interaction);
  EXPECT_EQ(*again.p_slope_difference, *sampled.p_slope_difference);
  o.seed = 7;
  const auto other = relabel_condition_tests(d, {"a", "b"}, o);
  within(*other.p_condition, *exact.p_condition);
}

// Besag & Clifford's sequential p-values (RelabellingOptions::exceedances = h, n = 2000): a test
// whose fixed-n p-value is at most h / n never reaches h and is that p-value, from the same draws;
// one above it stops once h draws reach its statistic, p = h / l after l draws, near the fixed-n p.
TEST(ModelRelabelling, SequentialPValuesStopFarFromAlphaAndEqualTheFixedNOnesBelowHOverN) {
  RelabellingOptions fixed, sequential;
  fixed.permutations = sequential.permutations = 1999;
  fixed.exceedances = 0;
  sequential.exceedances = 20;
  int stopped = 0, full = 0;
  for (const std::uint64_t seed : {301u, 302u, 303u}) {
    SCOPED_TRACE(seed);
    // 301: a planted slope (its p about 1 / 2000); 302, 303: nulls.
    const LongData d = simulate({.per_group = 10, .iterations = 8, .ar = 0.5, .planted_slope = seed == 301 ? 0.3 : 0.0}, seed);
    const auto f = relabel_condition_tests(d, {"a", "b"}, fixed);
    const auto s = relabel_condition_tests(d, {"a", "b"}, sequential);
    EXPECT_EQ(f.labellings, 2000u);
    EXPECT_EQ(*s.interaction_f, *f.interaction_f);
    auto check = [&](double pf, double ps, std::uint64_t n) {
      const double reached = std::round(pf * 2000) - 1;  // draws reaching it in the fixed-n run
      if (reached < 20) {
        EXPECT_EQ(ps, pf);
        EXPECT_EQ(n, 2000u);
        ++full;
      } else {
        EXPECT_DOUBLE_EQ(ps, 20.0 / static_cast<double>(n - 1));
        EXPECT_NEAR(ps, pf, 5 * pf / std::sqrt(20.0));
        stopped += n < 2000;
      }
    };
    check(*f.p_interaction, *s.p_interaction, s.labellings_interaction);
    check(*f.p_condition, *s.p_condition, s.labellings_condition);
    check(*f.p_slope_difference, *s.p_slope_difference, s.labellings_slope);
    EXPECT_EQ(s.labellings, std::max({s.labellings_interaction, s.labellings_condition, s.labellings_slope}));
  }
  EXPECT_GE(full, 1) << "the planted slope's p-value was expected below h / n";
  EXPECT_GE(stopped, 4) << "the nulls' p-values were expected to stop early";
}

// A null whose trials are AR(1)-correlated within each participant (rho = 0.8) over 10 iterations:
// the model's interaction F (compound symmetry) rejects far too often; the relabelling p-values
// stay at the level. 300 studies of 2 x 8 participants: the bound for a test at 5% is 25 of 300
// (binomial 99.5% quantile); the model F's rate is checked to exceed it (the point of the
// exercise).
TEST(ModelRelabelling, HoldsItsLevelOnANullWithCorrelatedTrialsWhereTheModelFDoesNot) {
  int model_int = 0, relab_int = 0, relab_cond = 0, relab_slope = 0;
  RelabellingOptions o;
  o.permutations = 199;
  const int studies = 300;
  for (int s = 0; s < studies; ++s) {
    const LongData d = simulate({.per_group = 8, .iterations = 10, .participant_sd = 0.2, .ar = 0.8}, 1000 + s);
    o.seed = 500 + static_cast<std::uint64_t>(s);
    const auto r = relabel_condition_tests(d, {"a", "b"}, o);
    const FitStatistics f = fitted(d);
    model_int += f.p_interaction < 0.05;
    relab_int += *r.p_interaction < 0.05;
    relab_cond += *r.p_condition < 0.05;
    relab_slope += *r.p_slope_difference < 0.05;
  }
  EXPECT_GT(model_int, 25) << "the model F was expected to be liberal here";
  std::printf("null, AR(1) 0.8: p < .05 in %d (model F), %d / %d / %d (relabelled) of %d\n", model_int, relab_int,
              relab_cond, relab_slope, studies);
  EXPECT_LE(relab_int, 25);
  EXPECT_LE(relab_cond, 25);
  EXPECT_LE(relab_slope, 25);
  EXPECT_GE(relab_int + relab_cond + relab_slope, 3) << "a test that never rejects is not at its level";
}

TEST(ModelRelabelling, FindsAPlantedDifference) {
  RelabellingOptions o;
  o.permutations = 499;
  int slope = 0, shift = 0;
  for (int s = 0; s < 20; ++s) {
    const auto a = relabel_condition_tests(simulate({.per_group = 10, .iterations = 8, .planted_slope = 0.25}, 300 + s),
                                           {"a", "b"}, o);
    slope += *a.p_slope_difference < 0.05 && *a.p_interaction < 0.05;
    const auto b = relabel_condition_tests(
        simulate({.per_group = 10, .iterations = 8, .participant_sd = 0.2, .planted_shift = 1.0}, 400 + s), {"a", "b"}, o);
    shift += *b.p_condition < 0.05;
  }
  EXPECT_GE(slope, 18);
  EXPECT_GE(shift, 18);
}

TEST(ModelRelabelling, RejectsWhatItCannotRelabel) {
  LongData d = simulate({.per_group = 3, .iterations = 3}, 31);
  EXPECT_THROW(relabel_condition_tests(d, {"a"}), feint::UsageError);
  EXPECT_THROW(relabel_condition_tests(d, {"a", "b", "c"}), feint::UsageError);
  RelabellingOptions zero;
  zero.permutations = 0;
  EXPECT_THROW(relabel_condition_tests(d, {"a", "b"}, zero), feint::UsageError);
  EXPECT_THROW(relabel_condition_tests(d, {"a", "x"}), feint::InvalidData);  // 'b' is neither
  LongData both = d;
  both.group[0] = "b";  // A0's first trial in the other condition
  try {
    relabel_condition_tests(both, {"a", "b"});
    FAIL() << "a participant in both conditions was relabelled";
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("participant A0 has trials in both conditions"), std::string::npos) << e.what();
  }
  LongData short_y = d;
  short_y.y.pop_back();
  EXPECT_THROW(relabel_condition_tests(short_y, {"a", "b"}), feint::UsageError);
  LongData one_side;
  for (std::size_t r = 0; r < d.y.size(); ++r)
    if (d.group[r] == "a") {
      one_side.participant.push_back(d.participant[r]);
      one_side.group.push_back("a");
      one_side.time.push_back(d.time[r]);
      one_side.y.push_back(d.y[r]);
    }
  EXPECT_THROW(relabel_condition_tests(one_side, {"a", "b"}), feint::UsageError);
}

// A relabelling that empties a condition x iteration cell (only one participant has iteration 4)
// cannot give the factor model's F: it counts as reaching the observed value.
TEST(ModelRelabelling, ARelabellingThatEmptiesACellCountsAsReaching) {
  LongData d = simulate({.per_group = 3, .iterations = 3}, 41);
  // Iteration 4 for A0 and B0 only: a labelling with both in one condition empties a cell.
  for (const char* p : {"A0", "B0"}) {
    d.participant.push_back(p);
    d.group.push_back(p[0] == 'A' ? "a" : "b");
    d.time.push_back(4);
    d.y.push_back(2.5);
  }
  const auto r = relabel_condition_tests(d, {"a", "b"});
  ASSERT_TRUE(r.exact);
  // Labellings with A0 and B0 on the same side: 2 * C(4, 1) = 8 of 20.
  EXPECT_EQ(r.not_computable, 8u);
  EXPECT_GE(*r.p_interaction, 8.0 / 20);
  EXPECT_GE(*r.p_condition, 8.0 / 20);
}

// Two participants with the same values (to the last bit, or one ulp apart), one in each
// condition: the labelling that swaps them (and its mirror) gives the observed statistics up to
// rounding. Such a tie reaches the observed statistic, so each p counts at least 4 of the 70
// labellings: the 1e-9 slack of the threshold keeps a tie from being lost to the last bit (without
// it, some of these 40 studies lose it: the mutant relabel_no_rounding_slack).
TEST(ModelRelabelling, ExactTiesReachTheObservedStatistic) {
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    SCOPED_TRACE(seed);
    LongData d = simulate({.per_group = 4, .iterations = 5, .missing = 0.1}, seed);
    std::vector<double> a0;
    std::vector<double> t0;
    for (std::size_t i = 0; i < d.y.size(); ++i)
      if (d.participant[i] == "A0") {
        a0.push_back(d.y[i]);
        t0.push_back(d.time[i]);
      }
    // B0's trials become A0's, trial by trial (the same iterations, the same values).
    LongData e;
    for (std::size_t i = 0; i < d.y.size(); ++i) {
      if (d.participant[i] == "B0") continue;
      e.participant.push_back(d.participant[i]);
      e.group.push_back(d.group[i]);
      e.time.push_back(d.time[i]);
      e.y.push_back(d.y[i]);
    }
    for (std::size_t k = 0; k < a0.size(); ++k) {
      e.participant.push_back("B0");
      e.group.push_back("b");
      e.time.push_back(t0[k]);
      e.y.push_back(a0[k] * 1.0000000000000002);  // the same value, or the next double up
    }
    const auto r = relabel_condition_tests(e, {"a", "b"});
    ASSERT_TRUE(r.exact);
    ASSERT_EQ(r.labellings, 70u);
    EXPECT_GE(*r.p_condition, 4.0 / 70);
    EXPECT_GE(*r.p_interaction, 4.0 / 70);
    EXPECT_GE(*r.p_slope_difference, 4.0 / 70);
  }
}

}  // namespace

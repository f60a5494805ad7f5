// Deceptiveness measures (feint/models/deceptiveness.hpp): worked examples of docs/observer.md,
// invariants, and bad input; the observer fit's handling of bad trials.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "feint/error.hpp"
#include "feint/models/deceptiveness.hpp"
#include "feint/models/observer_fit.hpp"
#include "observer_test_paths.hpp"

using namespace feint::models;
namespace tp = feint::testpaths;

TEST(Deceptiveness, StraightPathWorkedExample) {
  // docs/observer.md, worked example: (0,0) -> (0,2) -> (2,4) at t = 0, 2, 2 + 2 sqrt 2, beta = 1.
  // On the midline p = 1/2 exactly; legibility, time deceived and the last deceptive point by hand.
  const double t2 = 2 + 2 * std::sqrt(2.0);
  const std::vector<PathSample> path{{0, 0, 0}, {2, 0, 2}, {t2, 2, 4}};
  DeceptivenessSettings s;
  s.observer = {1.0, 0.0, 0.5};
  const auto m = deceptiveness(path, GoalSide::right, s);
  // p at the end: logit = -beta [(V_R(G) - V_R(S)) - (V_L(G) - V_L(S))] = -[(0 - sqrt 20) - (4 - sqrt 20)] = 4.
  EXPECT_NEAR(m.final_belief, 1 / (1 + std::exp(-4.0)), 1e-15);
  const double T = t2;
  // Trapezoids: [0, 2] p = 1/2 both ends; [2, T] from 1/2 to p_end with f from T - 2 to 0.
  const double p2 = 1 / (1 + std::exp(-4.0));
  const double num = (0.5 * T + 0.5 * (T - 2)) / 2 * 2 + (0.5 * (T - 2) + p2 * 0) / 2 * (T - 2);
  EXPECT_NEAR(m.legibility, num / (T * T / 2), 1e-15);
  EXPECT_EQ(m.time_deceived, 0.0);          // a tie is not deceived
  EXPECT_NEAR(m.last_deceptive_point, 2 / (2 + 2 * std::sqrt(2.0)), 1e-15);  // leaves the midline at s = 2
  EXPECT_NEAR(m.cost_overhead, (2 + 2 * std::sqrt(2.0)) / std::sqrt(20.0) - 1, 1e-15);
}

TEST(Deceptiveness, OptimalPathIsNeverDeceptiveAndMirrorSymmetric) {
  const auto r = deceptiveness(tp::shape(0, 1.0), GoalSide::right, DeceptivenessSettings{});
  EXPECT_EQ(r.time_deceived, 0.0);
  EXPECT_EQ(r.last_deceptive_point, 0.0);
  EXPECT_NEAR(r.cost_overhead, 0.0, 1e-15);
  EXPECT_GT(r.legibility, 0.5);
  for (int k = 0; k < 4; ++k) {
    const auto a = deceptiveness(tp::shape(k, 1.0), GoalSide::right, DeceptivenessSettings{});
    const auto b = deceptiveness(tp::shape(k, -1.0), GoalSide::left, DeceptivenessSettings{});
    EXPECT_NEAR(a.legibility, b.legibility, 1e-12) << k;
    EXPECT_NEAR(a.time_deceived, b.time_deceived, 1e-12) << k;
    EXPECT_NEAR(a.last_deceptive_point, b.last_deceptive_point, 1e-12) << k;
    EXPECT_NEAR(a.belief_error, b.belief_error, 1e-12) << k;
    EXPECT_NEAR(a.belief_confusion, b.belief_confusion, 1e-12) << k;
  }
}

TEST(Deceptiveness, ExaggeratingIsMoreDeceptiveThanOptimal) {
  const auto opt = deceptiveness(tp::shape(0, 1.0), GoalSide::right, DeceptivenessSettings{});
  const auto exa = deceptiveness(tp::shape(1, 1.0), GoalSide::right, DeceptivenessSettings{});
  EXPECT_LT(exa.legibility, opt.legibility);
  EXPECT_GT(exa.time_deceived, 0.5);
  EXPECT_GT(exa.last_deceptive_point, 0.5);
  EXPECT_GT(exa.belief_error, opt.belief_error);
  EXPECT_GT(exa.cost_overhead, 0.5);
}

TEST(Deceptiveness, BadPathsAreRefusedWithAReason) {
  DeceptivenessSettings s;
  const std::vector<PathSample> still{{0, 1, 1}, {1, 1, 1}, {2, 1, 1}};
  try {
    deceptiveness(still, GoalSide::right, s);
    FAIL();
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("never moves"), std::string::npos) << e.what();
  }
  const std::vector<PathSample> zero{{1, 0, 0}, {1, 1, 1}};
  EXPECT_THROW(deceptiveness(zero, GoalSide::right, s), feint::InvalidData);
  const std::vector<PathSample> one{{0, 0, 0}};
  EXPECT_THROW(deceptiveness(one, GoalSide::right, s), feint::InvalidData);
  const std::vector<PathSample> loop{{0, 0, 0}, {1, 1, 1}, {2, 0, 0}};
  EXPECT_THROW(deceptiveness(loop, GoalSide::right, s), feint::InvalidData);
  s.observer.beta = -1;
  EXPECT_THROW(deceptiveness(tp::shape(0, 1.0), GoalSide::right, s), feint::UsageError);
  s.observer.beta = 1;
  s.pad_speed = 0;
  EXPECT_THROW(deceptiveness(tp::shape(0, 1.0), GoalSide::right, s), feint::UsageError);
}

TEST(ObserverFitBadInput, EachBadTrialIsNamedAndTheRestIsFitted) {
  feint::Rng rng(11);
  auto trials = tp::simulate_participant(GoalObserver{1.5, 0.3, 0.5}, 12, 0.9, 0.02, rng, "P1");
  auto more = tp::simulate_participant(GoalObserver{1.5, 0.3, 0.5}, 12, 0.9, 0.02, rng, "P2");
  // P1/sim/1: a path that never moves; P1/sim/2: zero-duration pad trace; P1/sim/3: 2 samples.
  trials[0].path = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  trials[1].times = {1.0, 1.0, 1.0};
  trials[1].pads = {0.5, 0.5, 0.5};
  trials[2].times = {0.0, 0.1};
  trials[2].pads = {0.5, 0.5};
  // P2: every trial broken -> the participant is named, P1 and the pooled fit go on.
  for (auto& t : more) t.times.resize(2), t.pads.resize(2);
  trials.insert(trials.end(), more.begin(), more.end());
  ObserverFitSettings s;
  s.learning = false;
  const auto r = fit_study(trials, s);
  auto has = [&](const std::string& label, const std::string& text) {
    for (const auto& i : r.issues)
      if (i.label == label && i.reason.find(text) != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(has("P1/sim/1", "never moves"));
  EXPECT_TRUE(has("P1/sim/2", "increase strictly"));
  EXPECT_TRUE(has("P1/sim/3", "2 sample(s); at least 3"));
  EXPECT_TRUE(has("P2/sim/5", "at least 3"));
  ASSERT_EQ(r.participants.size(), 1u);
  EXPECT_EQ(r.participants[0].unit, "P1");
  EXPECT_EQ(r.participants[0].trials, 9u);
  EXPECT_EQ(r.trials_used, 9u);
  ASSERT_EQ(r.conditions.size(), 1u);
  EXPECT_NEAR(r.participants[0].parameter("beta").estimate, 1.5, 0.3);
}

TEST(ObserverFitBadInput, BetaAtTheBoundIsFlaggedByName) {
  feint::Rng rng(5);
  // A pad that follows the path's side at once (beta far above the range).
  const auto trials = tp::simulate_participant(GoalObserver{200.0, 0.2, 0.5}, 8, 0.5, 0.01, rng, "P9");
  ObserverFitSettings s;
  s.beta_max = 5;
  const auto fit = fit_observer(trials, s, "P9");
  EXPECT_NEAR(fit.parameter("beta").estimate, 5.0, 1e-2);
  EXPECT_TRUE(fit.parameter("beta").high_at_bound);
  ASSERT_FALSE(fit.notes.empty());
  EXPECT_NE(fit.notes[0].find("P9: beta is at the upper bound 5"), std::string::npos) << fit.notes[0];
  // beta = 0: the pad ignores the path.
  const auto flat = tp::simulate_participant(GoalObserver{0.0, 0.2, 0.5}, 8, 0.5, 0.02, rng, "P8");
  const auto f0 = fit_observer(flat, ObserverFitSettings{}, "P8");
  EXPECT_LT(f0.parameter("beta").conf_low, 1e-9);
  EXPECT_TRUE(f0.parameter("beta").low_at_bound);
}

TEST(ObserverFitLearning, DetectsADecliningBeta) {
  feint::Rng rng(21);
  // Exposure grows with each earlier trial of the same strategy (4 strategies cycled): simulate
  // beta_k = 2 exp(-0.3 exposure).
  std::vector<ObservedTrial> trials;
  for (int p = 0; p < 4; ++p) {
    for (int k = 0; k < 16; ++k) {
      const double beta = 2.0 * std::exp(-0.3 * (k / 4));
      auto one = tp::simulate_participant(GoalObserver{beta, 0.3, 0.5}, 1, 0.9, 0.02, rng, "P" + std::to_string(p));
      one[0].iteration = k + 1;
      one[0].strategy = std::to_string(k % 4);
      one[0].path = tp::shape(k % 4, one[0].goal == GoalSide::right ? 1.0 : -1.0);
      const auto b = belief_trace(one[0].path, one[0].times, Goals{}, GoalObserver{beta, 0.3, 0.5});
      for (std::size_t i = 0; i < b.size(); ++i) one[0].pads[i] = b[i] + 0.02 * rng.normal();
      trials.push_back(one[0]);
    }
  }
  ObserverFitSettings s;
  const auto r = fit_study(trials, s);
  ASSERT_EQ(r.learning.size(), 1u);
  EXPECT_NEAR(r.learning[0].gamma.estimate, -0.3, 0.05);
  EXPECT_LT(r.learning[0].p_value, 1e-6);
  EXPECT_LT(r.learning[0].gamma.conf_low, -0.3);
  EXPECT_GT(r.learning[0].gamma.conf_high, -0.3);
}

TEST(Deceptiveness, BetaAtTheBoundsGivesTheLimits) {
  DeceptivenessSettings s;
  s.observer.beta = 0;  // belief = prior everywhere
  const auto m = deceptiveness(tp::shape(1, 1.0), GoalSide::right, s);
  EXPECT_DOUBLE_EQ(m.legibility, 0.5);
  EXPECT_EQ(m.time_deceived, 0.0);
  EXPECT_EQ(m.last_deceptive_point, 1.0);
  EXPECT_NEAR(m.belief_error, 0.5, 1e-15);
  EXPECT_EQ(m.belief_confusion, 0.0);
  s.observer.beta = 1e6;  // a step function of the side: finite, bounded, the jumps clamped to v
  const auto h = deceptiveness(tp::shape(1, 1.0), GoalSide::right, s);
  for (double v : {h.legibility, h.time_deceived, h.last_deceptive_point, h.belief_error, h.belief_confusion}) {
    EXPECT_TRUE(std::isfinite(v));
    EXPECT_GE(v, 0.0);
    EXPECT_LE(v, 1.0);
  }
  EXPECT_GT(h.belief_overspeed_segments, 0);
}

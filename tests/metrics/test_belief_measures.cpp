// Belief-trace measures (docs/metrics.md "Belief-trace measures"): the worked examples A-E worked by
// hand (exact fractions, to 1e-12), invariants, and the undefined cases (empty, never 0).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "feint/error.hpp"
#include "feint/metrics/trial_metrics.hpp"

using feint::metrics::ConfusionNorm;
using feint::metrics::MetricSettings;
using feint::metrics::score_trace;
using feint::metrics::TrialScore;

namespace {

const double kNone = std::nan("");

struct Expected {
  const char* name;
  std::vector<double> t, mu;
  double target;
  double signed_area, max_deviation;
  int flips;
  double time_deceived, final_belief_time;  // NaN = empty
};

std::vector<double> zero_to_ten() {
  std::vector<double> t;
  for (int i = 0; i <= 10; ++i) t.push_back(i);
  return t;
}

// docs/metrics.md, worked examples, belief dead band 0.05 (the default).
std::vector<Expected> examples_default() {
  return {
      {"A", zero_to_ten(), {0.5, 0.75, 1, 1, 1, 1, 1, 1, 1, 1, 1}, 1, 1.0 / 32, -1.0 / 8, 0, 0,
       1.0 / 5},
      {"B", zero_to_ten(), {0.5, 0.25, 0, 0, 0, 0, 0, 0.25, 0.5, 0.75, 1}, 1, 115.0 / 144, 0.5, 1,
       73.0 / 90, 41.0 / 5},
      {"C", zero_to_ten(), {0.5, 0.75, 0.5, 0.75, 0.5, 0.75, 0.5, 0.75, 0.5, 0.75, 0.5}, 0,
       91.0 / 144, 0.25, 9, 37.0 / 45, kNone},
      {"D", {0, 0.5, 2, 3.5, 4}, {0.5, 0.5, 0.2, 0.6, 0.6}, 0.3, 5.0 / 48, 1.0 / 10, 1, 13.0 / 96,
       kNone},
      {"E", {0, 0.3, 1, 2, 4}, {0.5, 0.6, 0.4, 0.4, 0.9}, 1, 25.0 / 54, 1.0 / 10, 2, 55.0 / 144,
       13.0 / 5},
  };
}

// The same with dead band 0 (docs/metrics.md, second table).
std::vector<Expected> examples_zero() {
  auto ex = examples_default();
  ex[0].final_belief_time = 0;
  ex[1].time_deceived = 5.0 / 6;
  ex[1].final_belief_time = 8;
  ex[2].time_deceived = 1;
  ex[3].time_deceived = 3.0 / 16;
  ex[4].time_deceived = 35.0 / 72;
  ex[4].final_belief_time = 12.0 / 5;
  return ex;
}

TrialScore run(const std::vector<double>& t, const std::vector<double>& mu, double target,
               double delta = 0.05) {
  MetricSettings s;
  s.norm = ConfusionNorm::raw;
  s.belief_deadband = delta;
  return score_trace(t, mu, target, std::nullopt, s);
}

void expect_near_or_empty(double got, double want, const char* what) {
  SCOPED_TRACE(what);
  if (std::isnan(want)) {
    EXPECT_TRUE(std::isnan(got)) << got;
  } else {
    EXPECT_NEAR(got, want, 1e-12);
  }
}

void check(const std::vector<Expected>& examples, double delta) {
  for (const auto& ex : examples) {
    SCOPED_TRACE(ex.name);
    const auto s = run(ex.t, ex.mu, ex.target, delta);
    expect_near_or_empty(s.signed_area, ex.signed_area, "signed_area");
    expect_near_or_empty(s.max_deviation, ex.max_deviation, "max_deviation");
    EXPECT_EQ(s.flips, ex.flips);
    expect_near_or_empty(s.time_deceived, ex.time_deceived, "time_deceived");
    expect_near_or_empty(s.final_belief_time, ex.final_belief_time, "final_belief_time");
  }
}

}  // namespace

TEST(BeliefMeasures, WorkedExamplesDefaultDeadBand) { check(examples_default(), 0.05); }

TEST(BeliefMeasures, WorkedExamplesZeroDeadBand) { check(examples_zero(), 0.0); }

TEST(BeliefMeasures, DefaultDeadBandIsFiveHundredths) {
  EXPECT_EQ(MetricSettings{}.belief_deadband, 0.05);
}

TEST(BeliefMeasures, MirroredTraceGivesTheSameMeasures) {
  // Left and right are symmetric: mu -> 1 - mu with T -> 1 - T changes nothing.
  for (const auto& ex : examples_default()) {
    SCOPED_TRACE(ex.name);
    std::vector<double> mirrored;
    for (double m : ex.mu) mirrored.push_back(1 - m);
    const auto a = run(ex.t, ex.mu, ex.target), b = run(ex.t, mirrored, 1 - ex.target);
    expect_near_or_empty(b.signed_area, a.signed_area, "signed_area");
    expect_near_or_empty(b.max_deviation, a.max_deviation, "max_deviation");
    EXPECT_EQ(b.flips, a.flips);
    expect_near_or_empty(b.time_deceived, a.time_deceived, "time_deceived");
    expect_near_or_empty(b.final_belief_time, a.final_belief_time, "final_belief_time");
  }
}

TEST(BeliefMeasures, SignedAreaEqualsErrorWhenThePadNeverCrossesTheTarget) {
  // With T = 0 or 1 the pad cannot pass T: |signed area| is the error.
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 200; ++k) {
    std::vector<double> t{0}, mu{0.5};
    for (int i = 0; i < 30; ++i) {
      t.push_back(t.back() + 0.01 + u(gen));
      mu.push_back(u(gen));
    }
    const double T = k % 2;
    const auto s = run(t, mu, T);
    EXPECT_NEAR(s.signed_area, s.error, 1e-12);
    EXPECT_GE(s.time_deceived, 0);
    EXPECT_LE(s.time_deceived, 1);
    EXPECT_GE(s.max_deviation, -0.5);
    EXPECT_LE(s.max_deviation, 0.5);
    // Only the pad on the false side beyond the dead band deceives; then it must lean past it.
    if (s.time_deceived > 0) {
      EXPECT_GT(s.max_deviation, 0.05);
    }
  }
}

TEST(BeliefMeasures, TargetInTheMiddleLeavesSideMeasuresEmpty) {
  // T = 1/2: no false side. Empty (NaN, written as an empty cell), never 0; flips still count.
  const auto s = run({0, 1, 2, 3}, {0.5, 0.9, 0.2, 0.6}, 0.5);
  EXPECT_TRUE(std::isnan(s.signed_area));
  EXPECT_TRUE(std::isnan(s.max_deviation));
  EXPECT_TRUE(std::isnan(s.time_deceived));
  EXPECT_TRUE(std::isnan(s.final_belief_time));
  EXPECT_EQ(s.flips, 2);
}

TEST(BeliefMeasures, PadThatNeverMovesHasNoFinalBeliefAndNoFlips) {
  const auto s = run({0, 1, 2, 3}, {0.5, 0.5, 0.5, 0.5}, 1);
  EXPECT_EQ(s.flips, 0);
  EXPECT_EQ(s.time_deceived, 0);
  EXPECT_EQ(s.max_deviation, 0);
  EXPECT_FALSE(std::signbit(s.max_deviation));  // written "0", never "-0"
  EXPECT_EQ(s.signed_area, 0.5);
  EXPECT_TRUE(std::isnan(s.final_belief_time));  // never committed to the true side: empty, not 0
}

TEST(BeliefMeasures, TwoSamplesAreEnough) {
  // One segment 0.5 -> 1 over [0, 1], T = 1: crosses 0.55 at t = 0.1; no flip; window [0.05, 0.95].
  const auto s = run({0, 1}, {0.5, 1}, 1);
  EXPECT_NEAR(s.final_belief_time, 0.1, 1e-12);
  EXPECT_EQ(s.flips, 0);
  EXPECT_EQ(s.time_deceived, 0);
  EXPECT_NEAR(s.max_deviation, -0.025, 1e-12);
  EXPECT_NEAR(s.signed_area, 0.25, 1e-12);
}

TEST(BeliefMeasures, FlipsIgnoreMovesWithinTheDeadBand) {
  // Tremor of 0.04 around 0.6 does not flip with delta 0.05; one real return (0.6 -> 0.3) does.
  const std::vector<double> t{0, 1, 2, 3, 4, 5, 6, 7};
  const std::vector<double> mu{0.5, 0.6, 0.56, 0.6, 0.56, 0.6, 0.3, 0.3};
  EXPECT_EQ(run(t, mu, 1, 0.05).flips, 1);
  EXPECT_EQ(run(t, mu, 1, 0.0).flips, 5);
  EXPECT_EQ(run(t, mu, 1, 0.35).flips, 0);  // nothing moves more than 0.35 from an extreme back
}

TEST(BeliefMeasures, TouchingTheDeadBandLineIsNotStaying) {
  // T = 1, delta 0: true side is mu > 1/2. The pad goes to 0.8, back to exactly 0.5 at t = 2, and
  // up again: the final correct belief starts at t = 2, not at 0.
  const auto s = run({0, 1, 2, 3}, {0.5, 0.8, 0.5, 0.9}, 1, 0.0);
  EXPECT_NEAR(s.final_belief_time, 2, 1e-12);
}

TEST(BeliefMeasures, ScaleOfTimeDoesNotChangeShares) {
  // time_deceived and signed_area are shares of the window; final_belief_time scales with time.
  const auto ex = examples_default()[4];
  for (double scale : {1e-200, 1e-3, 1e3, 1e200}) {
    SCOPED_TRACE(scale);
    std::vector<double> t;
    for (double x : ex.t) t.push_back(x * scale);
    const auto s = run(t, ex.mu, ex.target);
    EXPECT_NEAR(s.time_deceived, ex.time_deceived, 1e-12);
    EXPECT_NEAR(s.signed_area, ex.signed_area, 1e-12);
    EXPECT_NEAR(s.final_belief_time / scale, ex.final_belief_time, 1e-12);
  }
}

TEST(BeliefMeasures, DeadBandOutOfRangeIsAUsageError) {
  for (double bad : {-0.01, 0.5, 0.7, std::nan(""), HUGE_VAL}) {
    MetricSettings s;
    s.belief_deadband = bad;
    EXPECT_THROW(s.validate(), feint::UsageError) << bad;
  }
  MetricSettings ok;
  ok.belief_deadband = 0.49;
  EXPECT_NO_THROW(ok.validate());
}

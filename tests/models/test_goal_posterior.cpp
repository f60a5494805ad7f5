// The K-goal observer (feint/models/goal_posterior.hpp): the two-goal observer at K = 2, the
// worked example of docs/deceptive-paths.md at K = 3, invariants, and refused parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/metrics/layout.hpp"
#include "feint/models/goal_inference.hpp"
#include "feint/models/goal_posterior.hpp"
#include "feint/rng.hpp"
#include "observer_test_paths.hpp"

using namespace feint::models;
using feint::metrics::Layout;
namespace tp = feint::testpaths;

namespace {

// docs/deceptive-paths.md's three targets, all 5 m from the start: (-3, 4), (0, 5), (3, 4).
Layout three_targets() { return {{0, 0}, {{-3, 4}, {0, 5}, {3, 4}}}; }

// Points on a grid around the paper's layout and beyond it (behind the start, past the targets).
std::vector<Position> probe_points() {
  std::vector<Position> pts;
  for (double x = -6; x <= 6; x += 0.37) {
    for (double y = -3; y <= 9; y += 0.41) pts.push_back({x, y});
  }
  for (double y = -1; y <= 6; y += 0.5) pts.push_back({0, y});  // the midline: ties
  return pts;
}

}  // namespace

TEST(GoalPosterior, TwoGoalsEqualBeliefRightTo1e15) {
  // K = 2 on the paper's layout: target 1 is the right goal. Every point, beta from 0 to 50, three
  // priors and two starts; both probabilities against belief_right and its complement.
  const Layout paper = feint::metrics::paper_layout();
  const Goals goals;  // (-2, 4), (2, 4): the same targets
  double worst = 0;
  for (const Position start : {Position{0, 0}, Position{0.7, -1.3}}) {
    for (const double beta : {0.0, 0.05, 0.3, 1.0, 2.5, 7.0, 15.0, 30.0, 50.0}) {
      for (const double prior_right : {0.5, 0.3, 0.85}) {
        const std::vector<double> prior{1 - prior_right, prior_right};
        for (const Position q : probe_points()) {
          const auto p = goal_posterior(start, q, paper.targets, beta, prior);
          const double b = belief_right(start, q, goals, beta, prior_right);
          worst = std::max({worst, std::abs(p[1] - b), std::abs(p[0] - (1 - b))});
        }
      }
    }
  }
  EXPECT_LE(worst, 1e-15);
}

TEST(GoalPosterior, TwoGoalTraceEqualsBeliefTrace) {
  // The four paper shapes toward each side, with a delay: before the start the prior, then the
  // delayed posterior, row by row equal to belief_trace.
  const Layout paper = feint::metrics::paper_layout();
  for (int shape = 0; shape < 4; ++shape) {
    for (const double side : {-1.0, 1.0}) {
      const auto path = tp::shape(shape, side);
      std::vector<double> times;
      for (double t = -0.5; t < path.back().t + 1; t += 0.13) times.push_back(t);
      const GoalObserver two{1.7, 0.35, 0.4};
      const GoalPosteriorObserver k{1.7, 0.35, {0.6, 0.4}};
      const auto b = belief_trace(path, times, Goals{}, two);
      const auto p = posterior_trace(path, times, paper, k);
      ASSERT_EQ(p.size(), times.size());
      for (std::size_t i = 0; i < times.size(); ++i) {
        ASSERT_EQ(p[i].size(), 2u);
        EXPECT_NEAR(p[i][1], b[i], 1e-15) << shape << " " << side << " t = " << times[i];
      }
      EXPECT_NEAR(p.front()[1], 0.4, 1e-15);  // before the robot moves: the prior
    }
  }
}

TEST(GoalPosterior, ThreeTargetsWorkedExample) {
  // docs/deceptive-paths.md: beta = 1, uniform prior. At the start every cost difference is 0, so
  // the posterior is the prior. At Q = (0, 4), on the line to target 1: V = (3, 1, 3), V(S) = 5, so
  // a = -(V - 5) = (2, 4, 2): P(1) = 1 / (1 + 2 e^-2), P(0) = P(2) = 1 / (2 + e^2).
  const Layout map = three_targets();
  const GoalPosteriorObserver o{1.0, 0.0, {}};
  const auto at_start = goal_posterior(map, {0, 0}, o);
  for (double v : at_start) EXPECT_NEAR(v, 1.0 / 3, 2e-16);
  const auto at_q = goal_posterior(map, {0, 4}, o);
  const double p1 = 1 / (1 + 2 * std::exp(-2.0)), p0 = 1 / (2 + std::exp(2.0));
  EXPECT_NEAR(at_q[1], p1, 1e-15);  // 0.786986...
  EXPECT_NEAR(at_q[0], p0, 1e-15);  // 0.106507...
  EXPECT_NEAR(at_q[2], p0, 1e-15);
  EXPECT_NEAR(at_q[1], 0.78698604, 5e-9);  // the values printed in the docs
  EXPECT_NEAR(entropy_bits(at_q), -(p1 * std::log2(p1) + 2 * p0 * std::log2(p0)), 1e-15);
  EXPECT_NEAR(entropy_bits(at_q), 0.96021841, 5e-9);
  EXPECT_NEAR(entropy_bits(at_start), std::log2(3.0), 1e-15);
  // A non-uniform prior is returned unchanged at the start, and scales the odds at Q.
  const GoalPosteriorObserver skew{1.0, 0.0, {0.2, 0.5, 0.3}};
  const auto s0 = goal_posterior(map, {0, 0}, skew);
  EXPECT_NEAR(s0[0], 0.2, 2e-16);
  EXPECT_NEAR(s0[1], 0.5, 2e-16);
  EXPECT_NEAR(s0[2], 0.3, 2e-16);
  const auto sq = goal_posterior(map, {0, 4}, skew);
  const double z = 0.2 * std::exp(2.0) + 0.5 * std::exp(4.0) + 0.3 * std::exp(2.0);
  EXPECT_NEAR(sq[0], 0.2 * std::exp(2.0) / z, 1e-15);
  EXPECT_NEAR(sq[1], 0.5 * std::exp(4.0) / z, 1e-15);
}

TEST(GoalPosterior, SumsToOneEntropyBoundedAndTheLogFormAgrees) {
  feint::Rng rng(20240611);
  for (int trial = 0; trial < 400; ++trial) {
    const std::size_t k = 2 + static_cast<std::size_t>(trial % 6);
    Layout map{{rng.uniform() - 0.5, rng.uniform() - 0.5}, {}};
    std::vector<double> prior;
    double sum = 0;
    for (std::size_t i = 0; i < k; ++i) {
      map.targets.push_back({10 * rng.uniform() - 5, 6 * rng.uniform()});
      prior.push_back(0.05 + rng.uniform());
      sum += prior.back();
    }
    for (double& v : prior) v /= sum;
    const double beta = trial % 7 == 0 ? 0.0 : 60 * rng.uniform();
    const Position q{12 * rng.uniform() - 6, 10 * rng.uniform() - 3};
    const Position s{map.start.x, map.start.y};
    const auto p = goal_posterior(s, q, map.targets, beta, prior);
    const auto lp = goal_log_posterior(s, q, map.targets, beta, prior);
    double total = 0;
    for (std::size_t i = 0; i < k; ++i) {
      total += p[i];
      ASSERT_GE(p[i], 0.0);
      ASSERT_LE(lp[i], 1e-15);
      EXPECT_NEAR(std::exp(lp[i]), p[i], 1e-13);
      if (beta == 0) {
        EXPECT_NEAR(p[i], prior[i], 1e-15);  // the path is ignored
      }
    }
    EXPECT_NEAR(total, 1.0, 1e-15);
    const double h = entropy_bits(p);
    EXPECT_GE(h, 0.0);
    EXPECT_LE(h, std::log2(static_cast<double>(k)) + 1e-15);
  }
}

TEST(GoalPosterior, HugeBetaNeitherOverflowsNorLosesTheLead) {
  // beta = 1e6: exp(beta * rise) would overflow; the log-sum-exp form gives the target the robot
  // made most progress toward probability 1, and finite logs for the others.
  const Layout map = three_targets();
  const auto p = goal_posterior({0, 0}, {0, 4}, map.targets, 1e6, {});
  EXPECT_EQ(p[1], 1.0);
  EXPECT_EQ(p[0], 0.0);
  const auto lp = goal_log_posterior({0, 0}, {0, 4}, map.targets, 1e6, {});
  EXPECT_TRUE(std::isfinite(lp[0]));
  EXPECT_NEAR(lp[0], -2e6, 1e-6 * 2e6);  // ln P(0) = -beta (rise_0 - rise_1) = -2e6
  EXPECT_EQ(lp[1], 0.0);
  EXPECT_NEAR(entropy_bits(p), 0.0, 1e-300);
}

TEST(GoalPosterior, StraightLineToATargetRaisesItsProbability) {
  const Layout map = three_targets();
  double last = 0;
  for (double y = 0; y <= 5; y += 0.25) {
    const auto p = goal_posterior({0, 0}, {0, y}, map.targets, 2.0, {});
    EXPECT_GE(p[1], last);
    EXPECT_NEAR(p[0], p[2], 1e-15);  // mirror symmetry
    last = p[1];
  }
}

TEST(GoalPosterior, EntropyOfKnownDistributions) {
  EXPECT_EQ(entropy_bits(std::vector<double>{0.5, 0.5}), 1.0);
  EXPECT_EQ(entropy_bits(std::vector<double>{1.0, 0.0, 0.0}), 0.0);
  EXPECT_NEAR(entropy_bits(std::vector<double>(5, 0.2)), std::log2(5.0), 1e-15);
  EXPECT_NEAR(entropy_bits(std::vector<double>{0.25, 0.75}), 2 - 0.75 * std::log2(3.0), 1e-15);
}

TEST(GoalPosterior, BadParametersAreRefusedByName) {
  const Layout map = three_targets();
  auto refuses = [&](GoalPosteriorObserver o, const std::string& word) {
    try {
      goal_posterior(map, {0, 1}, o);
      ADD_FAILURE() << "accepted: " << word;
    } catch (const feint::UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  refuses({-0.1, 0, {}}, "beta");
  refuses({std::nan(""), 0, {}}, "beta");
  refuses({std::numeric_limits<double>::infinity(), 0, {}}, "beta");
  refuses({1, -1, {}}, "tau");
  refuses({1, 0, {0.5, 0.5}}, "2 entries for 3 targets");
  refuses({1, 0, {0.3, 0.3, 0.3}}, "prior sums to 0.89");
  refuses({1, 0, {0.0, 0.5, 0.5}}, "target 0");
  refuses({1, 0, {-0.2, 0.7, 0.5}}, "target 0");
  refuses({1, 0, {0.2, std::nan(""), 0.5}}, "target 1");
  EXPECT_NO_THROW(goal_posterior(map, {0, 1}, {1, 0, {0.2, 0.5, 0.3}}));
  const Layout one{{0, 0}, {{1, 1}}};
  EXPECT_THROW(goal_posterior(one, {0, 1}, {}), feint::UsageError);
  const Layout inf{{0, 0}, {{1, 1}, {std::numeric_limits<double>::infinity(), 2}}};
  EXPECT_THROW(goal_posterior(inf, {0, 1}, {}), feint::UsageError);
  const std::vector<PathSample> path{{0, 0, 0}, {1, 0, 1}};
  const std::vector<double> times{0, 0.5};
  EXPECT_THROW(posterior_trace(path, times, map, {-1, 0, {}}), feint::UsageError);
}

// The goal-inference observer's closed form: invariants of the posterior.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "feint/error.hpp"
#include "feint/models/goal_inference.hpp"

using namespace feint::models;

TEST(GoalInference, StraightPathToTheRightGoalRaisesTheBeliefMonotonicallyTowardOne) {
  const Goals goals;  // (-2, 4) and (2, 4)
  std::vector<PathSample> path;
  for (int i = 0; i <= 100; ++i) path.push_back({i * 0.0565685424949238, 0.02 * i, 0.04 * i});
  std::vector<double> times;
  for (const auto& s : path) times.push_back(s.t);
  const auto b = belief_trace(path, times, goals, GoalObserver{3.0, 0.0, 0.5});
  EXPECT_DOUBLE_EQ(b.front(), 0.5);
  for (std::size_t i = 1; i < b.size(); ++i) EXPECT_GT(b[i], b[i - 1]) << i;
  EXPECT_GT(b.back(), 0.999);
}

TEST(GoalInference, MidlineGivesExactlyOneHalf) {
  const Goals goals;
  for (double y : {0.0, 0.5, 1.7, 3.9}) {
    EXPECT_EQ(belief_right({0, 0}, {0, y}, goals, 5.0, 0.5), 0.5) << y;
  }
}

TEST(GoalInference, LeftAndRightAreMirrorSymmetric) {
  const Goals goals;
  for (double x : {0.1, 0.7, 1.9}) {
    const double r = belief_right({0, 0}, {x, 1.3}, goals, 2.0, 0.5);
    const double l = belief_right({0, 0}, {-x, 1.3}, goals, 2.0, 0.5);
    EXPECT_NEAR(r + l, 1.0, 1e-15) << x;
  }
}

TEST(GoalInference, BetaZeroReturnsThePrior) {
  EXPECT_NEAR(belief_right({0, 0}, {1.5, 2}, Goals{}, 0.0, 0.3), 0.3, 1e-15);
}

TEST(GoalInference, ClosedFormMatchesTheDefinitionWithThePathCost) {
  // P(R) = exp(-b (C + V_R(Q) - V_R(S))) / (that + the same for L), C = path length cancels.
  const Goals goals;
  const Position s{0, 0}, q{0.6, 1.0};
  const double beta = 1.7, c = 2.3;
  auto term = [&](Position g) {
    return std::exp(-beta * (c + std::hypot(q.x - g.x, q.y - g.y) - std::hypot(s.x - g.x, s.y - g.y)));
  };
  const double expected = term(goals.right) / (term(goals.right) + term(goals.left));
  EXPECT_NEAR(belief_right(s, q, goals, beta, 0.5), expected, 1e-15);
}

TEST(GoalInference, DelayShiftsTheTraceInTime) {
  const std::vector<PathSample> path{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  const std::vector<double> times{0.5, 1.0, 1.5, 2.5};
  const auto late = belief_trace(path, times, Goals{}, GoalObserver{1.0, 0.5, 0.5});
  const std::vector<double> early_times{0.0, 0.5, 1.0, 2.0};
  const auto early = belief_trace(path, early_times, Goals{}, GoalObserver{1.0, 0.0, 0.5});
  for (std::size_t i = 0; i < times.size(); ++i) EXPECT_DOUBLE_EQ(late[i], early[i]) << i;
}

TEST(GoalInference, ExtremeBetaStaysFinite) {
  const double b = belief_right({0, 0}, {-1.9, 3.9}, Goals{}, 1e6, 0.5);
  EXPECT_EQ(b, 0.0);
  EXPECT_TRUE(std::isfinite(belief_logit({0, 0}, {-1.9, 3.9}, Goals{}, 1e6, 0.5)));
}

TEST(GoalInference, InvalidParametersAreRefusedByName) {
  EXPECT_THROW(validate(GoalObserver{-1, 0, 0.5}), feint::UsageError);
  EXPECT_THROW(validate(GoalObserver{1, -0.1, 0.5}), feint::UsageError);
  EXPECT_THROW(validate(GoalObserver{1, 0, 1.0}), feint::UsageError);
  EXPECT_NO_THROW(validate(GoalObserver{}));
}

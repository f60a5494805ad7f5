// The observer's measures of the paper's strategies (feint/sim/trajectory_measures.hpp).
#include <cmath>
#include <gtest/gtest.h>

#include "feint/error.hpp"
#include "feint/models/goal_inference.hpp"
#include "feint/sim/trajectory_measures.hpp"

using namespace feint::sim;

TEST(TrajectoryMeasures, AmbiguousOnTheMidlineIsExactlyOneHalf) {
  const Geometry g;
  const auto path = to_path(trajectory(Strategy::ambiguous, Variant::main, Target::right, g));
  const auto goals = goals_of(g);
  std::vector<double> times;
  for (const auto& s : path) times.push_back(s.t);
  const auto b = feint::models::belief_trace(path, times, goals, feint::models::GoalObserver{3.0, 0.0, 0.5});
  int on_midline = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i].x == 0.0) {
      EXPECT_EQ(b[i], 0.5) << i;
      ++on_midline;
    }
  }
  EXPECT_GT(on_midline, 50);
}

TEST(TrajectoryMeasures, EveryStrategyBothTargetsMirrorSymmetric) {
  const auto rows = strategy_measures(Geometry{}, feint::models::DeceptivenessSettings{});
  ASSERT_EQ(rows.size(), 14u);
  for (std::size_t i = 0; i < rows.size(); i += 2) {
    EXPECT_EQ(rows[i].target, "left");
    EXPECT_EQ(rows[i + 1].target, "right");
    EXPECT_EQ(rows[i].strategy, rows[i + 1].strategy);
    const auto& l = rows[i].measures;
    const auto& r = rows[i + 1].measures;
    EXPECT_NEAR(l.legibility, r.legibility, 1e-12) << rows[i].strategy;
    EXPECT_NEAR(l.time_deceived, r.time_deceived, 1e-12);
    EXPECT_NEAR(l.last_deceptive_point, r.last_deceptive_point, 1e-12);
    EXPECT_NEAR(l.belief_error, r.belief_error, 1e-12);
    EXPECT_NEAR(l.belief_confusion, r.belief_confusion, 1e-12);
  }
  // Optimal: never deceptive, no overhead; exaggerating main deceives longer than ambiguous main.
  EXPECT_EQ(rows[13].strategy, "optimal");
  EXPECT_EQ(rows[13].measures.time_deceived, 0.0);
  EXPECT_EQ(rows[13].measures.last_deceptive_point, 0.0);
  EXPECT_NEAR(rows[13].measures.cost_overhead, 0.0, 1e-12);
  EXPECT_GT(rows[0].measures.time_deceived, rows[9].measures.time_deceived);
}


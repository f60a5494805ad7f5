// Trajectory invariants (selection.md "Trajectories"): not pixel positions.
#include <gtest/gtest.h>

#include <cmath>

#include "feint/error.hpp"
#include "feint/sim/trajectory.hpp"

using namespace feint::sim;

namespace {
const Geometry g{};
constexpr Strategy kAll[] = {Strategy::exaggerating, Strategy::switching, Strategy::ambiguous,
                             Strategy::optimal};

double pad(const TrajectorySample& s) { return pad_coordinate(s.x, g); }

/// Crossings of the midline x = 0 (a sign change between samples, ignoring samples on it).
int midline_crossings(const std::vector<TrajectorySample>& path) {
  int crossings = 0;
  double last = 0;
  for (const auto& s : path) {
    if (std::abs(s.x) < 1e-9) continue;
    if (last != 0 && (s.x > 0) != (last > 0)) ++crossings;
    last = s.x;
  }
  return crossings;
}
}  // namespace

TEST(Trajectory, EveryPathEndsAtTheTrueTargetAtConstantSpeed) {
  for (auto s : kAll) {
    for (auto v : {Variant::main, Variant::v2}) {
      if (s == Strategy::optimal && v == Variant::v2) continue;
      for (auto t : {Target::left, Target::right}) {
        const auto path = trajectory(s, v, t, g);
        ASSERT_GE(path.size(), 10u);
        EXPECT_EQ(path.front().t, 0.0);
        EXPECT_NEAR(path.front().x, 0.0, 1e-12);
        EXPECT_NEAR(path.front().y, 0.0, 1e-12);
        EXPECT_NEAR(pad(path.back()), t == Target::left ? 0.0 : 1.0, 1e-12);
        EXPECT_NEAR(path.back().y, g.target_height, 1e-12);
        // constant speed: the path length / duration is the speed, and no step is faster
        const double len = path_length(waypoints(s, v, t, g));
        EXPECT_NEAR(len / g.speed, path.back().t, 1e-4);
        int full_steps = 0;
        for (std::size_t i = 1; i < path.size(); ++i) {
          const double dt = path[i].t - path[i - 1].t;
          ASSERT_GT(dt, 0.0);
          const double step = std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
          EXPECT_LE(step, g.speed * dt * (1 + 1e-9) + 1e-12);
          full_steps += std::abs(step - g.speed * dt) < 1e-9 ? 1 : 0;
        }
        // only steps that round a corner (and the last) are shorter than speed * dt
        EXPECT_GE(full_steps, static_cast<int>(path.size()) - 2 - g.zigzag_corners - 2);
        EXPECT_NEAR(path[1].t - path[0].t, 1.0 / g.sample_rate, 1e-12);
      }
    }
  }
}

TEST(Trajectory, OptimalGoesStraightToTheTarget) {
  const auto path = trajectory(Strategy::optimal, Variant::main, Target::right, g);
  // every sample on the segment from (0, 0) to (d/2, h): x h = y d/2
  for (const auto& s : path) EXPECT_NEAR(s.x * g.target_height, s.y * g.target_distance / 2, 1e-9);
  EXPECT_THROW(trajectory(Strategy::optimal, Variant::v2, Target::left, g), std::invalid_argument);
}

TEST(Trajectory, ExaggeratingGoesTowardTheFalseSideFirst) {
  for (auto t : {Target::left, Target::right}) {
    const auto path = trajectory(Strategy::exaggerating, Variant::main, t, g);
    const double false_sign = t == Target::left ? 1.0 : -1.0;
    // the first third of the path moves away from the midline, on the false side
    for (std::size_t i = 1; i < path.size() / 3; ++i) {
      EXPECT_GT(false_sign * path[i].x, 0.0);
      EXPECT_GT(false_sign * path[i].x, false_sign * path[i - 1].x);
    }
    double furthest = 0;
    for (const auto& s : path) furthest = std::max(furthest, false_sign * s.x);
    EXPECT_GE(furthest, 0.9 * g.target_distance / 2);  // it comes beside the false target
  }
}

TEST(Trajectory, SwitchingCrossesTheMidlineAtLeastTwice) {
  for (auto t : {Target::left, Target::right}) {
    EXPECT_GE(midline_crossings(trajectory(Strategy::switching, Variant::main, t, g)), 2);
    EXPECT_GE(midline_crossings(trajectory(Strategy::switching, Variant::v2, t, g)), 2);
  }
  Geometry three = g;
  three.zigzag_corners = 3;
  EXPECT_GE(midline_crossings(trajectory(Strategy::switching, Variant::main, Target::left, three)), 2);
}

TEST(Trajectory, AmbiguousGoesUpTheMidline) {
  const auto path = trajectory(Strategy::ambiguous, Variant::main, Target::left, g);
  for (const auto& s : path) {
    if (s.y <= g.ambiguous_height * g.target_height - 1e-9) {
      EXPECT_NEAR(s.x, 0.0, 1e-12);
    }
  }
  EXPECT_GT(path.back().y, g.ambiguous_height * g.target_height);
}

TEST(Trajectory, Version2HeadsToTheFalseTargetAndEndsAtTheTrueOne) {
  for (auto s : {Strategy::exaggerating, Strategy::switching, Strategy::ambiguous}) {
    for (auto t : {Target::left, Target::right}) {
      const auto path = trajectory(s, Variant::v2, t, g);
      const double T = t == Target::left ? 0.0 : 1.0;
      // the pad coordinate comes within a quarter of the false target, late in the path ...
      std::size_t near_false = 0;
      for (std::size_t i = 0; i < path.size(); ++i) {
        if (std::abs(pad(path[i]) - (1 - T)) <= 0.35) near_false = i;
      }
      EXPECT_GT(near_false, path.size() / 2) << to_string(s);
      // ... and then it turns: the last stretch moves monotonically to the true target
      for (std::size_t i = near_false + 1; i < path.size(); ++i) {
        EXPECT_LE(std::abs(pad(path[i]) - T), std::abs(pad(path[i - 1]) - T) + 1e-12);
      }
      EXPECT_NEAR(pad(path.back()), T, 1e-12);
    }
  }
}

TEST(Geometry, BadParametersAreNamed) {
  Geometry bad = g;
  bad.speed = 0;
  try {
    validate(bad);
    FAIL();
  } catch (const feint::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("speed"), std::string::npos);
  }
  bad = g;
  bad.zigzag_corners = 2;
  EXPECT_THROW(validate(bad), feint::UsageError);
  bad = g;
  bad.ambiguous_height = 1.0;
  EXPECT_THROW(validate(bad), feint::UsageError);
}

// feint/sim/trajectory.hpp - robot trajectories of the four strategies (seed paper sec. III;
// selection.md "Trajectories").
//
// A 2-D world in metres: the robot starts at (0, 0), midway between and below the two targets at
// (-d/2, h) (left, pad 0) and (+d/2, h) (right, pad 1). Every path is a polyline traversed at one
// constant speed and sampled at a fixed rate; it ends exactly at the true target.
//   optimal       straight to the true target;
//   exaggerating  first to a point beside the false target, then to the true target;
//   switching     zig-zag across the midline (corners alternate sides, false side first), then to
//                 the true target;
//   ambiguous     straight up the midline to a set height, then to the true target;
//   v2 (S0-S2)    the main path planned as if the false target were the true one, cut short
//                 `v2_turn_remaining` metres before its end, then straight to the true target.
#pragma once

#include <vector>

#include "feint/sim/selection.hpp"

namespace feint::sim {

/// Every geometric setting, with its default (metres, seconds).
struct Geometry {
  double target_distance = 4.0;    // distance between the two targets (m)
  double target_height = 4.0;      // height of the targets' row above the start (m)
  double speed = 1.0;              // robot speed (m/s), constant along the path
  double sample_rate = 25.0;       // samples per second (Hz)
  double exaggeration_x = 1.0;     // exaggerating waypoint: x in units of the false target's x
  double exaggeration_y = 0.6;     //   ... and y as a fraction of target_height
  double zigzag_width = 0.8;       // switching: |x| of the zig-zag corners (m)
  int zigzag_corners = 4;          // switching: number of corners (corners - 1 midline crossings)
  double zigzag_height = 0.75;     // switching: y of the last corner, fraction of target_height
  double ambiguous_height = 0.8;   // ambiguous: y where the robot leaves the midline, fraction
  double v2_turn_remaining = 0.8;  // v2: path length (m) short of the decoy's end where it turns
};

/// Throws UsageError naming the parameter when a setting is out of range (non-positive sizes,
/// speed or rate; zigzag_corners < 3; fractions outside (0, 1); exaggeration_x <= 0).
void validate(const Geometry& g);

struct Point {
  double x = 0;
  double y = 0;
};

struct TrajectorySample {
  double t = 0;  // s since the start
  double x = 0;
  double y = 0;
};

/// The waypoints (start first, true target last) of a strategy's path.
/// Throws std::invalid_argument for optimal/v2 (the optimal strategy has one version).
std::vector<Point> waypoints(Strategy s, Variant v, Target true_target, const Geometry& g);

/// The path sampled at `sample_rate` at constant `speed`: samples at t = i / rate along the
/// polyline's arc length, plus the end point at t = length / speed rounded up to 0.1 ms (the robot
/// rests at the target for that fraction; grid samples closer than 1 ms to the end are dropped).
std::vector<TrajectorySample> trajectory(Strategy s, Variant v, Target true_target,
                                         const Geometry& g);

/// A polyline (start first) sampled as trajectory() samples a strategy's path: at `sample_rate` Hz
/// at constant `speed`, plus its last point at length / speed rounded up to 0.1 ms. `pts` must hold
/// at least one point; speed and rate > 0. The paths of sim/k_goal_paths.hpp are sampled with it.
std::vector<TrajectorySample> sample_polyline(const std::vector<Point>& pts, double speed,
                                              double sample_rate);

/// v2's turn "at the last moment": the polyline `decoy` cut `remaining` metres (path length) before
/// its end, then straight to `goal`. waypoints() builds every v2 path with it.
std::vector<Point> turn_before_end(const std::vector<Point>& decoy, double remaining, Point goal);

/// Pad coordinate of an x position: 0 at the left target, 1 at the right one (not clamped).
double pad_coordinate(double x, const Geometry& g) noexcept;

/// Total length of a polyline.
double path_length(const std::vector<Point>& pts) noexcept;

}  // namespace feint::sim

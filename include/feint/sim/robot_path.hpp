// feint/sim/robot_path.hpp - the robot's path during a logged trial (docs/formats.md "Robot path").
//
// A log written by `feint simulate study` or `feint collect` carries the robot's position at every
// pad sample (robot_x, robot_y: metres, the study's geometry; io::Trial::robot_x / robot_y when
// read with TraceOptions::read_robot_path). For a log without them the path is rebuilt from the
// trial's strategy, variant and target with the study's geometry: the robot runs the strategy's
// polyline (waypoints()) at geometry.speed from t0 and rests at the true target after its end, so
// its position at the pad sample time t_i is the point at arc length speed * (t_i - t0) (exact, not
// interpolated between the 25 Hz trajectory samples). The result says which it was, so that a
// report can state that the path was rebuilt (and is only as right as the geometry it was given).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "feint/io/trace.hpp"
#include "feint/sim/selection.hpp"
#include "feint/sim/trajectory.hpp"

namespace feint::sim {

/// The robot's path at a trial's pad samples.
struct RobotPath {
  /// One sample per pad sample: t = t_i - t0 (s since the trial's first sample), x, y (m).
  std::vector<TrajectorySample> samples;
  /// True when rebuilt from strategy, variant, target and geometry (the log had no robot columns).
  bool rebuilt = false;
};

/// "exaggerating", "switching", "ambiguous", "optimal" (any case, trimmed); nullopt otherwise.
std::optional<Strategy> parse_strategy(std::string_view text);
/// "main" or "v2" (any case, trimmed); also "" (a log without a variant column) as main.
std::optional<Variant> parse_variant(std::string_view text);

/// The robot's exact position at `t` seconds after the start on the polyline `pts` at `speed`:
/// the start before 0, the last point after the end.
Point position_on_path(const std::vector<Point>& pts, double speed, double t) noexcept;

/// The positions at `times` (s since the start) of a strategy's path: position_on_path on
/// waypoints(s, v, target, g). Throws UsageError for an invalid geometry, std::invalid_argument
/// for optimal/v2.
std::vector<TrajectorySample> robot_positions(Strategy s, Variant v, Target target,
                                              const Geometry& g, std::span<const double> times);

/// A robot coordinate (m) as the logs write it (robot_x, robot_y): rounded to 0.1 mm, shortest
/// decimal, never "-0".
std::string format_metres(double metres);

/// The trial's robot path: its robot_x / robot_y when the log has them (rebuilt = false), else
/// rebuilt from strategy, variant and target with `g` (rebuilt = true). Throws InvalidData naming
/// the trial (`file:line: ... (trial P/C/I)`) when the path cannot be rebuilt: no strategy, an
/// unknown strategy or variant, optimal v2, a target other than left/right (0 or 1); or when the
/// robot columns do not match the samples.
RobotPath robot_path(const io::Trial& trial, const Geometry& g);

}  // namespace feint::sim

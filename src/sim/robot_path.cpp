// The robot's path during a logged trial (see feint/sim/robot_path.hpp).
#include "feint/sim/robot_path.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/number.hpp"

namespace feint::sim {

std::optional<Strategy> parse_strategy(std::string_view text) {
  const std::string s = io::to_lower(io::trim(text));
  for (const Strategy st :
       {Strategy::exaggerating, Strategy::switching, Strategy::ambiguous, Strategy::optimal}) {
    if (s == to_string(st)) return st;
  }
  return std::nullopt;
}

std::optional<Variant> parse_variant(std::string_view text) {
  const std::string s = io::to_lower(io::trim(text));
  if (s.empty() || s == to_string(Variant::main)) return Variant::main;
  if (s == to_string(Variant::v2)) return Variant::v2;
  return std::nullopt;
}

Point position_on_path(const std::vector<Point>& pts, double speed, double t) noexcept {
  if (pts.empty()) return {};
  double s = std::max(0.0, t) * speed;  // arc length travelled
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const double seg = std::hypot(pts[i].x - pts[i - 1].x, pts[i].y - pts[i - 1].y);
    if (s < seg) {
      const double f = s / seg;
      return {pts[i - 1].x + f * (pts[i].x - pts[i - 1].x),
              pts[i - 1].y + f * (pts[i].y - pts[i - 1].y)};
    }
    s -= seg;
  }
  return pts.back();  // at rest on the true target
}

std::vector<TrajectorySample> robot_positions(Strategy s, Variant v, Target target,
                                              const Geometry& g, std::span<const double> times) {
  const std::vector<Point> pts = waypoints(s, v, target, g);
  std::vector<TrajectorySample> out;
  out.reserve(times.size());
  for (const double t : times) {
    const Point p = position_on_path(pts, g.speed, t);
    out.push_back({t, p.x, p.y});
  }
  return out;
}

std::string format_metres(double metres) {
  // A robot's position is not known better than 0.1 mm; + 0.0 turns -0 into 0.
  return io::format_double(std::round(metres * 1e4) / 1e4 + 0.0);
}

RobotPath robot_path(const io::Trial& trial, const Geometry& g) {
  auto fail = [&](const std::string& what) -> InvalidData {
    return InvalidData(fmt::format("{}:{}: {} (trial {})", trial.file, trial.line, what,
                                   trial.label()));
  };
  RobotPath out;
  const std::size_t n = trial.times.size();
  const double t0 = n > 0 ? trial.times.front() : 0.0;
  if (!trial.robot_x.empty() || !trial.robot_y.empty()) {
    if (trial.robot_x.size() != n || trial.robot_y.size() != n) {
      throw fail(fmt::format("{} robot_x and {} robot_y values for {} samples (the robot's "
                             "position is needed on every row)",
                             trial.robot_x.size(), trial.robot_y.size(), n));
    }
    out.samples.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      out.samples.push_back({trial.times[i] - t0, trial.robot_x[i], trial.robot_y[i]});
    }
    return out;
  }
  const std::string how =
      "give the logs robot_x and robot_y columns, or a strategy, variant and target per trial";
  if (io::trim(trial.strategy).empty()) {
    throw fail(fmt::format("cannot rebuild the robot's path: the trial has no strategy ({})", how));
  }
  const auto s = parse_strategy(trial.strategy);
  if (!s) {
    throw fail(fmt::format("cannot rebuild the robot's path: strategy '{}' is not exaggerating, "
                           "switching, ambiguous or optimal ({})", trial.strategy, how));
  }
  const auto v = parse_variant(trial.variant);
  if (!v) {
    throw fail(fmt::format("cannot rebuild the robot's path: variant '{}' is not main or v2 ({})",
                           trial.variant, how));
  }
  if (*s == Strategy::optimal && *v == Variant::v2) {
    throw fail(fmt::format("cannot rebuild the robot's path: the optimal strategy has no v2 ({})",
                           how));
  }
  if (trial.target != 0 && trial.target != 1) {
    throw fail(fmt::format("cannot rebuild the robot's path: target {} is not left (0) or right "
                           "(1); the strategies are defined for two targets ({})",
                           io::format_double(trial.target), how));
  }
  std::vector<double> since_start(n);
  for (std::size_t i = 0; i < n; ++i) since_start[i] = trial.times[i] - t0;
  out.samples = robot_positions(*s, *v, trial.target == 0 ? Target::left : Target::right, g,
                                since_start);
  out.rebuilt = true;
  return out;
}

}  // namespace feint::sim

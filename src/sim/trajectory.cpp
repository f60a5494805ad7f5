// Strategy trajectories (selection.md "Trajectories"). See feint/sim/trajectory.hpp.
#include "feint/sim/trajectory.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::sim {

void validate(const Geometry& g) {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw UsageError(fmt::format("geometry: {} must be > 0, got {}", name, v));
  };
  auto fraction = [](double v, const char* name) {
    if (!(v > 0 && v < 1)) throw UsageError(fmt::format("geometry: {} must be in (0, 1), got {}", name, v));
  };
  positive(g.target_distance, "target_distance");
  positive(g.target_height, "target_height");
  positive(g.speed, "speed");
  positive(g.sample_rate, "sample_rate");
  positive(g.exaggeration_x, "exaggeration_x");
  positive(g.zigzag_width, "zigzag_width");
  positive(g.v2_turn_remaining, "v2_turn_remaining");
  fraction(g.exaggeration_y, "exaggeration_y");
  fraction(g.zigzag_height, "zigzag_height");
  fraction(g.ambiguous_height, "ambiguous_height");
  if (g.zigzag_corners < 3) {
    throw UsageError(fmt::format("geometry: zigzag_corners must be >= 3 (two midline crossings), got {}",
                                 g.zigzag_corners));
  }
}

double path_length(const std::vector<Point>& pts) noexcept {
  double len = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    len += std::hypot(pts[i].x - pts[i - 1].x, pts[i].y - pts[i - 1].y);
  }
  return len;
}

double pad_coordinate(double x, const Geometry& g) noexcept {
  return (x + g.target_distance / 2) / g.target_distance;
}

namespace {

/// The point at arc length s along the polyline (clamped to its ends).
Point point_at(const std::vector<Point>& pts, double s) noexcept {
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const double seg = std::hypot(pts[i].x - pts[i - 1].x, pts[i].y - pts[i - 1].y);
    if (s <= seg || i + 1 == pts.size()) {
      const double f = seg > 0 ? std::min(1.0, std::max(0.0, s / seg)) : 1.0;
      return {pts[i - 1].x + f * (pts[i].x - pts[i - 1].x), pts[i - 1].y + f * (pts[i].y - pts[i - 1].y)};
    }
    s -= seg;
  }
  return pts.back();
}

/// The main path toward `goal_sign` (-1 left, +1 right).
std::vector<Point> main_path(Strategy s, double goal_sign, const Geometry& g) {
  const double half = g.target_distance / 2;
  const double h = g.target_height;
  const Point goal{goal_sign * half, h};
  const double false_sign = -goal_sign;
  std::vector<Point> pts{{0, 0}};
  switch (s) {
    case Strategy::optimal:
      break;
    case Strategy::exaggerating:
      pts.push_back({false_sign * half * g.exaggeration_x, g.exaggeration_y * h});
      break;
    case Strategy::switching:
      for (int j = 1; j <= g.zigzag_corners; ++j) {
        const double side = (j % 2 == 1) ? false_sign : goal_sign;  // false side first
        pts.push_back({side * g.zigzag_width, g.zigzag_height * h * j / g.zigzag_corners});
      }
      break;
    case Strategy::ambiguous:
      pts.push_back({0, g.ambiguous_height * h});
      break;
  }
  pts.push_back(goal);
  return pts;
}

}  // namespace

std::vector<Point> waypoints(Strategy s, Variant v, Target true_target, const Geometry& g) {
  validate(g);
  const double sign = true_target == Target::left ? -1.0 : 1.0;
  if (v == Variant::main) return main_path(s, sign, g);
  if (s == Strategy::optimal) throw std::invalid_argument("the optimal strategy has no version 2");
  // v2: the main strategy as if the false target were the true one, turning to the true target
  // v2_turn_remaining metres before the decoy path's end ("at the last moment").
  return turn_before_end(main_path(s, -sign, g), g.v2_turn_remaining,
                         {sign * g.target_distance / 2, g.target_height});
}

std::vector<Point> turn_before_end(const std::vector<Point>& decoy, double remaining, Point goal) {
  const double len = path_length(decoy);
  const double cut = std::max(0.0, len - remaining);
  std::vector<Point> pts{decoy.front()};
  double acc = 0;
  for (std::size_t i = 1; i < decoy.size(); ++i) {
    const double seg = std::hypot(decoy[i].x - decoy[i - 1].x, decoy[i].y - decoy[i - 1].y);
    if (acc + seg >= cut) break;
    pts.push_back(decoy[i]);
    acc += seg;
  }
  pts.push_back(point_at(decoy, cut));
  pts.push_back(goal);
  return pts;
}

std::vector<TrajectorySample> trajectory(Strategy s, Variant v, Target true_target, const Geometry& g) {
  return sample_polyline(waypoints(s, v, true_target, g), g.speed, g.sample_rate);
}

std::vector<TrajectorySample> sample_polyline(const std::vector<Point>& pts, double speed,
                                              double sample_rate) {
  const double len = path_length(pts);
  // End time rounded up to 0.1 ms (the robot rests at the target for the remainder), so that a log
  // written with 4 decimals carries the exact sample times.
  const double duration = std::ceil(len / speed * 1e4) / 1e4;
  std::vector<TrajectorySample> out;
  for (long i = 0;; ++i) {
    const double t = static_cast<double>(i) / sample_rate;
    if (t >= duration - 1e-3) break;  // the end point is added below (no sample closer than 1 ms)
    const Point p = point_at(pts, t * speed);
    out.push_back({t, p.x, p.y});
  }
  out.push_back({duration, pts.back().x, pts.back().y});  // ends exactly at the true target
  return out;
}

}  // namespace feint::sim

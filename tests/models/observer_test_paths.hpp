// Robot paths and simulated pad traces for the observer tests and benchmarks (models cannot use
// sim, so the paths are built here: polylines at 1 m/s sampled at 25 Hz, like sim::trajectory).
#pragma once

#include <cmath>
#include <vector>

#include "feint/models/goal_inference.hpp"
#include "feint/models/observer_fit.hpp"
#include "feint/rng.hpp"

namespace feint::testpaths {

using models::PathSample;
using models::Position;

/// The polyline `pts` traversed at `speed` m/s, sampled at `rate` Hz, plus the end point.
inline std::vector<PathSample> polyline(const std::vector<Position>& pts, double speed = 1.0,
                                        double rate = 25.0) {
  std::vector<double> cum{0.0};
  for (std::size_t i = 1; i < pts.size(); ++i)
    cum.push_back(cum.back() + std::hypot(pts[i].x - pts[i - 1].x, pts[i].y - pts[i - 1].y));
  const double duration = cum.back() / speed;
  std::vector<PathSample> out;
  for (long k = 0;; ++k) {
    const double t = static_cast<double>(k) / rate;
    if (t >= duration - 1e-3) break;
    const double s = t * speed;
    std::size_t i = 1;
    while (i + 1 < pts.size() && cum[i] < s) ++i;
    const double seg = cum[i] - cum[i - 1];
    const double w = seg > 0 ? (s - cum[i - 1]) / seg : 1.0;
    out.push_back({t, pts[i - 1].x + w * (pts[i].x - pts[i - 1].x), pts[i - 1].y + w * (pts[i].y - pts[i - 1].y)});
  }
  out.push_back({duration, pts.back().x, pts.back().y});
  return out;
}

/// Four path shapes toward the goal on `side` (+1 right, -1 left), in the default goals' geometry.
inline std::vector<PathSample> shape(int kind, double side) {
  const Position goal{2.0 * side, 4.0};
  switch (kind % 4) {
    case 0: return polyline({{0, 0}, goal});                                   // optimal
    case 1: return polyline({{0, 0}, {-2.0 * side, 2.4}, goal});                // exaggerating
    case 2: return polyline({{0, 0}, {0, 3.2}, goal});                          // ambiguous
    default: return polyline({{0, 0}, {-0.8 * side, 0.75}, {0.8 * side, 1.5}, {-0.8 * side, 2.25},
                              {0.8 * side, 3.0}, goal});                        // switching
  }
}

/// A participant's trials: pads sampled at `rate` Hz over the path's duration plus 0.5 s, drawn
/// from the fit's noise model: pad = b(t) + e, e AR(1) with `phi` and innovation sd `sigma`
/// (stationary start).
inline std::vector<models::ObservedTrial> simulate_participant(const models::GoalObserver& obs, int trials,
                                                               double phi, double sigma, Rng& rng,
                                                               const std::string& id = "P1",
                                                               double rate = 25.0) {
  std::vector<models::ObservedTrial> out;
  for (int k = 0; k < trials; ++k) {
    models::ObservedTrial tr;
    tr.participant = id;
    tr.condition = "sim";
    tr.iteration = k + 1;
    const double side = rng.uniform() < 0.5 ? -1.0 : 1.0;
    tr.goal = side > 0 ? models::GoalSide::right : models::GoalSide::left;
    tr.strategy = std::to_string(k % 4);
    tr.path = shape(k % 4, side);
    const double end = tr.path.back().t + 0.5;
    for (long i = 0;; ++i) {
      const double t = static_cast<double>(i) / rate;
      if (t > end) break;
      tr.times.push_back(t);
    }
    const auto b = models::belief_trace(tr.path, tr.times, models::Goals{}, obs);
    double e = rng.normal() * sigma / std::sqrt(1 - phi * phi);
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (i > 0) e = phi * e + sigma * rng.normal();
      tr.pads.push_back(b[i] + e);
    }
    out.push_back(std::move(tr));
  }
  return out;
}

}  // namespace feint::testpaths

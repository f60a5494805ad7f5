// A participant who points on a map of K targets (see feint/sim/pointer_participant.hpp).
#include "feint/sim/pointer_participant.hpp"

#include <algorithm>
#include <cmath>

#include "feint/error.hpp"
#include "feint/models/goal_posterior.hpp"

namespace feint::sim {

metrics::Layout row_layout(std::size_t k, const Geometry& g) {
  if (k < 2) throw UsageError("--targets: a layout needs 2 or more targets");
  metrics::Layout l;
  for (std::size_t j = 0; j < k; ++j) {
    const double f = static_cast<double>(j) / static_cast<double>(k - 1);
    l.targets.push_back({-g.target_distance / 2 + f * g.target_distance, g.target_height});
  }
  return l;
}

std::vector<PointerSample> watch_pointer(const std::vector<TrajectorySample>& path, const metrics::Layout& layout,
                                         const ObserverParams& p, Rng& rng) {
  metrics::validate(layout, 0, 0);
  if (path.empty()) throw UsageError("watch_pointer: the robot's path is empty");
  const double s = metrics::layout_scale(layout);
  std::vector<models::PathSample> seen;
  std::vector<double> times;
  for (const auto& q : path) {
    seen.push_back({q.t, q.x, q.y});
    times.push_back(q.t);
  }
  const models::GoalPosteriorObserver o{p.beta, p.reaction_delay, {}};
  const auto posterior = models::posterior_trace(seen, times, layout, o);
  // The prior mean: the targets' centroid.
  PointerSample at{path.front().t, 0, 0};
  for (const auto& g : layout.targets) {
    at.x += g.x / static_cast<double>(layout.targets.size());
    at.y += g.y / static_cast<double>(layout.targets.size());
  }
  std::vector<PointerSample> out;
  out.reserve(path.size());
  double goal_x = at.x, goal_y = at.y, next_decision = path.front().t;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const double t = path[i].t;
    if (i > 0) {
      // Move toward the goal at the bounded speed, stopping on it.
      const double dx = goal_x - at.x, dy = goal_y - at.y, d = std::hypot(dx, dy);
      const double step = p.pad_speed * s * (t - at.t);
      if (d > p.move_threshold * s) {
        const double f = std::min(1.0, step / d);
        at.x += f * dx;
        at.y += f * dy;
      }
      at.t = t;
    }
    out.push_back(at);
    if (t + 1e-12 >= next_decision) {
      double mx = 0, my = 0;
      for (std::size_t k = 0; k < layout.targets.size(); ++k) {
        mx += posterior[i][k] * layout.targets[k].x;
        my += posterior[i][k] * layout.targets[k].y;
      }
      goal_x = mx + p.noise_sd * s * rng.normal();
      goal_y = my + p.noise_sd * s * rng.normal();
      next_decision += p.decision_interval;
    }
  }
  return out;
}

}  // namespace feint::sim

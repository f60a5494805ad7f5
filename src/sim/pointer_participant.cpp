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

std::vector<double> recognised_posterior(std::span<const double> posterior, std::size_t true_target,
                                         double learned) {
  // Tilt toward (learned > 0) or away from (learned < 0) the true target, scaling the side that
  // gains by 1 and the other by exp(-|learned|): no exponential overflows.
  const double damp = std::exp(-std::abs(learned));
  const double w_true = learned >= 0 ? 1.0 : damp;
  const double w_rest = learned >= 0 ? damp : 1.0;
  double rest = 0;
  for (std::size_t k = 0; k < posterior.size(); ++k)
    if (k != true_target) rest += posterior[k];
  const double norm = w_true * posterior[true_target] + w_rest * rest;
  std::vector<double> out(posterior.size());
  for (std::size_t k = 0; k < posterior.size(); ++k)
    out[k] = (k == true_target ? w_true : w_rest) * posterior[k] / norm;
  return out;
}

namespace {

// Both participants: `learning` null = the one who does not learn.
std::vector<PointerSample> pointer_trace(const std::vector<TrajectorySample>& path, const metrics::Layout& layout,
                                         const ObserverParams& p, Rng& rng, const PointerRecognition* learning) {
  metrics::validate(layout, 0, 0);
  if (path.empty()) throw UsageError("watch_pointer: the robot's path is empty");
  if (learning != nullptr && learning->true_target >= layout.targets.size())
    throw UsageError("watch_pointer: the true target is not a target of the layout");
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
  std::vector<double> recognised;
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
      const double learned =
          learning == nullptr
              ? 0.0
              : learned_logodds(p, learning->recognition, recognition_progress(p, t - path.front().t));
      // learned == 0 keeps the observer's posterior itself (the participant who does not learn).
      if (learned != 0) recognised = recognised_posterior(posterior[i], learning->true_target, learned);
      const std::vector<double>& belief = learned != 0 ? recognised : posterior[i];
      double mx = 0, my = 0;
      for (std::size_t k = 0; k < layout.targets.size(); ++k) {
        mx += belief[k] * layout.targets[k].x;
        my += belief[k] * layout.targets[k].y;
      }
      goal_x = mx + p.noise_sd * s * rng.normal();
      goal_y = my + p.noise_sd * s * rng.normal();
      next_decision += p.decision_interval;
    }
  }
  return out;
}

}  // namespace

std::vector<PointerSample> watch_pointer(const std::vector<TrajectorySample>& path, const metrics::Layout& layout,
                                         const ObserverParams& p, Rng& rng) {
  return pointer_trace(path, layout, p, rng, nullptr);
}

std::vector<PointerSample> watch_pointer(const std::vector<TrajectorySample>& path, const metrics::Layout& layout,
                                         const ObserverParams& p, Rng& rng, const PointerRecognition& learning) {
  return pointer_trace(path, layout, p, rng, &learning);
}

}  // namespace feint::sim

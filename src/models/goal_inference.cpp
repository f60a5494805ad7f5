// The goal-inference observer (feint/models/goal_inference.hpp, docs/observer.md).
#include "feint/models/goal_inference.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::models {

namespace {

double distance(Position a, Position b) noexcept { return std::hypot(a.x - b.x, a.y - b.y); }

/// 1 / (1 + exp(-z)) without overflow for any z.
double logistic(double z) noexcept {
  if (z >= 0) return 1.0 / (1.0 + std::exp(-z));
  const double e = std::exp(z);
  return e / (1.0 + e);
}

}  // namespace

void validate(const GoalObserver& o) {
  auto fail = [](const char* name, double v, const char* expected) {
    throw UsageError(fmt::format("observer parameter '{}' = {} is invalid: expected {}", name, v,
                                 expected));
  };
  if (!std::isfinite(o.beta) || o.beta < 0) fail("beta", o.beta, "a finite number >= 0 (1/m)");
  if (!std::isfinite(o.tau) || o.tau < 0) fail("tau", o.tau, "a finite delay >= 0 (s)");
  if (!std::isfinite(o.prior_right) || o.prior_right <= 0 || o.prior_right >= 1)
    fail("prior_right", o.prior_right, "a probability strictly between 0 and 1");
}

double belief_logit(Position start, Position q, const Goals& goals, double beta,
                    double prior_right) noexcept {
  // Progress toward each goal: how much the cost to go has fallen since the start.
  const double right_rise = distance(q, goals.right) - distance(start, goals.right);
  const double left_rise = distance(q, goals.left) - distance(start, goals.left);
  const double prior_logit = std::log(prior_right) - std::log1p(-prior_right);
  return prior_logit - beta * (right_rise - left_rise);
}

double belief_right(Position start, Position q, const Goals& goals, double beta,
                    double prior_right) noexcept {
  return logistic(belief_logit(start, q, goals, beta, prior_right));
}

Position position_at(std::span<const PathSample> path, double t) noexcept {
  if (t <= path.front().t) return {path.front().x, path.front().y};
  if (t >= path.back().t) return {path.back().x, path.back().y};
  // First sample strictly after t; its predecessor is at or before t.
  const auto hi = std::upper_bound(path.begin(), path.end(), t,
                                   [](double v, const PathSample& s) { return v < s.t; });
  const PathSample& b = *hi;
  const PathSample& a = *(hi - 1);
  const double span = b.t - a.t;
  if (!(span > 0)) return {b.x, b.y};
  const double w = (t - a.t) / span;
  return {a.x + w * (b.x - a.x), a.y + w * (b.y - a.y)};
}

std::vector<double> belief_trace(std::span<const PathSample> path, std::span<const double> times,
                                 const Goals& goals, const GoalObserver& observer) {
  const Position start{path.front().x, path.front().y};
  std::vector<double> out;
  out.reserve(times.size());
  for (double t : times) {
    const Position q = position_at(path, t - observer.tau);
    out.push_back(belief_right(start, q, goals, observer.beta, observer.prior_right));
  }
  return out;
}

}  // namespace feint::models

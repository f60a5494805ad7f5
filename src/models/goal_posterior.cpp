// The K-goal observer (feint/models/goal_posterior.hpp, docs/deceptive-paths.md).
#include "feint/models/goal_posterior.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "feint/error.hpp"

namespace feint::models {

namespace {

double cost_to_go(Position a, metrics::MapPoint g) noexcept {
  return std::hypot(a.x - g.x, a.y - g.y);
}

bool finite_point(metrics::MapPoint p) noexcept { return std::isfinite(p.x) && std::isfinite(p.y); }

}  // namespace

void validate(const GoalPosteriorObserver& o, std::size_t k) {
  if (!std::isfinite(o.beta) || o.beta < 0) {
    throw UsageError(
        fmt::format("observer parameter 'beta' = {} is invalid: expected a finite "
                    "number >= 0 (1/m)",
                    o.beta));
  }
  if (!std::isfinite(o.tau) || o.tau < 0) {
    throw UsageError(
        fmt::format("observer parameter 'tau' = {} is invalid: expected a finite "
                    "delay >= 0 (s)",
                    o.tau));
  }
  if (o.prior.empty()) return;
  if (o.prior.size() != k) {
    throw UsageError(
        fmt::format("observer prior has {} entries for {} targets: give one "
                    "probability per target, or none for a uniform prior",
                    o.prior.size(), k));
  }
  double sum = 0;
  for (std::size_t i = 0; i < k; ++i) {
    const double p = o.prior[i];
    if (!std::isfinite(p) || p <= 0 || p > 1) {
      throw UsageError(
          fmt::format("observer prior of target {} = {} is invalid: expected a "
                      "probability in (0, 1]",
                      i, p));
    }
    sum += p;
  }
  if (std::abs(sum - 1) > 1e-9) {
    throw UsageError(
        fmt::format("observer prior sums to {}, not 1: the K probabilities must "
                    "add up to 1",
                    sum));
  }
}

void validate_goals(const metrics::Layout& layout) {
  if (layout.targets.size() < 2) {
    throw UsageError(fmt::format("the layout has {} target(s): goal inference needs at least 2",
                                 layout.targets.size()));
  }
  if (!finite_point(layout.start)) throw UsageError("the layout's start is not finite");
  for (std::size_t k = 0; k < layout.targets.size(); ++k) {
    if (!finite_point(layout.targets[k])) {
      throw UsageError(fmt::format("target {} of the layout is not finite", k));
    }
  }
}

std::vector<double> resolved_prior(const GoalPosteriorObserver& o, std::size_t k) {
  if (!o.prior.empty()) return o.prior;
  return std::vector<double>(k, 1.0 / static_cast<double>(k));
}

namespace {

// a_k = ln P(G_k) - beta (rise_k - rise_0), rise_k = V_k(Q) - V_k(S): the log posterior up to a
// constant. Subtracting goal 0's rise (a constant for all k) keeps the terms near the log-odds, so
// at K = 2 the sum is the one belief_logit forms, to the last bits.
std::vector<double> log_weights(Position start, Position q,
                                std::span<const metrics::MapPoint> targets, double beta,
                                std::span<const double> prior) {
  const std::size_t k = targets.size();
  std::vector<double> a(k);
  const double uniform = -std::log(static_cast<double>(k));
  const double rise0 = cost_to_go(q, targets[0]) - cost_to_go(start, targets[0]);
  for (std::size_t i = 0; i < k; ++i) {
    const double rise = cost_to_go(q, targets[i]) - cost_to_go(start, targets[i]);
    a[i] = (prior.empty() ? uniform : std::log(prior[i])) - beta * (rise - rise0);
  }
  return a;
}

}  // namespace

std::vector<double> goal_log_posterior(Position start, Position q,
                                       std::span<const metrics::MapPoint> targets, double beta,
                                       std::span<const double> prior) {
  std::vector<double> a = log_weights(start, q, targets, beta, prior);
  // log-sum-exp: with the largest term subtracted every exp is in (0, 1] and one of them is 1.
  const double top = *std::max_element(a.begin(), a.end());
  double sum = 0;
  for (double v : a) sum += std::exp(v - top);
  const double log_norm = top + std::log(sum);
  for (double& v : a) v -= log_norm;
  return a;
}

std::vector<double> goal_posterior(Position start, Position q,
                                   std::span<const metrics::MapPoint> targets, double beta,
                                   std::span<const double> prior) {
  std::vector<double> p = log_weights(start, q, targets, beta, prior);
  const double top = *std::max_element(p.begin(), p.end());
  double sum = 0;
  for (double& v : p) {
    v = std::exp(v - top);  // in (0, 1]; underflows to 0 only below 1e-308 of the top goal
    sum += v;
  }
  for (double& v : p) v /= sum;
  return p;
}

std::vector<double> goal_posterior(const metrics::Layout& layout, Position q,
                                   const GoalPosteriorObserver& o) {
  validate_goals(layout);
  validate(o, layout.targets.size());
  return goal_posterior({layout.start.x, layout.start.y}, q, layout.targets, o.beta, o.prior);
}

std::vector<std::vector<double>> posterior_trace(std::span<const PathSample> path,
                                                 std::span<const double> times,
                                                 const metrics::Layout& layout,
                                                 const GoalPosteriorObserver& o) {
  validate_goals(layout);
  validate(o, layout.targets.size());
  const Position start{path.front().x, path.front().y};
  std::vector<std::vector<double>> out;
  out.reserve(times.size());
  for (double t : times) {
    const Position q = position_at(path, t - o.tau);
    out.push_back(goal_posterior(start, q, layout.targets, o.beta, o.prior));
  }
  return out;
}

double entropy_bits(std::span<const double> p) noexcept {
  double h = 0;
  for (double v : p) {
    if (v > 0) h -= v * std::log2(v);
  }
  return h;
}

}  // namespace feint::models

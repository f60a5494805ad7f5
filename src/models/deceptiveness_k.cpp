// Deceptiveness measures among K targets (feint/models/deceptiveness_k.hpp,
// docs/deceptive-paths.md).
#include "feint/models/deceptiveness_k.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "feint/error.hpp"
#include "feint/models/deceptiveness.hpp"

namespace feint::models {

namespace {

// Two targets whose probabilities differ by at most this are tied. On a line where two targets'
// costs are equal (a bisector), the two are computed with different roundings and differ by ~1e-16;
// without a tolerance a path along such a line would count as deceived, or as truthful, at random.
constexpr double kTie = 1e-12;

// Posterior of every target at every sample (no delay), S = the first sample.
std::vector<std::vector<double>> sample_posteriors(std::span<const PathSample> path,
                                                   const metrics::Layout& layout,
                                                   const GoalPosteriorObserver& o) {
  const Position start{path.front().x, path.front().y};
  std::vector<std::vector<double>> p;
  p.reserve(path.size());
  for (const auto& s : path) {
    p.push_back(goal_posterior(start, {s.x, s.y}, layout.targets, o.beta, o.prior));
  }
  return p;
}

double clamp01(double v) noexcept { return std::min(1.0, std::max(0.0, v)); }

// Share of a linear piece, s in [0, 1], on which some other target is strictly more probable than
// the true one. d_k = p_k - p* is linear on the piece; an end is deceived by k when d_k > kTie
// there, and the deceived part reaches to where d_k = 0. So each k deceives on nothing, the whole
// piece, or an interval touching one end; the union of those is [0, a) u (b, 1].
double deceived_share(const std::vector<double>& p0, const std::vector<double>& p1,
                      std::size_t star) {
  double a = 0, b = 1;
  for (std::size_t k = 0; k < p0.size(); ++k) {
    if (k == star) continue;
    const double d0 = p0[k] - p0[star], d1 = p1[k] - p1[star];
    const bool from_start = d0 > kTie, to_end = d1 > kTie;
    if (from_start && to_end) return 1;
    if (from_start)
      a = std::max(a, clamp01(d0 / (d0 - d1)));
    else if (to_end)
      b = std::min(b, clamp01(d0 / (d0 - d1)));
  }
  return a >= b ? 1 : a + (1 - b);
}

// Largest margin of another target over the true one: >= -kTie means the point is not truthful
// (another target is at least as probable, ties included).
double top_rival_margin(const std::vector<double>& p, std::size_t star) {
  double m = -2;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (k != star) m = std::max(m, p[k] - p[star]);
  }
  return m;
}

// The last point that is not truthful, as a share of the path's length: the last such sample, then
// the last s on the next piece where some d_k = p_k - p* (linear there) still reaches 0.
double last_deceptive_point(const std::vector<std::vector<double>>& p, std::size_t star,
                            const std::vector<double>& arc) {
  const std::size_t n = p.size();
  std::optional<std::size_t> last;
  for (std::size_t i = n; i-- > 0;) {
    if (top_rival_margin(p[i], star) >= -kTie) {
      last = i;
      break;
    }
  }
  if (!last) return 0;
  if (*last == n - 1) return 1;
  const std::size_t i = *last;
  double frac = 0;
  for (std::size_t k = 0; k < p[i].size(); ++k) {
    if (k == star) continue;
    const double d0 = p[i][k] - p[i][star], d1 = p[i + 1][k] - p[i + 1][star];  // d1 < -kTie
    if (d0 >= -kTie) frac = std::max(frac, clamp01(d0 / (d0 - d1)));
  }
  return (arc[i] + frac * (arc[i + 1] - arc[i])) / arc.back();
}

// Legibility (trapezoids of p* f over int f = T^2 / 2), time deceived and the mean entropy, in one
// pass over the pieces.
void measure_pieces(std::span<const PathSample> path, const std::vector<std::vector<double>>& p,
                    std::size_t star, KDeceptivenessMeasures& m) {
  const double t0 = path.front().t;
  const double T = m.duration;
  double num = 0, deceived = 0, entropy = 0;
  double h_prev = entropy_bits(p.front());
  for (std::size_t i = 1; i < path.size(); ++i) {
    const double dt = path[i].t - path[i - 1].t;
    const double f0 = T - (path[i - 1].t - t0), f1 = T - (path[i].t - t0);
    num += (p[i - 1][star] * f0 + p[i][star] * f1) / 2 * dt;
    deceived += dt * deceived_share(p[i - 1], p[i], star);
    const double h = entropy_bits(p[i]);
    entropy += (h_prev + h) / 2 * dt;
    h_prev = h;
  }
  m.legibility = num / (T * T / 2);
  m.time_deceived = deceived / T;
  m.mean_entropy = entropy / T;
}

}  // namespace

KDeceptivenessMeasures deceptiveness_k(std::span<const PathSample> path, std::size_t true_target,
                                       const metrics::Layout& layout,
                                       const GoalPosteriorObserver& observer) {
  validate_goals(layout);
  validate(observer, layout.targets.size());
  if (true_target >= layout.targets.size()) {
    throw UsageError(
        fmt::format("true target {} is out of range: the layout has {} targets (0 to {})",
                    true_target, layout.targets.size(), layout.targets.size() - 1));
  }
  validate_path(path);
  const auto arc = arc_lengths(path);

  KDeceptivenessMeasures m;
  m.duration = path.back().t - path.front().t;
  m.path_length = arc.back();
  m.straight_length = std::hypot(path.back().x - path.front().x, path.back().y - path.front().y);
  if (!(m.straight_length > 0)) {
    throw InvalidData(
        "the robot path ends where it started: the straight-line cost is 0, so the cost "
        "overhead is undefined");
  }
  m.cost_overhead = m.path_length / m.straight_length - 1;

  const auto p = sample_posteriors(path, layout, observer);
  m.final_belief = p.back()[true_target];
  measure_pieces(path, p, true_target, m);
  m.last_deceptive_point = last_deceptive_point(p, true_target, arc);
  return m;
}

}  // namespace feint::models

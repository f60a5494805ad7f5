#include "feint/metrics/belief_point.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "finite_score.hpp"
#include "time_scale.hpp"

namespace feint::metrics {

namespace detail {

// (1/L) integral_{q0}^{q1} sqrt(q^2 + h^2) dq with q1 = q0 + L, i.e.
//   [q1 r1 - q0 r0 + h^2 (asinh(q1/h) - asinh(q0/h))] / (2 L),   r = sqrt(q^2 + h^2),
// rearranged so that nothing cancels:
//   (q1 r1 - q0 r0) / L = ((r0 + r1) + (q0 + q1)^2 / (r0 + r1)) / 2      (r1 - r0 = L (q0+q1)/(r0+r1))
//   asinh(q1/h) - asinh(q0/h) = asinh(q1/h) + asinh(-q0/h)     when the foot point is inside (a sum)
//                             = asinh(L (q0 + q1) / (q1 r0 + q0 r1))  otherwise (sinh(A - B)).
// With h = 0 (a segment on a line through the origin) the first part alone is the trapezoid, or the
// two triangles when the segment passes through the origin: the 1-D error's formula.
double mean_distance_to_origin(MapPoint p0, MapPoint p1) noexcept {
  const double dx = p1.x - p0.x, dy = p1.y - p0.y;
  const double len = std::hypot(dx, dy);
  if (!(len > 0)) return std::hypot(p0.x, p0.y);  // a point that does not move
  const double ux = dx / len, uy = dy / len;
  const double q0 = p0.x * ux + p0.y * uy;  // position along the line, from the foot point
  const double q1 = q0 + len;               // (not p1 . u: q1 - q0 must be the length itself)
  const double h = std::fabs(p0.x * uy - p0.y * ux);
  const double r0 = std::hypot(q0, h), r1 = std::hypot(q1, h);
  const double qs = q0 + q1, rs = r0 + r1;
  double mean = 0.25 * (rs + qs * (qs / rs));
  if (h * h > 0) {  // else the asinh part is below the last bit (and q/h may overflow)
    const double delta = (q0 < 0 && q1 > 0) ? std::asinh(q1 / h) + std::asinh(-q0 / h)
                                            : std::asinh(len * qs / (q1 * r0 + q0 * r1));
    mean += 0.5 * h * (h * delta / len);
  }
  return mean;
}

}  // namespace detail

MapPoint pad_point(const Layout& layout, double mu) {
  if (layout.targets.size() < 2) {
    throw UsageError(fmt::format("K = {}: a pad value is a point between targets 0 and 1, so the "
                                 "layout needs at least two targets", layout.targets.size()));
  }
  const MapPoint g0 = layout.targets[0], g1 = layout.targets[1];
  return {g0.x + mu * (g1.x - g0.x), g0.y + mu * (g1.y - g0.y)};
}

namespace {

// Throws InvalidData unless the trace can be scored: as many points as times, at least 2 samples,
// finite strictly increasing times, finite points, and a true target of the layout.
void check_trace(std::span<const double> times, std::span<const MapPoint> points,
                 std::size_t k, std::size_t true_target) {
  const std::size_t n = times.size();
  if (points.size() != n) {
    throw InvalidData(fmt::format("{} times but {} belief points", n, points.size()));
  }
  if (n < 2) throw InvalidData(fmt::format("{} sample(s); a trial needs at least 2", n));
  if (true_target >= k) {
    throw InvalidData(fmt::format("true target {} is not a target of the layout (K = {}: targets "
                                  "0 to {})", true_target, k, k - 1));
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(times[i])) throw InvalidData(fmt::format("sample {}: time is not finite", i));
    if (!(std::isfinite(points[i].x) && std::isfinite(points[i].y))) {
      throw InvalidData(fmt::format("sample {}: belief point ({}, {}) is not finite", i,
                                    points[i].x, points[i].y));
    }
    if (i > 0 && !(times[i] > times[i - 1])) {
      throw InvalidData(fmt::format("sample {}: time {} is not after {} (times must strictly "
                                    "increase)", i, times[i], times[i - 1]));
    }
  }
  const double duration = times[n - 1] - times[0];
  if (!std::isfinite(duration)) {
    throw InvalidData(fmt::format("duration ({} - {} s) is not a finite number", times[n - 1],
                                  times[0]));
  }
}

// The pointer speed v (layout scales per second; the settings' overrides the trial's), checked;
// empty when unknown, which only the raw confusion allows.
std::optional<double> checked_pointer_speed(std::optional<double> pointer_speed,
                                            const MetricSettings& settings) {
  const std::optional<double> v = settings.pad_speed ? settings.pad_speed : pointer_speed;
  if (v && !(std::isfinite(*v) && *v > 0)) {
    throw InvalidData(fmt::format("pointer speed {} must be > 0 (layout scales per second)", *v));
  }
  if (settings.norm == ConfusionNorm::speed && !v) {
    throw InvalidData("the pointer speed is unknown: the 'speed' confusion normalisation needs it "
                      "(give it in layout scales per second, or use the raw normalisation)");
  }
  return v;
}

// The trace as the 1-D scorer sees its pad: times scaled as there (w = t - t0 in units of 2^-k s,
// time_scale.hpp), and points relative to the true target in layout scales (G* at the origin,
// r_i = |p_i|).
struct Trace {
  detail::ScaledTime w;  // w(i): sample i's scaled time; w.times, w.t0 and w.k
  std::vector<MapPoint> p;
};

Trace relative_trace(std::span<const double> times, std::span<const MapPoint> points,
                     MapPoint goal, double scale) {
  const double duration = times[times.size() - 1] - times[0];
  Trace tr{detail::scaled_time(times, duration), {}};
  tr.p.reserve(points.size());
  for (const MapPoint b : points) tr.p.push_back({(b.x - goal.x) / scale, (b.y - goal.y) / scale});
  return tr;
}

struct Directions {
  std::size_t rev_segment;  // the first segment against the first direction; n when none
  int reversals = 0;
  int overspeed_segments;  // -1 when v is unknown
};

// First pass (the whole trace): each segment's direction relative to the true target (the sign of
// r_{i+1} - r_i beyond eps) gives the first reversal and the reversals; the displacement per
// second gives the overspeed segments.
Directions scan_directions(const Trace& tr, double eps, std::optional<double> v) {
  const std::size_t n = tr.p.size();
  Directions out{n, 0, v ? 0 : -1};
  int first_dir = 0, last_dir = 0;
  double r_prev = std::hypot(tr.p[0].x, tr.p[0].y);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double r_next = std::hypot(tr.p[i + 1].x, tr.p[i + 1].y);
    const double d = r_next - r_prev;
    r_prev = r_next;
    const int dir = d > eps ? 1 : (d < -eps ? -1 : 0);
    if (dir != 0) {
      if (first_dir == 0) first_dir = dir;
      if (dir == -first_dir && out.rev_segment == n) out.rev_segment = i;
      if (last_dir != 0 && dir != last_dir) ++out.reversals;
      last_dir = dir;
    }
    if (v) {
      const double moved = std::hypot(tr.p[i + 1].x - tr.p[i].x, tr.p[i + 1].y - tr.p[i].y);
      if (moved / (tr.w.times[i + 1] - tr.w.times[i]) > *v * (1 + kOverspeedTolerance)) {
        ++out.overspeed_segments;
      }
    }
  }
  return out;
}

struct WindowIntegrals {
  double error = 0;   // integral of |b(t) - G*| / s over [a, b] (scaled time)
  double moving = 0;  // M (speed) or the raw sum over [c, b]
};

// Second pass, over the segments inside the window [a, b] (scaled time): the exact error integral
// (mean distance of the clipped segment times its length in time) and the time-weighted movement
// after the first reversal.
WindowIntegrals integrate_window(const Trace& tr, double a, double b, std::size_t rev_segment,
                                 ConfusionNorm norm, std::optional<double> v) {
  const std::size_t n = tr.p.size();
  auto at = [&](std::size_t i, double x) {  // b(t) at scaled time x inside segment i
    const double x0 = tr.w(i), x1 = tr.w(i + 1);
    if (x <= x0) return tr.p[i];
    if (x >= x1) return tr.p[i + 1];
    const double f = (x - x0) / (x1 - x0);
    return MapPoint{tr.p[i].x + (tr.p[i + 1].x - tr.p[i].x) * f,
                    tr.p[i].y + (tr.p[i + 1].y - tr.p[i].y) * f};
  };
  WindowIntegrals r;
  const double c = rev_segment < n ? std::max(a, tr.w(rev_segment)) : b;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double x0 = tr.w(i), x1 = tr.w(i + 1);
    if (x1 <= a) continue;
    if (x0 >= b) break;
    const double lo = std::max(x0, a), hi = std::min(x1, b);
    if (hi > lo) r.error += (hi - lo) * detail::mean_distance_to_origin(at(i, lo), at(i, hi));
    const double cs = std::max(x0, c), ce = std::min(x1, b);
    if (rev_segment < n && ce > cs) {
      const double moved = std::hypot(tr.p[i + 1].x - tr.p[i].x, tr.p[i + 1].y - tr.p[i].y);
      const double speed = moved / (tr.w.times[i + 1] - tr.w.times[i]);  // may be +inf: see below
      const double rate = norm == ConfusionNorm::speed ? std::min(1.0, speed / *v) : speed;
      r.moving += rate * (0.5 * (ce * ce - cs * cs));
    }
  }
  return r;
}

}  // namespace

BeliefPointScore score_belief_points(std::span<const double> times,
                                     std::span<const MapPoint> points, const Layout& layout,
                                     std::size_t true_target, std::optional<double> pointer_speed,
                                     const MetricSettings& settings) {
  settings.validate();
  validate(layout, 0.0, 0.0);
  check_trace(times, points, layout.targets.size(), true_target);
  const std::optional<double> v = checked_pointer_speed(pointer_speed, settings);
  const std::size_t n = times.size();
  const Trace tr = relative_trace(times, points, layout.targets[true_target],
                                  layout_scale(layout));
  const double tau = tr.w(n - 1);
  const double a = settings.trim_start * tau;
  const double b = (1 - settings.trim_end) * tau;

  BeliefPointScore s;
  s.n_samples = n;
  s.duration = times[n - 1] - times[0];
  s.final_point = points[n - 1];
  s.final_target = nearest_target(layout, points[n - 1]);
  const Directions dirs = scan_directions(tr, settings.deadband, v);
  s.reversals = dirs.reversals;
  s.overspeed_segments = dirs.overspeed_segments;
  s.reversal_time = dirs.rev_segment < n ? times[dirs.rev_segment] - tr.w.t0
                                         : std::numeric_limits<double>::quiet_NaN();
  const WindowIntegrals in = integrate_window(tr, a, b, dirs.rev_segment, settings.norm, v);
  s.error = in.error / (b - a);
  if (settings.norm == ConfusionNorm::speed) {
    // Rounding can push a mean of values in [0, 1] an ulp outside; the true value cannot be.
    s.confusion = std::clamp(in.moving / (0.5 * (b * b - a * a)), 0.0, 1.0);
  } else {
    s.confusion = std::ldexp(in.moving / tau, tr.w.k);  // 2^-k twice in w^2, once in tau
  }
  detail::reject_non_finite(s);
  return s;
}

}  // namespace feint::metrics

// feint/metrics/belief_point.hpp - error and confusion when the belief is a point on the map
// (docs/many-targets.md "Scores for a belief point").
//
// With K >= 2 targets a pad from 0 to 1 no longer says which target the participant believes in;
// the participant points at where they think the robot goes. The trial's belief is then a trace of
// points (t_i, b_i), b(t) piecewise linear between them, and the true target is G* = targets[k*].
// Distances are in layout scales s = layout_scale(layout) (the largest distance between two
// targets), the window [a, b] and the time weight w(t) = t - t0 are those of trial_metrics.hpp:
//
//   error      E = 1/(b - a) * integral_a^b |b(t) - G*| / s dt     (exact per segment: the mean of
//                                                                   sqrt(q^2 + h^2), closed form)
//   confusion  r_i = |b_i - G*| / s; segment i's direction d_i = sign(r_{i+1} - r_i) (dead band
//              eps): toward (-1) or away from (+1) the true target; t_rev = start of the first
//              segment against the first non-zero direction; counted on [c, b], c = max(a, t_rev);
//              a segment's movement is the point's displacement |b_{i+1} - b_i| / s, so a swing
//              between decoys at one distance from G* counts:
//     speed:   M / D,  M = sum m_i (w(e_i)^2 - w(s_i)^2)/2,  m_i = min(1, |db_i|/s/dt_i / v),
//              D = (w(b)^2 - w(a)^2)/2        (v: the pointer speed in layout scales per second)
//     raw:     1/tau * sum |db_i|/s/dt_i * (w(e_i)^2 - w(s_i)^2)/2
//
// On the paper's layout with b_i = pad_point(layout, mu_i) (target 0 + mu (target 1 - target 0))
// and k* = T, every score equals score_trace's for T in {0, 1} (docs/many-targets.md proves it; the
// tests check it on every trial of data/demo to 1e-12).
#pragma once

#include <cstddef>
#include <optional>
#include <span>

#include "feint/metrics/layout.hpp"
#include "feint/metrics/trial_metrics.hpp"

namespace feint::metrics {

/// One trial's scores and diagnostics, as TrialScore's for the pad.
struct BeliefPointScore {
  std::size_t n_samples = 0;
  double duration = 0;       // tau, seconds
  double error = 0;          // E, layout scales (>= 0; at most the farthest point's distance)
  double confusion = 0;      // speed: [0, 1]; raw: layout scales (unbounded)
  double reversal_time = 0;  // t_rev - t0 in seconds; NaN when the distance never reverses
  int reversals = 0;         // direction changes among the non-zero segment directions
  MapPoint final_point;      // b_{n-1}
  std::size_t final_target = 0;  // the target nearest b_{n-1} (lowest index among equals)
  /// Segments faster than v (1 + 1e-6), over the whole trace; -1 when v is unknown (raw norm).
  int overspeed_segments = 0;
};

/// The pad value `mu` as a point of the map: target 0 + mu (target 1 - target 0) (target 0 is pad
/// 0, target 1 pad 1, as in paper_layout). The layout needs two targets (UsageError otherwise).
MapPoint pad_point(const Layout& layout, double mu);

/// Scores one belief trace against `layout` with true target `true_target`. `settings` is the 1-D
/// scorer's: trimming, the dead band eps and the pad speed (overrides `pointer_speed`) are read in
/// layout scales (at K = 2 a layout scale is one pad unit); belief_deadband is not used.
/// Throws InvalidData when n < 2, the sizes differ, a time is not finite or not strictly
/// increasing, a point is not finite, true_target is not a target of the layout, v is needed but
/// unknown or not > 0, or a score is not a finite number; UsageError when the layout is invalid
/// (validate(layout, 0, 0): K < 2, a point not finite, two targets or a target and the start on one
/// spot) or a setting is out of range.
BeliefPointScore score_belief_points(std::span<const double> times,
                                     std::span<const MapPoint> points, const Layout& layout,
                                     std::size_t true_target, std::optional<double> pointer_speed,
                                     const MetricSettings& settings);

namespace detail {
/// The mean of |p(u)| over u uniform in [0, 1], p going linearly from p0 to p1: the segment's
/// distance to the origin averaged along it. Closed form (docs/many-targets.md): with q the
/// position along the segment's line measured from the origin's foot point and h the origin's
/// distance to that line, (1/L) integral sqrt(q^2 + h^2) dq, written so that nothing cancels
/// (segment through the origin, collinear with it, of zero length, or very short).
double mean_distance_to_origin(MapPoint p0, MapPoint p1) noexcept;
}  // namespace detail

}  // namespace feint::metrics

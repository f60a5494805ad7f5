// feint/sim/k_goal_paths.hpp - deceptive robot paths on a map with K >= 2 targets
// (docs/deceptive-paths.md, "Paths").
//
// The paper's four strategies, played against one decoy in the frame of the pair (true target,
// decoy): origin the start S, forward axis toward the pair's midpoint, lateral axis to its right.
// A point's frame coordinates (x, y) are its lateral and forward offsets from S. At K = 2 on the
// paper's layout this frame is the paper's own (x to the right, y up), and every path below is
// exactly sim::waypoints (tested bit for bit).
//   optimal       straight to the true target;
//   exaggerating  first to (exaggeration_x * x_d, exaggeration_y * y_d), d the decoy, then to the
//                 true target;
//   switching     zig-zag: corner j = 1..n at forward zigzag_height * F * j / n (F = distance from
//   S
//                 to the midpoint of the targets the zig-zag visits) and lateral zigzag_width * x_g
//                 / W, g the target corner j heads for: decoys at odd corners (in turn), the true
//                 target at even ones; W = the largest |x| of those targets. Then to the true
//                 target;
//   ambiguous     straight to the ambiguous point (ambiguous_point), then to the true target;
//   v2            the main path planned as if the decoy were the true target (and the true target
//                 its decoy), cut v2_turn_remaining metres before its end, then to the true target.
// Masters & Sardina (2017), with straight-line costs; t is their last deceptive point
// (masters_ldp), where the decoy g_b and the true target are equally probable; past t the path is
// truthful:
//   simulation    S -> t -> true target: the cheapest path through t. When S is no nearer the true
//                 target than g_b, g_b is at least as probable as the true target all the way to t;
//   dissimulation S -> w -> t -> true target, w the flattest point (largest posterior entropy over
//                 all K targets) of the arc of radius ambiguous_height * |t - S| around S, bearings
//                 measured from the direction of t: it hides the true target among all the others
//                 before it commits at t. w is dropped when it lies on the straight line S -> t (at
//                 K = 2 on the paper's layout both plans are S -> (0, h) -> true target).
// Every path is a polyline that starts at S and ends exactly at the true target; k_goal_trajectory
// samples it as sim::trajectory does (sample_polyline).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "feint/metrics/layout.hpp"
#include "feint/models/goal_posterior.hpp"
#include "feint/sim/selection.hpp"
#include "feint/sim/trajectory.hpp"

namespace feint::sim {

/// Masters & Sardina's (2017) two ways to deceive: show the false, or hide the real.
enum class DeceptivePlan : std::uint8_t { simulation, dissimulation };

struct KGoalPathSettings {
  /// Speed, sample rate and the strategies' shape parameters (exaggeration_x/y, zigzag_*,
  /// ambiguous_height, v2_turn_remaining); target_distance and target_height are not used (the
  /// layout places the targets) but must be valid.
  Geometry geometry;
  /// The decoy (target index). Empty: the paper's strategies use nearest_bearing_decoy, Masters &
  /// Sardina's the decoy of smallest radius of maximum probability (their g_b).
  std::optional<std::size_t> decoy;
  /// The decoys switching's odd corners head for, in turn. Empty: the decoy above, then every other
  /// decoy by nearest bearing.
  std::vector<std::size_t> switching_decoys;
  /// The observer whose posterior entropy the ambiguous and dissimulation points maximise (beta and
  /// prior; tau is not used).
  models::GoalPosteriorObserver observer;
};

/// The decoy whose direction from the start is closest to the true target's (smallest angle; ties:
/// the lower index): the one toward which a feint costs least and looks most plausible.
std::size_t nearest_bearing_decoy(const metrics::Layout& layout, std::size_t true_target);

/// The other targets ordered by that angle (ties: lower index first).
std::vector<std::size_t> decoys_by_bearing(const metrics::Layout& layout, std::size_t true_target);

/// Masters & Sardina's last deceptive point with straight-line costs. For a decoy b,
/// rmp_b = (|b G*| + |S G*| - |S b|) / 2; their g_b is the decoy of smallest rmp_b (ties: lower
/// index) unless `decoy` names one; t = G* + rmp (b - G*) / |b - G*|. At t the decoy and the true
/// target are equally probable; every point closer than rmp (the smallest over decoys) to G* is
/// truthful.
struct LastDeceptivePoint {
  std::size_t decoy = 0;  // g_b
  double radius = 0;      // rmp_{g_b} (m)
  Point point;            // t
};
LastDeceptivePoint masters_ldp(const metrics::Layout& layout, std::size_t true_target,
                               std::optional<std::size_t> decoy = {});

/// The ambiguous strategy's waypoint: on the arc of radius ambiguous_height * F around S (F = the
/// distance from S to the targets' centroid), between the bearings of the outermost targets, the
/// point where the observer's posterior has the largest entropy. Found deterministically: a grid of
/// 721 bearings (ties within 1e-12 bits: the bearing nearest the centroid's), refined by golden
/// section between the best point's neighbours (kept only when it gains more than 1e-12 bits).
Point ambiguous_point(const metrics::Layout& layout, double ambiguous_height,
                      const models::GoalPosteriorObserver& observer);

/// The waypoints (S first, the true target last) of one of the paper's strategies. Throws
/// UsageError for an invalid layout (< 2 targets, a target at the start, two targets at one point,
/// the targets' centroid at the start), geometry or observer, a target index out of range, a decoy
/// equal to the true target, or optimal with v2.
std::vector<Point> k_goal_waypoints(const metrics::Layout& layout, std::size_t true_target,
                                    Strategy s, Variant v, const KGoalPathSettings& settings = {});

/// The waypoints of Masters & Sardina's simulation or dissimulation path (checks as above; the
/// settings' decoy, when given, replaces g_b).
std::vector<Point> deceptive_waypoints(const metrics::Layout& layout, std::size_t true_target,
                                       DeceptivePlan plan, const KGoalPathSettings& settings = {});

/// The paths above sampled at the geometry's rate and speed (sample_polyline).
std::vector<TrajectorySample> k_goal_trajectory(const metrics::Layout& layout,
                                                std::size_t true_target, Strategy s, Variant v,
                                                const KGoalPathSettings& settings = {});
std::vector<TrajectorySample> deceptive_trajectory(const metrics::Layout& layout,
                                                   std::size_t true_target, DeceptivePlan plan,
                                                   const KGoalPathSettings& settings = {});

}  // namespace feint::sim

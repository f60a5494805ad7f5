// feint/sim/pointer_participant.hpp - a simulated participant who points at where the robot goes,
// on a map of K >= 2 targets (docs/simulation.md "Studies of K targets").
//
// Each round the robot follows sim::k_goal_paths for the round's strategy and true target. The
// participant's belief is the goal-inference observer over the K targets (models::goal_posterior,
// rationality `beta`, delay `reaction_delay`), shown as a point: the posterior mean of the targets,
// sum_k P(G_k | path seen tau ago) G_k. Every `decision_interval` seconds the participant picks a
// pointer goal = that point + N(0, (noise_sd s)^2) on each axis and moves the pointer toward it at
// pad_speed s metres per second while it is farther than move_threshold s, s = layout_scale (the
// pad's units become layout scales: at K = 2 one pad unit is the distance between the targets).
// The pointer starts at the prior mean (the targets' centroid, as the pad starts at 0.5).
//
// Learning (the study's participant; the pad observer's memory, sim/observer.hpp): recognition acts
// on the posterior as a change in the prior. With f_same, f_other the familiarities of
// Observer::recognition and r the recognition's progress, the true target's log prior gains
// learned = recognition_logodds r (f_same - f_other), and the posterior is renormalised:
//     P'(G_k) ∝ P(G_k | path) exp(learned [k = true]).
// At K = 2 this is the pad's rule, logit b' = logit b + learned (2T - 1), in exact arithmetic.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "feint/metrics/layout.hpp"
#include "feint/rng.hpp"
#include "feint/sim/observer.hpp"
#include "feint/sim/trajectory.hpp"

namespace feint::sim {

/// One pointer sample: time (s) and the pointer on the map (m).
struct PointerSample {
  double t = 0;
  double x = 0;
  double y = 0;
};

/// The fixed layout of K targets: evenly spaced on the paper's row, x from -d/2 to d/2 at height h
/// (target 0 the leftmost), start (0, 0). At K = 2 it is metrics::paper_layout(d, h).
metrics::Layout row_layout(std::size_t k, const Geometry& g);

/// What the learning participant knows of a round: the true target's index (the one a recognised
/// strategy is remembered to reach) and its familiarity with the strategy shown.
struct PointerRecognition {
  std::size_t true_target = 0;
  Recognition recognition;
};

/// The posterior after recognition: P'(G_k) ∝ P(G_k) exp(learned [k = true_target]), computed
/// with only exponentials of non-positive numbers (no overflow for any learned). Unchecked:
/// true_target < posterior.size().
std::vector<double> recognised_posterior(std::span<const double> posterior, std::size_t true_target,
                                         double learned);

/// The pointer trace of one round at the path's sample times, a participant who does not learn
/// (see the top of this file). Throws UsageError for an invalid layout or observer.
std::vector<PointerSample> watch_pointer(const std::vector<TrajectorySample>& path, const metrics::Layout& layout,
                                         const ObserverParams& p, Rng& rng);

/// The same for a participant who learns: each decision uses recognised_posterior with
/// learned = learned_logodds(p, learning.recognition, recognition_progress(p, t - t_start)). When
/// that is 0 (recognition_logodds 0, or nothing familiar yet) the trace is the one above, bit for
/// bit. Throws UsageError also when the true target is not a target of the layout.
std::vector<PointerSample> watch_pointer(const std::vector<TrajectorySample>& path, const metrics::Layout& layout,
                                         const ObserverParams& p, Rng& rng, const PointerRecognition& learning);

}  // namespace feint::sim

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
// The pointer starts at the prior mean (the targets' centroid, as the pad starts at 0.5). This
// participant does not learn the strategies (no memory): its belief is the observer's alone.
#pragma once

#include <cstddef>
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

/// The pointer trace of one round at the path's sample times (see the top of this file). Throws
/// UsageError for an invalid layout or observer.
std::vector<PointerSample> watch_pointer(const std::vector<TrajectorySample>& path, const metrics::Layout& layout,
                                         const ObserverParams& p, Rng& rng);

}  // namespace feint::sim

// feint/models/deceptiveness_k.hpp - how deceptive a robot path is among K >= 2 targets, measured
// with the K-goal observer of goal_posterior.hpp (docs/deceptive-paths.md, "Measures").
//
// The path xi is sampled at t_0 < ... < t_{n-1} (T = t_{n-1} - t_0); S = xi(t_0). With no delay
// (these are properties of the path), p_{k,i} = P(G_k | xi_{S->xi(t_i)}), each p_k linear in time
// between samples; k* is the true target and p* = p_{k*}.
//
//   legibility      L = int p*(t) f(t) dt / int f(t) dt, f(t) = T - (t - t_0) (Dragan & Srinivasa
//                   2013, eq. 7), trapezoids on the samples;
//   time_deceived   share of [t_0, t_0 + T] in which some other target is strictly more probable
//                   than the true one (p_k > p* for some k != k*); a tie at the top is not
//                   deceived. Exact on the piecewise-linear p_k. At K = 2 this is p* < 1/2;
//   last_deceptive_point  share of the path's length at which its last point that is not truthful
//                   lies (Masters & Sardina 2017: a point is truthful when the true target is
//                   strictly the most probable, p* > p_k for every k != k*); 0 when every point
//                   after the start is truthful, 1 when the end is not. At K = 2: the last point
//                   with p* <= 1/2;
//   cost_overhead   C(xi) / |end - S| - 1;
//   final_belief    p* at the end; mean_entropy the time-average of the posterior's entropy (bits,
//                   trapezoids on the samples): log2 K for a path that keeps every target equally
//                   likely throughout.
// Ties: at a sample, probabilities within 1e-12 of each other are equal (two equal costs computed
// with different roundings differ by ~1e-16; a path along a bisector would otherwise be deceived,
// or truthful, at random); between samples a crossing is where the linear difference p_k - p* is 0.
// At K = 2 the first five equal models::deceptiveness's (tested to 1e-14 on the paper's
// strategies).
#pragma once

#include <cstddef>
#include <span>

#include "feint/metrics/layout.hpp"
#include "feint/models/goal_inference.hpp"
#include "feint/models/goal_posterior.hpp"

namespace feint::models {

struct KDeceptivenessMeasures {
  double duration = 0;              // T (s)
  double path_length = 0;           // C(xi) (m)
  double straight_length = 0;       // |end - start| (m)
  double cost_overhead = 0;         // C / straight - 1
  double legibility = 0;            // in [0, 1]
  double time_deceived = 0;         // share of T, in [0, 1]
  double last_deceptive_point = 0;  // share of the path length, in [0, 1]
  double final_belief = 0;          // p* at the end of the path
  double mean_entropy = 0;          // bits, in [0, log2 K]
};

/// The measures above for one path whose true target is `true_target` (an index into
/// layout.targets). The posterior uses the path's first sample as S and the observer's beta and
/// prior (tau is not used: these are properties of the path). Throws UsageError for an invalid
/// observer, a layout with < 2 or non-finite targets, or `true_target` out of range; InvalidData
/// (as models::deceptiveness) for a path that cannot be measured, or one that ends where it
/// started.
KDeceptivenessMeasures deceptiveness_k(std::span<const PathSample> path, std::size_t true_target,
                                       const metrics::Layout& layout,
                                       const GoalPosteriorObserver& observer);

}  // namespace feint::models

// feint/models/deceptiveness.hpp - how deceptive a robot path is, measured with the goal-inference
// observer of goal_inference.hpp (docs/observer.md, "Deceptiveness measures").
//
// The path xi is sampled at times t_0 < ... < t_{n-1} (t_0 = start S, T = t_{n-1} - t_0 its
// duration). The observer's belief in the true goal G* is p_i = P(G* | xi_{S->xi(t_i)}) (no delay:
// these are properties of the path), a piecewise-linear function of time between samples.
//
//   legibility      L = int p(t) f(t) dt / int f(t) dt,  f(t) = T - (t - t_0)
//                   (Dragan & Srinivasa 2013, eq. 7), trapezoids on the samples;
//   time_deceived   share of [t_0, t_0 + T] with p(t) < 1/2 (the true goal is the less probable
//                   one; a tie is not deceived), exact on the piecewise-linear p;
//   last_deceptive_point  Masters & Sardina (2017): the last point of the path that is not truthful
//                   (p <= 1/2), as a fraction of the path's length; 0 when every point after the
//                   start is truthful;
//   cost_overhead   C(xi) / |G_end - S| - 1: how much longer the path is than the straight line;
//   belief_error, belief_confusion  the paper's error (eq. 3) and confusion (eq. 4) of the delayed
//                   belief trace b(t_i) = P(right | path seen up to t_i - tau), scored as if it were a
//                   pad with metrics::score_trace (trimming, reversal rule, `speed` normalisation with
//                   the stated pad speed v; a belief faster than v counts as moving at v and is
//                   reported in belief_overspeed_segments).
#pragma once

#include <span>
#include <vector>

#include "feint/metrics/trial_metrics.hpp"
#include "feint/models/goal_inference.hpp"

namespace feint::models {

/// Which goal the robot truly heads for.
enum class GoalSide { left = 0, right = 1 };

struct DeceptivenessSettings {
  GoalObserver observer;              // beta, tau (used by the belief error/confusion), prior
  Goals goals;                        // the two goals' positions
  double pad_speed = 0.8;             // v (pad units per second) for confusion's `speed` norm
  /// Trimming, dead band, norm (its pad_speed is ignored). The observer's belief is scored on the
  /// `speed` scale, [0, 1] at the pad speed above: a trajectory's deceptiveness is a property of
  /// the path, compared across paths, not a participant score tested against the paper's reference.
  metrics::MetricSettings metric = speed_scale();

  static metrics::MetricSettings speed_scale() {
    metrics::MetricSettings m;
    m.norm = metrics::ConfusionNorm::speed;
    return m;
  }
};

struct DeceptivenessMeasures {
  double duration = 0;               // T (s)
  double path_length = 0;            // C(xi) (m)
  double straight_length = 0;        // |end - start| (m)
  double cost_overhead = 0;          // C / straight - 1
  double legibility = 0;             // in [0, 1]
  double time_deceived = 0;          // share of T, in [0, 1]
  double last_deceptive_point = 0;   // share of the path length, in [0, 1]
  double final_belief = 0;           // P(G*) at the end of the path (no delay)
  double belief_error = 0;           // error of b(t) (delay tau) against the true target
  double belief_confusion = 0;       // confusion of b(t), `speed` norm with pad_speed
  int belief_overspeed_segments = 0; // segments of b(t) faster than pad_speed (clamped)
};

/// The measures above for one path whose true goal is `goal`. Throws InvalidData (a message without
/// the trial's name: callers prefix it) when the path has fewer than 2 samples, its times are not
/// strictly increasing or not finite, its duration is 0, it never moves, or it ends where it started;
/// UsageError for invalid observer parameters or pad speed.
DeceptivenessMeasures deceptiveness(std::span<const PathSample> path, GoalSide goal,
                                    const DeceptivenessSettings& settings);

/// Throws InvalidData (as above) unless `path` is a usable robot path: >= 2 samples, finite
/// strictly increasing times, a positive duration, positive length.
void validate_path(std::span<const PathSample> path);

/// Cumulative arc length at each sample (front 0).
std::vector<double> arc_lengths(std::span<const PathSample> path);

}  // namespace feint::models

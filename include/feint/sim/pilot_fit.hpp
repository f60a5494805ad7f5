// feint/sim/pilot_fit.hpp - the goal-inference participant fitted to a pilot study's scores, for
// power analysis (docs/paper-scale.md, "Power from a pilot").
//
// Method of simulated moments (McFadden 1989). Three moments of the pilot's trial error:
//   m1  the mean over iterations 1 .. from_iteration-1, both conditions (first exposures: beta);
//   m2  the mean over iterations from_iteration .. N of the adaptive condition minus that of the
//       random one (what learning does: recognition_logodds);
//   m3  the mean over iterations from_iteration .. N, both conditions.
// For each candidate (beta, recognition_logodds) a large study is simulated (common random numbers:
// the same seed at every candidate, so the distance is smooth) and the candidate minimising
// sum_k ((m_k(sim) - m_k(pilot)) / se_k)^2 wins, se_k the pilot's standard error of m_k. A coarse
// grid (beta 0.1..0.9 by 0.2, recognition 0..10 by 2) is refined twice around its best point.
// Every other parameter of the observer is taken as given.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "feint/io/scores.hpp"
#include "feint/sim/study.hpp"

namespace feint::sim {

struct PilotMoments {
  double early = 0;               ///< m1
  double later_difference = 0;    ///< m2 (adaptive - random)
  double later = 0;               ///< m3
  double se_early = 0, se_later_difference = 0, se_later = 0;  ///< the pilot's, per participant
  std::size_t adaptive = 0, random = 0;                        ///< participants per condition
};

/// The moments of a scores table (columns participant, condition, iteration and `metric`), from
/// per-participant means. Throws InvalidData naming the file when a condition is missing or has
/// fewer than 2 participants, or when no iteration lies on one side of `from_iteration`.
PilotMoments pilot_moments(const io::ScoresTable& scores, std::size_t metric_index,
                           std::string_view adaptive = "adaptive", std::string_view random = "random",
                           int from_iteration = 5);

struct PilotFit {
  ObserverParams observer;   ///< the base observer with beta and recognition_logodds fitted
  PilotMoments pilot;
  PilotMoments fitted;       ///< the simulated moments at the fitted parameters
  double distance = 0;
  int candidates = 0;        ///< simulated studies run
};

/// Fits beta and recognition_logodds of `study.observer` (study.participants participants per
/// condition are simulated for each candidate; 200 is a good size).
PilotFit fit_pilot(const PilotMoments& pilot, const StudySettings& study, int from_iteration = 5);

/// The moments of a simulated study (for the fit and its tests).
PilotMoments simulated_moments(const StudySettings& study, int from_iteration);

}  // namespace feint::sim

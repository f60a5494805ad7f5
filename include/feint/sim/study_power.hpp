// feint/sim/study_power.hpp - power of an adaptive-vs-random study, by simulating whole studies of
// goal-inference participants (docs/paper-scale.md, "Power from a pilot").
//
// For each number of participants per condition n, `studies` studies are simulated with
// simulate_participant (the observer's parameters as given, e.g. fitted to a pilot), each analysed
// as the paper's H1 in one test: every participant's mean trial error over iterations
// `from_iteration`..N, adaptive against random by Welch's t, one-sided (adaptive greater). Power is
// the share of studies with p < alpha, with its Monte Carlo standard error sqrt(P (1 - P) / studies).
//
// Every size is analysed on the same simulated people (common random numbers): study s is simulated
// once at the largest size, with the seed SplitMix64(SplitMix64(seed) xor s); its participant k of condition c
// (0 adaptive, 1 random) draws from Rng::stream(that seed, 2k + c); the study of size n is the first
// n of each condition. The work is that of the largest size alone, and the result depends on the
// seed only, not on the number of threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "feint/sim/study.hpp"

namespace feint::sim {

struct StudyPowerSettings {
  StudySettings study;              ///< participants is replaced by each value of `participants`
  std::vector<int> participants;    ///< n per condition to evaluate (each >= 2)
  std::size_t studies = 400;        ///< simulated studies per n
  std::uint64_t seed = 1;
  unsigned threads = 2;
  double alpha = 0.05;
  int from_iteration = 5;           ///< the "later iterations": from_iteration .. study.iterations
  double target_power = 0.8;
  /// Called now and then from the calling thread with the participants simulated so far and in
  /// all (for a progress line); may be empty.
  std::function<void(std::uint64_t done, std::uint64_t total)> on_progress;
};

struct StudyPowerPoint {
  int participants = 0;             ///< per condition
  double power = 0;
  double mc_se = 0;
  double mean_difference = 0;       ///< average over studies of mean(adaptive) - mean(random)
};

struct StudyPowerResult {
  StudyPowerSettings settings;
  std::vector<StudyPowerPoint> points;
  /// The smallest n of `participants` whose power reaches target_power, if any.
  std::optional<int> smallest_n_for_target;
};

/// Throws UsageError for bad settings (empty or < 2 participants, studies == 0, alpha outside
/// (0, 1), from_iteration outside 1..iterations, invalid observer or geometry).
StudyPowerResult study_power(const StudyPowerSettings& settings);

/// One simulated study's test: the one-sided Welch p and the mean difference (for tests); its
/// participant i is simulate_participant(study, i).
struct StudyTest {
  double p_value = 1;
  double difference = 0;
};
StudyTest simulate_study_test(const StudySettings& study, int from_iteration);

}  // namespace feint::sim

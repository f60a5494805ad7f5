// feint/analysis/figure_data.hpp - the data of the figures that need more than the tables: the
// strategies each participant saw (from the scores) and the mean pad traces per strategy (from the
// logs, read once by the analysis). The plot module draws these; it never reads a file.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "feint/io/trace.hpp"

namespace feint::analysis {

/// The trial-level labels of a scores file (feint score's output, or any CSV with participant,
/// iteration, strategy and optional condition and variant columns).
struct TrialLabel {
  std::string participant, condition;
  long long iteration = 0;
  std::string strategy, variant;
};
/// Throws InvalidData when the file has no participant, iteration or strategy column, or an
/// iteration that is not a whole number.
std::vector<TrialLabel> read_trial_labels(const std::string& scores_path);

struct Occurrence {
  std::vector<std::string> conditions;  ///< order of first appearance
  std::vector<long long> iterations;    ///< ascending
  std::vector<std::string> strategies;  ///< sorted
  /// counts[c][i][s]: trials of condition c at iteration i that showed strategy s.
  std::vector<std::vector<std::vector<std::size_t>>> counts;
  /// counts[c][i][s] / sum over s (0 when the iteration has no trial in c).
  double share(std::size_t c, std::size_t i, std::size_t s) const;
};
Occurrence strategy_occurrence(const std::vector<TrialLabel>& labels);

struct TraceCurve {
  std::string strategy, variant;
  bool first_exposure = true;  ///< the participant's first trial with this strategy and version
  std::size_t trials = 0;
  /// At kTracePoints equally spaced normalised times 0..1: mean of 1 - |pad - target| and its
  /// t interval at conf_level (NaN with fewer than 2 trials).
  std::vector<double> mean, conf_low, conf_high;
};
inline constexpr std::size_t kTracePoints = 101;

/// Streams the logs once (io::TraceReader with `options`; invalid trials are skipped, as
/// `feint score --on-error skip` does) and accumulates, per strategy, version and exposure, the
/// trace resampled by linear interpolation at kTracePoints normalised times
/// u = (t - t_first) / (t_last - t_first). Which trial is a first exposure comes from `labels`
/// (the scores): the lowest iteration of a (participant, condition, strategy, variant).
/// Memory is O(strategies x kTracePoints), whatever the size of the logs.
std::vector<TraceCurve> mean_traces(const std::vector<std::string>& log_files,
                                    io::TraceOptions options, const std::vector<TrialLabel>& labels,
                                    double conf_level = 0.95);

}  // namespace feint::analysis

// feint/metrics/mean_trace.hpp - figure data computed from scored trials: the trial labels of a
// scores file, and the mean pad trace per strategy, version and exposure (first exposure of a
// participant against later ones). plot/figures.hpp draws these; it reads no file itself.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "feint/io/trace.hpp"

namespace feint::metrics {

/// The trial-level labels of a scores file (feint score's output, or any CSV with participant,
/// iteration, strategy and optional condition and variant columns).
struct TrialLabel {
  std::string participant, condition;
  long long iteration = 0;
  std::string strategy, variant;
};
/// Reads the labels of a scores file. Throws InvalidData when the file has no participant,
/// iteration or strategy column, or an iteration that is not a whole number (file:line named).
std::vector<TrialLabel> read_trial_labels(const std::string& scores_path);

/// The mean trace of one strategy and version, at one exposure.
struct TraceCurve {
  std::string strategy, variant;
  bool first_exposure = true;  ///< the participant's first trial with this strategy and version
  std::size_t trials = 0;
  /// At kTracePoints equally spaced normalised times 0..1: mean of y = 1 - |pad - target| (the
  /// trace mirrored so that the true target is at 1) and its t interval at conf_level,
  /// mean -+ qt(1 - (1 - conf)/2, n - 1) sd / sqrt(n) (NaN with fewer than 2 trials). Not
  /// clipped: the figure clips its band to [0, 1].
  std::vector<double> mean, conf_low, conf_high;
};
inline constexpr std::size_t kTracePoints = 101;

/// Accumulates trials one at a time (memory O(strategies x kTracePoints), whatever the number of
/// trials): each trial's trace is resampled by linear interpolation at kTracePoints normalised
/// times u = (t - t_first) / (t_last - t_first). Which trial is a first exposure comes from
/// `labels` (the scores): the lowest iteration of a (participant, condition, strategy, variant).
class MeanTraceAccumulator {
 public:
  explicit MeanTraceAccumulator(const std::vector<TrialLabel>& labels);
  /// Adds a valid trial (times strictly increasing, size >= 2). False (and nothing added) when
  /// the trial is not in the labels (e.g. rejected when it was scored).
  bool add(const io::Trial& trial);
  /// The curves, per strategy and version (sorted), first exposure before later exposures.
  std::vector<TraceCurve> curves(double conf_level = 0.95) const;

 private:
  using Key = std::tuple<std::string, std::string, std::string, std::string>;
  struct Sums {
    std::size_t n = 0;
    std::vector<double> sum = std::vector<double>(kTracePoints, 0.0);
    std::vector<double> sumsq = std::vector<double>(kTracePoints, 0.0);
  };
  std::map<Key, long long> first_;
  std::map<std::tuple<std::string, std::string, bool>, Sums> acc_;
  std::vector<double> y_ = std::vector<double>(kTracePoints, 0.0);
};

/// The curves of already-loaded trials (a pure function).
std::vector<TraceCurve> mean_traces(const std::vector<io::Trial>& trials,
                                    const std::vector<TrialLabel>& labels,
                                    double conf_level = 0.95);

/// Streams the logs once through io::TraceReader with `options` (invalid trials are skipped, as
/// `feint score --on-error skip` does) into a MeanTraceAccumulator.
std::vector<TraceCurve> mean_traces(const std::vector<std::string>& log_files,
                                    io::TraceOptions options, const std::vector<TrialLabel>& labels,
                                    double conf_level = 0.95);

}  // namespace feint::metrics

// feint/plot/figures.hpp - the study's figures (issue #9), each in two steps: the figure's data,
// taken from the tidy results the tables already computed (no statistic is computed twice), then
// the Figure that draws them (canvas.hpp). docs/figures.md shows every figure.
//
//   metric      the paper's Fig. 9/10: mean per iteration and condition with its confidence
//               interval (one-sample Table 1), the reference line, iterations where the comparison
//               table found a difference marked (*), markers filled where the mean differs from
//               the reference (the table's labels, hence its p-value adjustment)
//   likert      the response distribution per item, diverging stacked bars centred on the neutral
//               point (Heiberger & Robbins 2014)
//   likert-means  item means with their t intervals against the reference (the paper's Fig. 11)
//   strategies  strategy occurrence per iteration by condition (the paper's Fig. 5/7, from the
//               logs' `strategy` column as carried into scores.csv)
//   participants  each participant's metric over the iterations (spaghetti, one panel per
//               condition) with the condition mean
//   traces      mean pad trace over normalised time per strategy and version, mirrored so that the
//               true target is at 1, first exposure against later exposures (needs the raw logs)
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "feint/io/scores.hpp"
#include "feint/io/trace.hpp"
#include "feint/plot/canvas.hpp"
#include "feint/report/likert.hpp"
#include "feint/report/table1.hpp"

namespace feint::plot {

// ---------------------------------------------------------------------------------------------
// Metric per iteration (Fig. 9/10)

struct MetricPoint {
  long long iteration = 0;
  double mean = 0;                     ///< the one-sample test's mean1 (NaN: no participant)
  double conf_low = 0, conf_high = 0;  ///< its interval at the table's conf_level (NaN: none)
  bool differs = false;                ///< the table's label is M>R or M<R
};

struct MetricSeries {
  std::string condition;
  std::vector<MetricPoint> points;
};

struct MetricFigureData {
  std::string metric;
  double reference = 0;
  double conf_level = 0.95;
  double alpha = 0.05;
  std::string p_adjust;              ///< the tables' adjustment ("none", "holm", ...)
  std::vector<MetricSeries> series;  ///< one per condition, the table's order
  std::string group1, group2;        ///< the comparison's conditions ("" without one)
  /// Iterations where the comparison's label is A>B or A<B (adjusted p < alpha when adjusted).
  std::vector<long long> marked;
};

/// Reads the figure's data from the one-sample Table 1 (and the two-sample one, if given).
/// Throws InvalidData when `metric` is not one of the tables' metrics.
MetricFigureData metric_figure_data(const report::Table1& one_sample,
                                    const report::Table1* comparison, const std::string& metric);
Figure metric_figure(const MetricFigureData& data);

/// The axis label of a metric with its unit ("Error (pad units)"); the name itself otherwise.
std::string metric_axis_label(const std::string& metric);

// ---------------------------------------------------------------------------------------------
// Likert (Fig. 11)

struct LikertMean {
  std::string name;                              ///< item or composite
  std::string group;                             ///< condition ("" = everybody)
  double mean = 0, conf_low = 0, conf_high = 0;  ///< the one-sample t-test's (NaN: none)
  bool differs = false;                          ///< the t-test's label is M>R or M<R
};

/// The one-sample t-test rows of a one-sample analysis, per group and name, in the table's order.
/// Throws InvalidData for a two-sample analysis (no reference to plot against).
std::vector<LikertMean> likert_means_data(const report::LikertAnalysis& analysis);
Figure likert_means_figure(const report::LikertAnalysis& analysis);

/// Percent of the answers per scale point, per group and item (composites have no distribution),
/// and each bar's start so that the neutral point is centred on 0.
struct LikertBar {
  std::string name, group;
  std::size_t n = 0;
  std::vector<double> percent;  ///< per scale point min..max; sums to 100 when n > 0
  double start = 0;             ///< -(% below neutral + half the % at neutral)
};
std::vector<LikertBar> likert_distribution_data(const report::LikertAnalysis& analysis);
Figure likert_distribution_figure(const report::LikertAnalysis& analysis);

// ---------------------------------------------------------------------------------------------
// Strategies shown (Fig. 5/7)

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
Figure occurrence_figure(const Occurrence& occurrence);

// ---------------------------------------------------------------------------------------------
// Participants

/// One panel per condition: every participant's `metric` per iteration (thin lines), and the
/// condition's mean from `one_sample` when given (the table's numbers, thick line).
Figure participants_figure(const io::ScoresTable& scores, const std::string& metric,
                           const report::Table1* one_sample);

// ---------------------------------------------------------------------------------------------
// Pad traces

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
Figure traces_figure(const std::vector<TraceCurve>& curves, double conf_level = 0.95);

}  // namespace feint::plot

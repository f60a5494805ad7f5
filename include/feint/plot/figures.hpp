// feint/plot/figures.hpp - the study's figures, each in two steps: the figure's
// data, plain structs taken from results computed upstream (the tables' tidy rows, the Likert
// analysis, metrics' mean traces and exposure trends, models' fitted trends; no statistic is
// computed twice and no file is read here), then the Figure that draws them (canvas.hpp), and a
// one- or two-sentence alt text for the report. docs/figures.md shows every figure.
//
// One colour code throughout: conditions are coloured by condition_style() in the order of their
// sorted names (R's factor order), so a condition has the same colour, line type and marker in
// every figure of a study; strategies are panels, or fills of a second palette stated in the
// legend. Axes fit the data and the metric's range (MetricRange); a reference far outside the data
// is an arrow at the plot's edge; confidence bands are clipped to the metric's range.
//
//   metric        the paper's Fig. 9/10: mean per iteration and condition with its CI band (the
//                 one-sample Table 1), the reference, iterations where the comparison differs (*)
//   participants  each participant's metric (faint), the condition means with their CI on top
//   exposure      the metric against the exposure (the times the participant has seen the
//                 strategy), one panel per strategy, with each condition's fitted slope and band
//   model         the mixed model's fitted trend with its band over the per-iteration means
//   likert        answers per item, diverging stacked bars with the answer labels
//   likert-means  item means with their t intervals against the reference (the paper's Fig. 11)
//   strategies    strategy occurrence per iteration by condition (the paper's Fig. 5/7)
//   traces        mean pad trace over normalised time per strategy and version, first exposure
//                 against later exposures
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "feint/io/scores.hpp"
#include "feint/metrics/exposure_trend.hpp"
#include "feint/metrics/mean_trace.hpp"
#include "feint/models/fitted_trend.hpp"
#include "feint/plot/canvas.hpp"
#include "feint/tables/likert.hpp"
#include "feint/tables/table1.hpp"

namespace feint::plot {

// The figures' trial data come from metrics (plot reads no file).
using metrics::TraceCurve;
using metrics::TrialLabel;

/// The range a metric can take: axes never go beyond it and bands are clipped to it.
struct MetricRange {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
};
/// [0, 1] for error (a fraction of the pad's travel); [0, inf) for confusion (unbounded above on
/// its raw scale, the default: docs/metrics.md "One scale"); unbounded otherwise.
MetricRange metric_range(const std::string& metric);

/// The axis label of a metric with its unit ("Error (pad units)"); the name itself otherwise.
std::string metric_axis_label(const std::string& metric);

/// The style of `condition` among `conditions`: condition_style() of its index in the sorted
/// names, so that its colour is the same in every figure.
Style style_of_condition(const std::vector<std::string>& conditions, const std::string& condition);

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
  MetricRange range;  ///< the band is clipped to it (the data keep the table's interval)
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
MetricFigureData metric_figure_data(const tables::Table1& one_sample,
                                    const tables::Table1* comparison, const std::string& metric);
MetricFigureData metric_figure_data(const tables::Table1& one_sample,
                                    const tables::Table1* comparison, const std::string& metric,
                                    MetricRange range);
Figure metric_figure(const MetricFigureData& data);
std::string alt_text(const MetricFigureData& data);

// ---------------------------------------------------------------------------------------------
// Participants: faint lines, the means with their CIs on top

struct ParticipantLine {
  std::string participant;
  std::vector<long long> iterations;  ///< ascending
  std::vector<double> values;         ///< NaN = missing
};
struct ParticipantsPanel {
  std::string condition;
  std::vector<ParticipantLine> participants;  ///< order of first appearance
  std::vector<MetricPoint> means;             ///< the table's (empty without one)
};
struct ParticipantsData {
  std::string metric;
  MetricRange range;
  double conf_level = 0.95;
  std::optional<double> reference;        ///< the table's reference (none without a table)
  std::vector<ParticipantsPanel> panels;  ///< one per condition, the scores' order
};
/// Throws InvalidData when `metric` is not loaded in `scores`. The range defaults to
/// metric_range(metric).
ParticipantsData participants_data(const io::ScoresTable& scores, const std::string& metric,
                                   const tables::Table1* one_sample);
ParticipantsData participants_data(const io::ScoresTable& scores, const std::string& metric,
                                   const tables::Table1* one_sample, MetricRange range);
Figure participants_figure(const ParticipantsData& data);
Figure participants_figure(const io::ScoresTable& scores, const std::string& metric,
                           const tables::Table1* one_sample);
std::string alt_text(const ParticipantsData& data);

// ---------------------------------------------------------------------------------------------
// Condition x exposure per strategy (metrics::exposure_trend)

/// One panel per strategy; per condition the fitted line with its band (clipped to `range`) and
/// the means with their intervals at the exposures with at least `min_trials` trials (fewer are
/// noise; the fit uses every trial).
Figure exposure_figure(const metrics::ExposureTrend& data, MetricRange range,
                       std::size_t min_trials = 5);
Figure exposure_figure(const metrics::ExposureTrend& data);  ///< range = metric_range(metric)
std::string alt_text(const metrics::ExposureTrend& data);

// ---------------------------------------------------------------------------------------------
// The mixed model's fitted trend over the per-iteration means

struct ModelFitFigureData {
  MetricFigureData means;  ///< the per-iteration means (points with their CI as error bars)
  /// Per condition: (iteration, fit, low, high), e.g. models::fitted_trend(fit, conf_level).
  std::vector<models::FittedTrend> trend;
  std::string model;  ///< how the model reads, for the legend, e.g. "linear trend, random slope"
};
Figure model_fit_figure(const ModelFitFigureData& data);
std::string alt_text(const ModelFitFigureData& data);

// ---------------------------------------------------------------------------------------------
// Likert (Fig. 11)

struct LikertMean {
  std::string name;                              ///< item or composite
  std::string group;                             ///< condition ("" = everybody)
  double mean = 0, conf_low = 0, conf_high = 0;  ///< the one-sample t-test's (NaN: none)
  bool differs = false;                          ///< the t-test's label is M>R or M<R
};
struct LikertMeansData {
  int scale_min = 1, scale_max = 7;
  double reference = 4;
  double conf_level = 0.95, alpha = 0.05;
  std::string p_adjust;             ///< "none", "holm", ...
  std::vector<std::string> names;   ///< items then composites, top to bottom
  std::vector<std::string> groups;  ///< conditions ("" = everybody)
  std::vector<LikertMean> means;    ///< the table's order
};
/// The one-sample t-test rows of a one-sample analysis, per group and name, in the table's order.
/// Throws InvalidData for a two-sample analysis (no reference to plot against).
LikertMeansData likert_means_data(const tables::LikertAnalysis& analysis);
Figure likert_means_figure(const LikertMeansData& data);
Figure likert_means_figure(const tables::LikertAnalysis& analysis);
std::string alt_text(const LikertMeansData& data);

/// Percent of the answers per scale point, per group and item (composites have no distribution),
/// and each bar's start so that the neutral point is centred on 0.
struct LikertBar {
  std::string name, group;
  std::size_t n = 0;
  std::vector<double> percent;  ///< per scale point min..max; sums to 100 when n > 0
  double start = 0;             ///< -(% below neutral + half the % at neutral)
};
struct LikertDistribution {
  int scale_min = 1, scale_max = 7;
  double neutral = 4;
  /// Per scale point min..max: the questionnaire's label map (first label of each value), else
  /// the built-in agree/disagree labels for 5 and 7 points, else the number itself.
  std::vector<std::string> answer_labels;
  std::vector<std::string> groups;  ///< conditions ("" = everybody)
  std::vector<LikertBar> bars;
};
LikertDistribution likert_distribution_data(const tables::LikertAnalysis& analysis);
Figure likert_distribution_figure(const LikertDistribution& data);
Figure likert_distribution_figure(const tables::LikertAnalysis& analysis);
std::string alt_text(const LikertDistribution& data);

// ---------------------------------------------------------------------------------------------
// Strategies shown (Fig. 5/7)

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
std::string alt_text(const Occurrence& occurrence);

// ---------------------------------------------------------------------------------------------
// Pad traces (metrics::mean_traces)

struct TracesFigureData {
  std::vector<TraceCurve> curves;
  double conf_level = 0.95;
};
Figure traces_figure(const std::vector<TraceCurve>& curves, double conf_level = 0.95);
std::string alt_text(const TracesFigureData& data);

}  // namespace feint::plot

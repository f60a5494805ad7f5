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

#include "feint/analysis/figure_data.hpp"
#include "feint/io/scores.hpp"
#include "feint/plot/canvas.hpp"
#include "feint/report/likert.hpp"
#include "feint/report/table1.hpp"

namespace feint::plot {

// The figure data that the analysis computes from the scored trials (feint/analysis/figure_data.hpp);
// the figures below only draw it.
using analysis::kTracePoints;
using analysis::mean_traces;
using analysis::Occurrence;
using analysis::read_trial_labels;
using analysis::strategy_occurrence;
using analysis::TraceCurve;
using analysis::TrialLabel;

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

Figure occurrence_figure(const Occurrence& occurrence);

// ---------------------------------------------------------------------------------------------
// Participants

/// One panel per condition: every participant's `metric` per iteration (thin lines), and the
/// condition's mean from `one_sample` when given (the table's numbers, thick line).
Figure participants_figure(const io::ScoresTable& scores, const std::string& metric,
                           const report::Table1* one_sample);

// ---------------------------------------------------------------------------------------------
// Pad traces

Figure traces_figure(const std::vector<TraceCurve>& curves, double conf_level = 0.95);

}  // namespace feint::plot

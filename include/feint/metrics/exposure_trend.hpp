// feint/metrics/exposure_trend.hpp - the data of the condition x exposure figure: a metric against
// the number of times the participant has seen the trial's strategy (the wear-off of a strategy),
// per strategy and condition, with a fitted exposure slope per condition.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "feint/io/scores.hpp"
#include "feint/metrics/mean_trace.hpp"

namespace feint::metrics {

/// The mean of the metric over the trials at one exposure (1 = the participant's first trial with
/// the strategy), with its t interval mean -+ qt(1 - (1 - conf)/2, n - 1) sd / sqrt(n) (NaN with
/// fewer than 2 trials).
struct ExposurePoint {
  long long exposure = 1;
  std::size_t n = 0;
  double mean = 0, conf_low = 0, conf_high = 0;
};

/// The least-squares line y = intercept + slope * exposure through the condition's trials of one
/// strategy, with intervals that respect that a participant contributes several trials: the
/// participant-clustered sandwich covariance V = c (X'X)^-1 [sum_g X_g' e_g e_g' X_g] (X'X)^-1
/// with X = [1, exposure], e the residuals, g the participants, the small-sample factor
/// c = G/(G-1) (N-1)/(N-2) (CR1, as Stata's `regress, vce(cluster)`), and t quantiles with G - 1
/// df (Cameron & Miller 2015, "A practitioner's guide to cluster-robust inference"). The band at
/// exposure x is fit -+ qt(1 - (1 - conf)/2, G - 1) sqrt(a' V a), a = (1, x); the slope's interval
/// is slope -+ qt(...) sqrt(V_11). Descriptive: the mixed model of `feint model --exposure` is
/// the inference. `fitted` is false with fewer than 3 trials, fewer than 2 participants or a
/// single exposure value.
struct ExposureFit {
  bool fitted = false;
  std::size_t n = 0;             ///< trials
  std::size_t participants = 0;  ///< clusters
  double intercept = 0, slope = 0, slope_low = 0, slope_high = 0;
  std::vector<double> exposure, fit, low, high;  ///< the band, at each observed exposure
};

struct ExposureSeries {
  std::string condition;
  std::vector<ExposurePoint> points;  ///< ascending exposure
  ExposureFit fit;
};

struct ExposureStrategy {
  std::string strategy;                ///< "(none)" for an empty strategy label
  std::vector<ExposureSeries> series;  ///< one per condition (ExposureTrend::conditions' order)
};

struct ExposureTrend {
  std::string metric;
  double conf_level = 0.95;
  std::vector<std::string> conditions;       ///< the scores' order
  std::vector<ExposureStrategy> strategies;  ///< sorted
  std::size_t unmatched = 0;                 ///< scored trials without a label (left out)
};

/// Joins the scores with the trial labels by (participant, condition, iteration). A trial's
/// exposure is 1 + the number of the participant's earlier iterations (in the labels) with the
/// same strategy, whether or not their metric is missing (models::exposure_counts + 1). Trials with
/// a missing metric are left out of the means and fits. Throws InvalidData when `metric` is not
/// one of the scores' metrics.
ExposureTrend exposure_trend(const io::ScoresTable& scores, const std::vector<TrialLabel>& labels,
                             const std::string& metric, double conf_level = 0.95);

}  // namespace feint::metrics

// feint/models/exposure.hpp - how often a participant had already seen a trial's strategy.
#pragma once

#include <span>
#include <string>
#include <vector>

namespace feint::models {

/// For each trial i, the number of earlier trials (smaller iteration) of the same participant with
/// the same strategy: 0 at a participant's first exposure to a strategy, 1 at the second, ...
/// Trials are counted whether or not their metric is missing (seeing a strategy is the exposure,
/// not scoring it). Equal iterations of one participant (a participant in two conditions) throw
/// InvalidData that says so. In R: ave(seq_along(s), participant, strategy,
/// FUN = seq_along) - 1 after sorting by participant and iteration.
std::vector<double> exposure_counts(std::span<const std::string> participant,
                                    std::span<const double> iteration,
                                    std::span<const std::string> strategy);

}  // namespace feint::models

#include <cstddef>

#include "feint/stats/bayes_factor.hpp"
#include "feint/stats/htest.hpp"

namespace feint::models {

/// An exposure slope (change of the metric per earlier exposure to the strategy) of one strategy in
/// one condition, or the difference of a strategy's slopes between two conditions.
struct ExposureSlope {
  std::string strategy;
  std::string condition;  ///< a condition, or "A-B" for a difference
  stats::TestResult test;  ///< "one_sample_t" (slope) or "welch_t" (difference, with its Bayes factor)
  double std_error = 0;    ///< SE of the estimate: sd / sqrt(n), or sqrt(sd1^2/n1 + sd2^2/n2)
  std::size_t participants = 0;  ///< participants with a slope (both conditions for a difference)
  std::size_t left_out = 0;      ///< participants with trials of the strategy but no slope
};

/// Condition x exposure per strategy, by the participant-level two-stage ("slopes as
/// outcomes") method, valid whenever participants are independent, whatever the within-participant
/// variance or correlation:
///  stage 1: for each participant and strategy, the OLS slope of y on exposure over that
///    participant's trials of that strategy with a finite y; a participant contributes to a strategy
///    only with >= 2 such trials at >= 2 distinct exposures (the others are counted in `left_out`
///    and named in the note);
///  stage 2, per condition: the strategy's slope = the mean of the participants' slopes, one-sample
///    t test against 0 with its t CI (df = n - 1); the difference (first condition minus second) =
///    Welch two-sample t test on the participants' slopes (stats::t_test_welch: CI, Cohen's d with
///    its CI) with the JZS Bayes factor (stats::add_bayes_factor, prior scale `bf_prior_r`).
/// `paired` (conditions within participants): the difference is the paired t test on the slopes of
/// the participants with a slope in both conditions (stats::t_test_paired: CI, d_z with its CI, the
/// one-sample JZS Bayes factor); the others are counted in `left_out`. Each participant's exposure
/// is then counted within each condition's block (docs/analysis.md, "Exposure within participants").
/// Fewer than 2 participants with a slope give results that are not computable, with the reason in
/// the note (never a throw). Golden: tests/golden/models/exposure_by_condition_golden.R (lm() per
/// participant x strategy, t.test()). `conditions` gives the two conditions in order (empty: sorted).
struct ExposureByCondition {
  std::vector<ExposureSlope> slopes;       ///< condition-major, strategies sorted
  std::vector<ExposureSlope> differences;  ///< one per strategy (empty with fewer than 2 conditions)
};
ExposureByCondition exposure_slopes_by_condition(std::span<const std::string> participant,
                                                 std::span<const std::string> condition,
                                                 std::span<const std::string> strategy,
                                                 std::span<const double> exposure,
                                                 std::span<const double> y,
                                                 std::vector<std::string> conditions = {},
                                                 double conf_level = 0.95,
                                                 double bf_prior_r = stats::kJzsMediumScale,
                                                 bool paired = false);

}  // namespace feint::models

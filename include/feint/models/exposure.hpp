// feint/models/exposure.hpp - how often a participant had already seen a trial's strategy.
#pragma once

#include <span>
#include <string>
#include <vector>

namespace feint::models {

/// For each trial i, the number of earlier trials (smaller iteration) of the same participant with
/// the same strategy: 0 at a participant's first exposure to a strategy, 1 at the second, ...
/// Trials are counted whether or not their metric is missing (seeing a strategy is the exposure,
/// not scoring it). Equal iterations of one participant throw std::invalid_argument (the scores
/// loader already rejects duplicate keys). In R: ave(seq_along(s), participant, strategy,
/// FUN = seq_along) - 1 after sorting by participant and iteration.
std::vector<double> exposure_counts(std::span<const std::string> participant,
                                    std::span<const double> iteration,
                                    std::span<const std::string> strategy);

}  // namespace feint::models

#include "feint/stats/htest.hpp"

namespace feint::models {

/// An exposure slope (change of the metric per earlier exposure to the strategy) of one strategy in
/// one condition, or the difference of a strategy's slopes between two conditions.
struct ExposureSlope {
  std::string strategy;
  std::string condition;  ///< a condition, or "A-B" for a difference
  stats::TestResult test;  ///< test "lmm_contrast" (slope) or "slope_difference"
  double std_error = 0;
};

/// Condition x exposure per strategy (issue 15): in each condition separately, the mixed model
/// y ~ strategy * exposure + (1 | participant) (REML; lmer) and each strategy's exposure slope by
/// lmerTest::contest1D (Satterthwaite df). Conditions are between participants, so the fits are
/// independent and the difference of a strategy's slopes (first condition minus second) has
/// SE = sqrt(SE1^2 + SE2^2) and Welch–Satterthwaite df (SE1^2 + SE2^2)^2 / (SE1^4/df1 + SE2^4/df2).
/// Golden: tests/golden/models/exposure_by_condition_golden.R. `conditions` gives the two
/// conditions in order (empty: sorted). A condition whose model cannot be fitted gives slopes that
/// are not computable, with the reason in the note (never a throw).
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
                                                 double conf_level = 0.95);

}  // namespace feint::models

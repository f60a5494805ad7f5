// exposure_findings.hpp - H1's condition x exposure findings (private to the analysis module;
// docs/analysis.md "Exposure").
#pragma once

#include <vector>

#include "feint/analysis/findings.hpp"
#include "feint/analysis/results.hpp"

namespace feint::analysis::detail {

/// H1, condition x exposure per strategy and metric ("H1-exposure-METRIC"): needs each trial's
/// strategy (the logs' labels). With three or more conditions and no pair named, one "not
/// computable" finding per metric says to name the pair.
void add_exposure_findings(std::vector<Finding>& out, const StudyResults& r,
                           const std::vector<tables::MetricSpec>& metrics, const WordingRules& rules);

}  // namespace feint::analysis::detail

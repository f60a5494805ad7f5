// observer_stage.hpp - the goal-inference observer in `feint analyze` (private to the analysis
// module; docs/analysis.md "The observer's parameters compared"): each participant's beta and tau
// fitted to the pad traces, the compared conditions' fits compared, and the findings on them.
#pragma once

#include <string>
#include <vector>

#include "feint/analysis/findings.hpp"
#include "feint/analysis/results.hpp"
#include "feint/io/trace.hpp"

namespace feint::analysis::detail {

/// Fits the observer to each participant's pad traces in each condition (models::fit_study through
/// sim::fit_observer_to_logs, the logs read with `reading`, the scorer's options; no learning test)
/// and compares the compared pair's fits (models::compare_conditions: Welch t and Mann-Whitney
/// between participants, paired t and Wilcoxon signed-rank within). Fills r.observer, or
/// r.observer_note with why there is none. Nothing for pointer logs (their fit is `feint observer
/// fit`'s) or when no pair is compared.
void fit_observer_stage(const std::vector<std::string>& logs, const io::TraceOptions& reading, StudyResults& r);

/// "observer-beta" and "observer-tau" (exploratory): which way, how much and how sure the compared
/// conditions differ in the fitted log beta and tau; one "not computable" finding with the reason
/// when the fit could not be made.
std::vector<Finding> observer_findings(const StudyResults& r, const WordingRules& rules);

}  // namespace feint::analysis::detail

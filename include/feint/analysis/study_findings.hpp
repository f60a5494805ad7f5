// feint/analysis/study_findings.hpp - the findings of a whole study, from its StudyResults.
#pragma once

#include <vector>

#include "feint/analysis/findings.hpp"
#include "feint/analysis/results.hpp"
#include "feint/report/table1.hpp"

namespace feint::analysis {

/// H1: per metric, the Holm-corrected family of per-iteration contrasts between the conditions (the
/// comparison table), or "only one condition" when there is none to compare; a reference-outside-
/// the-data warning per metric (check_reference over every participant and iteration).
/// H2: per Likert item and composite, the t test against the reference and between the conditions.
/// Wording rules: docs/findings.md.
std::vector<Finding> study_findings(const StudyResults& results,
                                    const std::vector<report::MetricSpec>& metrics,
                                    const WordingRules& rules = {});

}  // namespace feint::analysis

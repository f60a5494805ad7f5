// questionnaire_findings.hpp - the findings of H2: the questionnaire against its reference and
// between (or across) the conditions, and the yes/no questions (private to the analysis module).
#pragma once

#include <vector>

#include "feint/analysis/findings.hpp"
#include "feint/analysis/results.hpp"

namespace feint::analysis::detail {

/// H2 after every H1 finding: the Likert items against the reference, between the two compared
/// conditions (paired within participants), across three or more (the omnibus test, then the
/// protected pairs), then the yes/no questions (docs/findings.md "Questionnaire").
void add_questionnaire_findings(std::vector<Finding>& out, const StudyResults& r, const WordingRules& rules);

}  // namespace feint::analysis::detail

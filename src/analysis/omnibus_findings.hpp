// omnibus_findings.hpp - the per-iteration omnibus family of three or more conditions as an H1
// finding (private to the analysis module; docs/findings.md "Three or more conditions: the maxF
// family").
#pragma once

#include <optional>
#include <string>

#include "feint/analysis/findings.hpp"
#include "feint/analysis/results.hpp"

namespace feint::analysis::detail {

/// H1 "H1-iterations-<metric>" of a study of three or more conditions with no pair named: the
/// primary omnibus tests of Table 1's conditions table (Welch's F between participants, the
/// Greenhouse–Geisser repeated-measures F within) over the iterations as one family, adjusted by
/// the table's step-down maxF (OmnibusRow::p_maxf), or by Holm with a warning where the family has
/// a note. The sentence names the conditions highest and lowest at the iterations with evidence (all
/// iterations when none has), and the member with the smallest adjusted p with its F and effect
/// size (ω² of the one-way ANOVA between, generalized η² within, with their one-sided intervals).
/// nullopt when the results hold no conditions table or the metric is not in it.
std::optional<Finding> omnibus_iteration_finding(const StudyResults& r, const std::string& metric,
                                                 const WordingRules& rules);

}  // namespace feint::analysis::detail

// report_details.hpp - the parts of the study report that must agree with the rest of it: the
// tests' statistics under the paper-shaped tables, the reference check, what the findings left out,
// and whether the study has the seed paper's design (private to the publish module).
#pragma once

#include <string>
#include <vector>

#include "feint/analysis/results.hpp"

namespace feint::publish::detail {

/// Every test of a Table 1 (one-sample or the comparison) in APA style, as the CSV and tables::
/// apa_string give them (t, df, p, d with its CI, BF), folded in a <details> under the table.
std::string tests_html(const tables::Table1& table, bool comparison);

/// The questionnaire's tests with their effect sizes: the rank test with its rank-biserial r and
/// CI, the t test with its d and CI and the Bayes factor, in a <details>.
std::string likert_tests_html(const tables::LikertAnalysis& likert);

/// "error against 0.5; confusion against 0.95 on the raw scale": each reference with its scale
/// (the reference's own, else the scores', which load refused to differ).
std::string references_text(const analysis::StudyResults& r);

/// The Accounting's reference check: the scores' scale and each reference's, said once.
std::string reference_check_line(const analysis::StudyResults& r);

/// What the findings left out of an analysis (their warnings that say so), each once.
std::vector<std::string> left_out_lines(const analysis::StudyResults& r);

/// Findings carrying a warning that is not about data left out (for the Accounting's count).
std::size_t other_warned_findings(const analysis::StudyResults& r);

/// True when the study has the seed paper's design: two conditions compared, each participant in
/// one of them (between participants), and the paper's 20 iterations (1 to 20).
bool paper_design(const analysis::StudyResults& r);

/// The model tables' "Singular fit: ..." notes made to name their metric ("Singular fit of the
/// confusion model: ..."), in the order the models are rendered.
std::string name_singular_notes(std::string text, const tables::ModelAnalysis& model);

}  // namespace feint::publish::detail

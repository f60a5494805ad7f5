// feint/tables/yes_no.hpp - the questionnaire's yes/no questions (questionnaire_yesno.csv, written
// by `feint collect`: participant, condition, one column per question with yes / no).
//
// Per question and condition: the proportion of "yes" with its exact (Clopper–Pearson) and Wilson
// intervals. Between two conditions: Fisher's exact test (primary: exact at any size) with the
// conditional maximum-likelihood odds ratio and its interval, and beside it the chi-square test of
// two proportions with the difference p_A - p_B and its interval (R's prop.test, Yates-corrected).
// Within participants (`paired`): McNemar's exact test with the conditional odds ratio, and R's
// mcnemar.test beside it (feint/stats/paired_proportions.hpp).
// Three or more conditions and no pair named (`across_conditions`): per question the omnibus test,
// Fisher's exact test of the C x 2 table (primary) and Pearson's chi-square test with Cramér's V
// beside it (feint/stats/contingency.hpp), within participants Cochran's Q; then every pair of
// conditions compared as two are, Holm-adjusted over the pairs and protected by the omnibus test.
// docs/yes-no.md has the formulas and worked examples.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "feint/io/questionnaire.hpp"
#include "feint/stats/htest.hpp"
#include "feint/stats/proportions.hpp"
#include "feint/tables/tidy.hpp"
#include "feint/tables/writers.hpp"

namespace feint::tables {

/// The loader's options for yes/no answers: scale 0–1 with the labels yes/no, y/n, true/false
/// (any case); 1 and 0 are read as numbers.
io::QuestionnaireOptions yes_no_load_options();

struct YesNoSettings {
  io::QuestionnaireOptions load = yes_no_load_options();  ///< columns, items, delimiter
  std::optional<std::pair<std::string, std::string>> compare;  ///< (A, B); none = describe only
  /// With `compare`: within participants (each answered after each condition). Each participant's
  /// answer in A is paired with theirs in B: McNemar's exact test (binomial on the discordant pairs,
  /// primary) with the conditional odds ratio b/c, and R's mcnemar.test beside it; participants
  /// without both answers are left out (named in a note).
  bool paired = false;
  /// Without `compare`, three or more conditions are compared together: the omnibus test per
  /// question, then every pair (Holm over the pairs, protected by the omnibus test); within
  /// participants when `paired`. false: described per condition only.
  bool across_conditions = true;
  stats::TestOptions test;  ///< alternative, conf_level
  double alpha = 0.05;
};

/// One question in one condition.
struct YesNoSummary {
  std::string question;
  std::string group;  ///< condition ("" = no condition column)
  stats::Proportion proportion;
  std::size_t missing = 0;  ///< respondents of the group without an answer to this question
};

struct YesNoAnalysis {
  YesNoSettings settings;
  std::string source;
  std::vector<std::string> questions;
  std::vector<std::string> groups;        ///< conditions in file order ("" = none)
  std::vector<YesNoSummary> summaries;    ///< per question, per group
  /// Two conditions compared: per question Fisher's exact test, then the chi-square test (paired:
  /// McNemar's exact test, then mcnemar.test). Across three or more conditions: per question, per
  /// pair (i < j in file order) the same two rows, with p_adjusted Holm over the question's pairs
  /// (per test) and labels protected by the question's omnibus test.
  std::vector<TidyRow> rows;
  /// Across three or more conditions: the conditions compared (file order); empty otherwise.
  std::vector<std::string> compared;
  /// Across three or more conditions, per question: Fisher's exact test of the C x 2 table
  /// (test "fisher_exact_conditions", primary), then Pearson's chi-square test ("chisq_test") whose
  /// estimate, conf_low and conf_high are the bias-corrected Cramér's V and its one-sided interval;
  /// within participants Cochran's Q ("cochran_q") alone. group1 = the conditions joined by ", ".
  std::vector<TidyRow> omnibus;
  std::vector<std::string> notes;
};

/// Throws UsageError when `settings.compare` names a condition the answers do not have, or
/// InvalidData when the two compared conditions share a participant (not paired) or, paired, a
/// participant answered twice in one condition. Across three or more conditions the same problems
/// are said in a note instead and the conditions are described only (so that a study's analysis
/// goes on).
YesNoAnalysis analyze_yes_no(const io::Questionnaire& answers, const YesNoSettings& settings);

/// Loads `path` with settings.load and analyses it.
YesNoAnalysis analyze_yes_no_file(const std::string& path, const YesNoSettings& settings);

/// text / markdown / latex: one row per question and condition (yes, n, %, both intervals), the
/// comparison rows (across three or more conditions: the omnibus table, then the pairs) and the
/// notes; csv / json: per question and condition the proportion and its intervals, then the tidy
/// test rows (kTableColumns; the omnibus rows first).
std::string render_yes_no(const YesNoAnalysis& analysis, OutputFormat format);

}  // namespace feint::tables

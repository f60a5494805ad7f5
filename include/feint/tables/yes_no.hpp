// feint/tables/yes_no.hpp - the questionnaire's yes/no questions (questionnaire_yesno.csv, written
// by `feint collect`: participant, condition, one column per question with yes / no).
//
// Per question and condition: the proportion of "yes" with its exact (Clopper–Pearson) and Wilson
// intervals. Between two conditions: Fisher's exact test (primary: exact at any size) with the
// conditional maximum-likelihood odds ratio and its interval, and beside it the chi-square test of
// two proportions with the difference p_A - p_B and its interval (R's prop.test, Yates-corrected).
// Within participants (`paired`): McNemar's exact test with the conditional odds ratio, and R's
// mcnemar.test beside it (feint/stats/paired_proportions.hpp).
// docs/yes-no.md has the formulas and a worked example.
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
  /// Two conditions compared: per question Fisher's exact test, then the chi-square test.
  std::vector<TidyRow> rows;
  std::vector<std::string> notes;
};

/// Throws UsageError when `settings.compare` names a condition the answers do not have, or
/// InvalidData when the two compared conditions share a participant (not paired) or, paired, a
/// participant answered twice in one condition.
YesNoAnalysis analyze_yes_no(const io::Questionnaire& answers, const YesNoSettings& settings);

/// Loads `path` with settings.load and analyses it.
YesNoAnalysis analyze_yes_no_file(const std::string& path, const YesNoSettings& settings);

/// text / markdown / latex: one row per question and condition (yes, n, %, both intervals), the
/// comparison rows and the note; csv / json: per question and condition the proportion and its
/// intervals, then the tidy test rows (kTableColumns).
std::string render_yes_no(const YesNoAnalysis& analysis, OutputFormat format);

}  // namespace feint::tables

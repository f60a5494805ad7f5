// feint/tables/likert_conditions.hpp - a questionnaire compared across three or more conditions
// between participants (docs/likert.md "Three or more conditions").
//
// Per item and composite scale: first the omnibus test, Kruskal-Wallis (R's kruskal.test(y ~ g),
// tie-corrected) with the rank epsilon squared E^2_R = H / (n - 1) (Tomczak & Tomczak 2014; R's
// effectsize::rank_epsilon_squared); then every pair of conditions as `feint likert --compare A,B`
// compares two (Mann-Whitney U with the rank-biserial r, primary; Welch's t with Cohen's d and the
// JZS Bayes factor beside it), Holm-adjusted over the pairs of that item (R's
// pairwise.wilcox.test(y, g, p.adjust.method = "holm") for the Mann-Whitney p-values). The pairs
// are read only after the omnibus test: a pair is labelled as differing only when its item's
// Kruskal-Wallis test is significant at alpha (protected, as Fisher's LSD protects its pairs).
//
// Within participants (settings.paired: each participant answered after each condition), the
// omnibus test is Friedman's (R's friedman.test(y ~ condition | participant) on the participants who
// answered in every condition) with Kendall's W (R's effectsize::kendalls_w), and each pair is
// compared paired (Wilcoxon signed-rank on the differences with the matched-pairs r, primary; the
// paired t with d_z and the JZS Bayes factor beside it), Holm over the pairs and protected as above.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "feint/io/questionnaire.hpp"
#include "feint/tables/likert.hpp"
#include "feint/tables/tidy.hpp"
#include "feint/tables/writers.hpp"

namespace feint::tables {

struct LikertConditions {
  LikertSettings settings;
  std::string source;
  std::vector<std::string> conditions;  ///< in the questionnaire's order
  std::vector<std::string> names;       ///< items, then composites
  bool paired = false;  ///< within participants (settings.paired): Friedman and paired pairs
  /// Per name: the Kruskal-Wallis test, or Friedman's within participants (group1 = the conditions
  /// joined by ", ", group2 empty).
  std::vector<TidyRow> omnibus;
  /// Per name, within participants: Kendall's W of the Friedman test (empty between).
  std::vector<std::optional<double>> kendalls_w;
  /// Per pair (i < j in the conditions' order): the two-condition analysis, whose p_adjusted is
  /// Holm over the pairs of each name and whose labels are protected by the omnibus test.
  std::vector<LikertAnalysis> pairs;
  std::vector<std::string> notes;
};

/// The analysis above. Throws UsageError when the questionnaire has no condition column or fewer
/// than two conditions, InvalidData when a participant answered in two conditions (the tests
/// compare independent groups; settings.paired compares them within participants instead).
LikertConditions analyze_likert_conditions(const io::Questionnaire& questionnaire, const LikertSettings& settings);

/// text / markdown / latex: the omnibus table and the pairs table with the note; csv / json: the
/// tidy rows (omnibus rows, then each pair's rows) with likert_columns(settings.apa).
std::string render_likert_conditions(const LikertConditions& analysis, OutputFormat format);

}  // namespace feint::tables

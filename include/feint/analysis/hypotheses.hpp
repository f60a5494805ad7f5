// feint/analysis/hypotheses.hpp - the study's hypotheses: what it was run to answer.
//
// A hypothesis names, in words, a comparison of the study's two conditions (A and B of `compare`),
// the measures it is answered on, the expected direction and whether it was preregistered
// (confirmatory). feint.toml declares them in [hypotheses]; without that, the paper's H1 and H2
// (docs/findings.md "Hypotheses").
#pragma once

#include <string>
#include <vector>

namespace feint::analysis {

struct Hypothesis {
  std::string id;         ///< "H1", "H2", ... (the findings' `hypothesis`)
  std::string statement;  ///< the hypothesis in words, as a paper states it
  /// What it is answered on: "error", "confusion" (the per-trial metrics), "questionnaire".
  std::vector<std::string> measures;
  /// The expected direction of A relative to B: "greater", "less" or "two-sided".
  std::string direction = "two-sided";
  bool confirmatory = false;  ///< declared before the data (preregistered); else exploratory
  /// The two conditions it compares, A then B, when it is about a pair (default_hypotheses(a, b));
  /// empty when it is about all of the study's conditions. The Results text's headline of a
  /// measure is then that pair's comparison, never another pair's or the test across all.
  std::vector<std::string> pair;
};

/// The paper's hypotheses for conditions A and B: H1 (A deceives longer than B: higher error and
/// confusion) and H2 (the questionnaire differs between A and B). Exploratory unless declared.
std::vector<Hypothesis> default_hypotheses(const std::string& a, const std::string& b);

/// Three or more conditions compared together (no pair named): H1 (error and confusion differ
/// among them) and H2 (the questionnaire answers differ among them), both two-sided.
std::vector<Hypothesis> default_hypotheses(const std::vector<std::string>& conditions);

/// The study's hypotheses: `defaults` changed and added to by `ID:KEY=VALUE` settings, as below.
std::vector<Hypothesis> parse_hypotheses(const std::vector<std::string>& settings, std::vector<Hypothesis> defaults);

/// The study's hypotheses: the defaults, changed and added to by `ID:KEY=VALUE` settings (feint.toml
/// `[hypotheses.ID]` tables, `--hypothesis` on the command line). KEY is statement, measures (a
/// comma-separated list of error, confusion, questionnaire), direction (greater, less, two-sided)
/// or confirmatory (true, false). A new ID needs a statement and measures. Throws UsageError naming
/// the setting and the fix.
std::vector<Hypothesis> parse_hypotheses(const std::vector<std::string>& settings, const std::string& a,
                                         const std::string& b);

}  // namespace feint::analysis

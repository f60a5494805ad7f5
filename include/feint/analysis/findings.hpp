// feint/analysis/findings.hpp - what the study shows, in sentences: the findings engine.
//
// A Finding answers one question of the study in a sentence with its numbers (APA style), with a
// strength of evidence taken from the statistics by the wording rules of docs/findings.md, never
// from a p-value alone. The functions are pure: plain inputs (test results, values per iteration)
// in, findings out. The fields id/question/sentence/evidence/source are those StudyResults carries
// (branch issue19-arch); the others add what the rules rest on.
#pragma once

#include <optional>
#include <utility>
#include <span>
#include <string>
#include <vector>

#include "feint/models/exposure.hpp"
#include "feint/stats/htest.hpp"

namespace feint::analysis {

/// The strength categories of docs/findings.md.
enum class Strength {
  evidence_for_difference,     ///< BF10 >= 3 and the CI excludes the null (after correction)
  no_evidence_either_way,      ///< neither of the others
  evidence_for_no_difference,  ///< BF01 >= 3, or TOST equivalent within a stated margin
  not_computable,              ///< the data cannot answer (one condition, n < 2, no variance, ...)
};
/// "evidence for a difference", "no evidence either way", "evidence for no difference", "not computable".
std::string to_string(Strength strength);

/// Grading by the Bayes factor in the direction of the evidence: moderate 3..10, strong >= 10.
enum class Grade { none, moderate, strong };
std::string to_string(Grade grade);  ///< "", "moderate", "strong"

/// An effect size with its interval (docs/findings.md "Fields"): d, d_z, g, rank-biserial r,
/// partial eta squared, generalized eta squared.
struct EffectSize {
  std::string name;  ///< "d", "d_z", "g", "r_rb", "eta2_p", "eta2_G"
  double value = 0.0;
  std::optional<double> ci_low, ci_high;
};

/// One answered question of the study.
struct Finding {
  std::string id;        ///< stable key, e.g. "H1-iteration-contrasts-error"
  std::string question;  ///< the hypothesis in words
  std::string sentence;  ///< the answer, APA numbers included
  std::string evidence;  ///< to_string(strength), with the grade: "strong evidence for a difference"
  std::string source;    ///< anchor of the table or figure it comes from, e.g. "table1"
  std::string hypothesis;  ///< "H1" or "H2"
  Strength strength = Strength::not_computable;
  Grade grade = Grade::none;
  std::string statistics;              ///< the APA statistics it rests on
  std::vector<std::string> warnings;   ///< e.g. a reference outside the data's range

  // What a Results paragraph needs, as numbers (docs/findings.md "Fields"). For a family (e.g. the
  // per-iteration contrasts) these describe the member with the smallest adjusted p.
  std::string measure;    ///< "error", "confusion", a questionnaire item
  std::string contrast;   ///< "adaptive - random", "mean - 0.5": what `estimate` is the difference of
  /// The observed direction in words, e.g. "adaptive > random" (whatever the strength: which way
  /// the data lean; `evidence` says how sure); "" when there is no estimate.
  std::string direction;
  /// The means of the two sides (A and B; a one-sample test: the mean and the reference).
  std::optional<std::pair<double, double>> means;
  std::optional<double> estimate, ci_low, ci_high;  ///< the difference and its interval
  double conf_level = 0.95;
  std::optional<EffectSize> effect_size;
  std::optional<double> p, p_adjusted;
  std::optional<double> bf10;  ///< null only with bf_note
  std::string bf_note;         ///< why there is no Bayes factor, or how it was computed
  std::string test;            ///< the test the finding rests on, e.g. "Welch t", "Mann-Whitney"
  bool confirmatory = false;   ///< a preregistered hypothesis's test (feint.toml [hypotheses])
  /// The test's alternative: one-sided (greater, less: of `contrast`'s first side) only for a
  /// confirmatory hypothesis with a direction (docs/findings.md "Hypotheses"); else two-sided.
  stats::Alternative alternative = stats::Alternative::two_sided;
  std::string member;          ///< for a family: which member the numbers describe ("test 3")
  /// The test across three or more conditions that protects their pairs (the models' condition F,
  /// a questionnaire item's Kruskal-Wallis test): it speaks for its measure in a Results paragraph.
  bool omnibus = false;
};

/// Fills the structured fields (test, estimate and CI as a difference `lhs - rhs`, direction,
/// effect size with CI, p, adjusted p, BF10 or bf_note) from the test a finding rests on. A
/// one-sample estimate is reported as its difference from the reference.
void set_test_fields(Finding& f, const stats::TestResult& test, std::string_view lhs,
                     std::string_view rhs);

/// The thresholds of docs/findings.md (settable, stated in the report).
struct WordingRules {
  double bf_moderate = 3.0;  ///< BF >= 3: evidence (moderate)
  double bf_strong = 10.0;   ///< BF >= 10: strong evidence
  double alpha = 0.05;       ///< level of the interval that must exclude the null
  std::optional<double> equivalence_margin;  ///< TOST margin, when given
};

/// The strength of one difference test (a t test with its Bayes factor and, when a margin is given,
/// the TOST result): evidence for a difference needs BF10 >= bf_moderate AND the (adjusted) p below
/// alpha (the interval excludes the null); evidence for no difference needs BF01 >= bf_moderate OR
/// a TOST p below alpha. A test without a Bayes factor can never earn "evidence for no difference"
/// except by TOST, and earns "evidence for a difference" only from p AND its interval.
Strength classify(const stats::TestResult& difference, const stats::TestResult* tost,
                  const WordingRules& rules, Grade* grade = nullptr);

/// A finding from one difference test. `what` names the comparison in words ("mean error in
/// iteration 3, adaptive vs random"), `lhs`/`rhs` its two sides for the sentence.
Finding difference_finding(std::string id, std::string hypothesis, std::string question,
                           std::string what, const stats::TestResult& difference,
                           const stats::TestResult* tost, std::string source,
                           const WordingRules& rules = {});

/// A family of tests (e.g. the 20 per-iteration contrasts of one metric) summarised in one headline
/// finding: the p-values are Holm-adjusted within the family (unless already adjusted), each test
/// classified, and the sentence counts the iterations with evidence for a difference, for no
/// difference, and neither. The family's headline strength is "evidence for a difference" when at
/// least one test earns it after the correction.
/// `correction` names an adjustment the caller made (the tests' p_adjusted), for the sentence, e.g.
/// "Westfall–Young maxT permutation-adjusted over 20 iterations"; empty: "Holm-corrected over N tests".
Finding family_finding(std::string id, std::string hypothesis, std::string question,
                       std::string what, std::vector<stats::TestResult> tests, std::string source,
                       const WordingRules& rules = {}, std::string correction = {});

/// H1, condition x exposure per strategy: one finding per strategy on the difference of the two
/// conditions' exposure slopes (a Welch t test on the participants' slopes, or the paired t test
/// within participants, Holm-corrected over the strategies, then classify(): the rule of every t test
/// with a Bayes factor), both slopes with
/// their CIs and participant counts in the sentence.
/// With one condition only: one "not computable" finding that says so. `metric` (when given) is
/// named in the ids ("H1-exposure-error-<strategy>") and the sentences.
std::vector<Finding> exposure_findings(const models::ExposureByCondition& exposure,
                                       const WordingRules& rules = {},
                                       std::string source = "model-exposure",
                                       const std::string& metric = "");

/// Reference plausibility: where the reference lies relative to every value of the metric.
struct ReferenceCheck {
  bool outside = false;  ///< above every value, or below every value, in every iteration
  bool above = false;    ///< the reference is above all values (else below), when outside
  double min = 0, max = 0;
  std::string warning;   ///< empty unless outside
};
/// `values[i]` = the participants' values of the metric in iteration i (NaN = missing).
ReferenceCheck check_reference(const std::string& metric, double reference,
                               std::span<const std::vector<double>> values);

/// Bad input made into findings (never a crash, never a silent gap).
Finding one_condition_only(std::string id, std::string hypothesis, std::string question,
                           const std::string& condition, std::string source);
Finding questionnaire_without_log(std::string id, std::span<const std::string> participants);

/// Renderers: a Markdown list, an HTML fragment (<ul class="findings">), JSON (findings.json: an
/// array of objects with every field), and plain text for the terminal.
std::string findings_markdown(std::span<const Finding> findings);
std::string findings_html(std::span<const Finding> findings);
std::string findings_json(std::span<const Finding> findings);
std::string findings_text(std::span<const Finding> findings);

}  // namespace feint::analysis

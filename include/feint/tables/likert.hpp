// feint/tables/likert.hpp - Likert questionnaire analyses (`feint likert`).
//
// statistics.md "Likert questionnaires". Per item (after reverse coding) and per composite scale:
// n, missing, mean, sd, median, IQR (R's type-7 quartiles), counts and percentages per scale point,
// % below / at / above the neutral point (the scale midpoint). Against a reference (default the
// scale midpoint): the Wilcoxon signed-rank test (R's wilcox.test(x, mu = R); primary, because a
// single item is ordinal) with the rank-biserial correlation, and beside it the one-sample t-test
// with Cohen's d (the paper's analysis). Between two conditions: Mann-Whitney U with the
// rank-biserial correlation, and Welch's t-test; within participants (`paired`) the signed-rank test
// on the differences and the paired t-test. Composite scales: per-respondent mean of their
// items (complete cases), Cronbach's raw alpha (psych::alpha) and alpha if each item is dropped.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "feint/io/questionnaire.hpp"
#include "feint/tables/tidy.hpp"
#include "feint/tables/writers.hpp"
#include "feint/stats/reliability.hpp"
#include "feint/stats/htest.hpp"
#include "feint/stats/p_adjust.hpp"

namespace feint::tables {

/// A multi-item scale: its score is the per-respondent mean of its items.
struct LikertComposite {
  std::string name;
  std::vector<std::string> items;
};

/// Parses `--composite NAME=ITEM,ITEM,...`. Throws UsageError.
LikertComposite parse_composite(std::string_view text);

/// The paper's four items (`--paper`): entertainment, deception, intelligence, trust.
std::vector<std::string> paper_items();
/// The paper's reference mean (`--paper`): 3.5.
inline constexpr double kPaperReference = 3.5;

struct LikertSettings {
  io::QuestionnaireOptions load;  ///< layout, scale, columns, labels, items, reverse
  std::vector<LikertComposite> composites;
  std::optional<double> reference;  ///< default: the scale midpoint (min + max) / 2
  std::string condition;            ///< one-sample mode: only this condition ("" = each)
  std::optional<std::pair<std::string, std::string>> compare;  ///< two-sample mode: (A, B)
  /// With `compare`: the conditions are within participants (each answered after each
  /// condition). Each participant's A answer is paired with their B answer: the Wilcoxon
  /// signed-rank test on the differences A - B (R's wilcox.test(x, y, paired = TRUE)) with the
  /// matched-pairs rank-biserial r, and the paired t-test with d_z and the JZS Bayes factor.
  /// Participants who answered in only one of the two conditions are left out and named in a note.
  bool paired = false;
  stats::TestOptions test;                                     ///< alternative, conf_level
  double alpha = 0.05;
  stats::PAdjustMethod p_adjust = stats::PAdjustMethod::none;
  /// Cronbach's alpha with missing answers: psych::alpha's default pairwise covariances, or
  /// complete cases (--alpha-missing).
  stats::AlphaMissing alpha_missing = stats::AlphaMissing::pairwise;
  bool apa = false;    ///< fill TidyRow::apa (CSV/JSON column "apa", APA lines under the table)
  bool paper = false;  ///< the paper's analysis: its four items, reference 3.5 (see docs/likert.md)
  /// Scale r of the JZS Bayes factor's Cauchy prior (sqrt(2)/2 = BayesFactor's "medium").
  double bf_prior_r = 0.7071067811865476;
};

/// Descriptive summary of one item or composite in one group.
struct LikertSummary {
  std::string name;
  bool composite = false;
  std::string group;  ///< condition ("" = everybody)
  std::size_t n = 0;
  std::size_t missing = 0;
  std::optional<double> mean, sd, median, q1, q3, iqr;
  std::vector<std::size_t> counts;                     ///< per scale point min..max (items only)
  std::optional<double> pct_below, pct_at, pct_above;  ///< % of n, against the neutral point
};

/// Reliability of a composite over the respondents of one analysis (group, or A and B together).
struct LikertReliability {
  std::string name;
  std::string group;  ///< "A+B" style label for two-sample mode, condition or "" otherwise
  std::vector<std::string> items;
  std::size_t n = 0;  ///< complete cases, or (pairwise) respondents who answered any item
  std::optional<double> alpha;                    ///< raw alpha
  std::vector<std::optional<double>> if_dropped;  ///< alpha with item j dropped
  std::string note;
};

struct LikertAnalysis {
  LikertSettings settings;
  std::string source;
  int scale_min = 1;
  int scale_max = 7;
  double reference = 4.0;
  double neutral = 4.0;  ///< scale midpoint
  bool two_sample = false;
  bool paired = false;  ///< two-sample mode within participants (settings.paired)
  std::vector<std::string> unpaired;  ///< participants who answered in only one of A and B
  std::vector<std::string> groups;  ///< one-sample: analysed conditions ("" = no condition column)
  std::vector<std::string> names;   ///< items, then composites
  std::vector<bool> is_composite;
  std::vector<bool> reversed;                  ///< per name (composites: false)
  std::vector<LikertSummary> summaries;        ///< per group, per name
  std::vector<LikertReliability> reliability;  ///< per group, per composite
  /// Per group (two-sample: one block), per name: the primary rank test, then the t-test.
  std::vector<TidyRow> rows;
  std::vector<std::string> notes;  ///< what the table shows, decisions, warnings
};

/// Assembles the analysis. Throws UsageError for options that do not fit the data (unknown
/// condition/item, composite naming an unknown item), InvalidData when two-sample groups share a
/// participant (Mann-Whitney and Welch need independent groups; settings.paired pairs them instead)
/// or, paired, when a participant answered twice in one condition.
LikertAnalysis analyze_likert(const io::Questionnaire& questionnaire,
                              const LikertSettings& settings);

/// Loads with settings.load (plus --paper's items) and analyses.
LikertAnalysis analyze_likert_file(const std::string& path, const LikertSettings& settings);

/// text / markdown / latex: the Likert table, the response distribution, reliability and the
/// note; csv / json: the tidy rows with likert_columns(settings.apa).
/// `presentation` (--label, --caption, --latex-wide) applies to the main table; the response and
/// reliability tables get the label plus "-responses" / "-reliability". Default label:
/// tab:feint-likert, tab:feint-likert-<condition> (--condition), tab:feint-likert-<A>-vs-<B>.
std::string render_likert(const LikertAnalysis& analysis, OutputFormat format,
                          const TablePresentation& presentation = {});

/// Per group and item/composite descriptives as CSV: group, name, kind, n, missing, mean, sd,
/// median, q1, q3, iqr, pct_below, pct_at, pct_above, then n_<point> and pct_<point> per scale
/// point.
std::string likert_summary_csv(const LikertAnalysis& analysis);

/// Library entry point (used by `feint analyze` on a study folder): load `path`, analyse, render
/// in `format` and write `output_path` atomically (`-` = standard output).
void likert_report_to_file(const std::string& path, const LikertSettings& settings,
                           const std::string& output_path, OutputFormat format);

}  // namespace feint::tables

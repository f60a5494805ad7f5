// feint/analysis/study_findings.hpp - the findings of a whole study, from its StudyResults.
#pragma once

#include <cstdint>
#include <vector>

#include "feint/analysis/findings.hpp"
#include "feint/analysis/results.hpp"
#include "feint/tables/table1.hpp"

namespace feint::analysis {

/// Relabellings of the participants for the per-iteration contrasts' maxT adjustment (seeded, so
/// the findings are the same on every run; Monte Carlo SE of an adjusted p of .05: 0.002).
inline constexpr std::uint64_t kIterationPermutations = 9999;

/// Relabellings of the participants for the mixed models' condition tests (each refits both
/// random-intercept models; models::relabel_condition_tests).
inline constexpr std::uint64_t kModelPermutations = 9999;

/// H1: per metric, the family of per-iteration contrasts between the conditions (the comparison
/// table), adjusted by Westfall–Young step-down maxT over the iterations (participants relabelled
/// between the conditions, stats::maxt_step_down; Holm, with a warning that says why, where whole
/// participants cannot be relabelled: paired tests, a participant in both conditions), or "only
/// one condition" when there is none to compare; a reference-outside-the-data warning per metric
/// (check_reference over every participant and iteration).
/// H2: per Likert item and composite, the t test against the reference and between the conditions.
/// H1 from the mixed models: mixed_model_findings. H1 condition x exposure per strategy: the trial
/// labels (figures.labels) joined to the scores, exposure_findings per metric.
/// Wording rules: docs/findings.md.
std::vector<Finding> study_findings(const StudyResults& results,
                                    const std::vector<tables::MetricSpec>& metrics,
                                    const WordingRules& rules = {});

/// H1 from the mixed models, per metric: the condition x iteration interaction and the condition
/// main effect of `model` (type-III F, Satterthwaite or Kenward-Roger df) and the difference of the
/// conditions' linear slopes over the iterations in `trend` (the fixed effect
/// condition<B>:iteration, second level minus the first, with its interval). Each test's p-value
/// is its relabelling p-value (whole participants relabelled between the two conditions and both
/// models refitted on the trials they were fitted to, MetricModel::data;
/// models::relabel_condition_tests, kModelPermutations) when there are two conditions; otherwise
/// (or without the trials) the model's own, with a warning that says why. The three tests of a metric are one family, Holm-corrected. Neither has a Bayes factor: "evidence for a difference"
/// needs the corrected p below alpha (and, for the slope, its interval excluding 0); otherwise "no
/// evidence either way", never "evidence for no difference". Sources: "model" and "model-trend".
/// Either model may be null (left out of the study).
/// The condition main effect also carries its numbers (detail::describe_condition_effect: the
/// conditions' marginal means and difference, partial eta squared, and the JZS Bayes factor of a
/// Welch t test on the participants' mean scores, which its strength then uses as every t test's).
/// With three or more conditions the omnibus F is followed by one finding per pair of conditions
/// (ids H1-model-pair-METRIC-A-B; detail::pairwise_condition_findings: emmeans' Tukey-adjusted
/// pairwise contrast, protected by the omnibus finding).
std::vector<Finding> mixed_model_findings(const tables::ModelAnalysis* model,
                                          const tables::ModelAnalysis* trend,
                                          const WordingRules& rules = {},
                                          double bf_prior_r = 0.7071067811865476);

/// The input of models::exposure_slopes_by_condition for one metric: each scored trial with a value
/// of the metric, joined by (participant, condition, iteration) to its label (strategy), with its
/// exposure count taken over the participant's labelled trials in that condition
/// (models::exposure_counts; between participants, all of the participant's trials). Trials
/// without a label are left out (`unlabelled` counts them).
struct ExposureInput {
  std::vector<std::string> participant, condition, strategy;
  std::vector<double> exposure, y;
  std::size_t unlabelled = 0;
};
ExposureInput exposure_input(const io::ScoresTable& scores, const std::vector<TrialLabel>& labels,
                             const std::string& metric);

/// The report's condition x exposure table of `metric` (models::exposure_slopes_by_condition on
/// exposure_input, the conditions in `conditions` order, JZS prior scale `bf_prior_r` for the
/// difference tests' Bayes factors; `paired`: conditions within participants, paired differences);
/// throws what the fit throws.
tables::ExposureTable exposure_table(const io::ScoresTable& scores, const std::vector<TrialLabel>& labels,
                                     const std::string& metric, const std::vector<std::string>& conditions,
                                     double conf_level, double bf_prior_r = 0.7071067811865476,
                                     bool paired = false);

}  // namespace feint::analysis

// condition_effect.hpp - the numbers behind a finding that a model term alone does not give:
// which way and how much the conditions differ (private to the analysis module).
#pragma once

#include <optional>
#include <string>

#include "feint/analysis/findings.hpp"
#include "feint/tables/model.hpp"

namespace feint::analysis::detail {

/// The mixed model's condition effect in numbers (docs/findings.md "Fields"): the two conditions'
/// estimated marginal means averaged over the iterations and their difference with its interval
/// (emmeans pairwise ~ condition), the F's partial eta squared with its interval (effectsize's
/// F_to_eta2), and the JZS Bayes factor of a Welch t test on the participants' mean scores, with
/// `bf_note` saying so. Returns the natural log of that BF10 (nullopt when not computable), which
/// the caller gives the test so that the strength uses it.
std::optional<double> describe_condition_effect(Finding& f, const tables::MetricModel& m, double conf_level,
                                                double bf_prior_r);

/// The JZS Bayes factor (log BF10) of the t test on the participants' mean scores in conditions
/// `a` and `b`: Welch between participants, paired when some participant saw both; `note` says
/// which and on how many participants (or why there is none: nullopt).
std::optional<double> participant_means_bf(const models::LongData& data, const std::string& a, const std::string& b,
                                           double conf_level, double bf_prior_r, std::string& note);

/// Three or more conditions: after the omnibus F of condition, which conditions differ. One finding
/// per pair of conditions: the emmeans pairwise contrast over the iterations (Tukey-adjusted p and
/// interval over the k(k - 1)/2 pairs, Satterthwaite df), the two estimated marginal means, and the
/// JZS Bayes factor of the participants' mean scores (participant_means_bf); classified by the
/// rule of every difference test (adjusted p < alpha and BF10 >= 3), and protected: a pair earns
/// "evidence for a difference" only when `omnibus` (the condition F's finding) did too, else it is
/// "no evidence either way" with a warning that says why. Empty for fewer than 3 conditions.
std::vector<Finding> pairwise_condition_findings(const tables::MetricModel& m, double conf_level, double bf_prior_r,
                                                 const WordingRules& rules, const Finding* omnibus);

/// Protection after an omnibus test: a pair's "evidence for a difference" becomes "no evidence
/// either way", with a warning naming `measure`, unless `omnibus` earned evidence for a difference.
void protect_by_omnibus(Finding& f, const Finding* omnibus, const std::string& measure);

/// "M = 0.48 vs 0.46; difference 0.03, 95% CI [0.01, 0.05]; ηp² = .13 [.03, 1.00]; BF10 = 4.2":
/// the structured fields in words for a sentence ("" when there are none).
std::string effect_words(const Finding& f);

/// Partial eta squared with its interval (effectsize's F_to_eta2) of a model test that has none
/// yet: an F from its df, a t (the slope difference) as F = t^2 on 1 df.
void add_model_effect_size(Finding& f, const stats::TestResult& test, double conf_level);

/// Replaces the sides "A" and "B" of a finding's contrast and direction by the condition names.
void name_conditions(Finding& f, const std::string& a, const std::string& b);

}  // namespace feint::analysis::detail

// feint/models/model_relabelling.hpp - relabelling (permutation) p-values for the condition tests
// of the random-intercept mixed models.
//
// The findings' three model tests of a metric (docs/findings.md, "Mixed models: relabelling
// p-values") are those of
//
//     y ~ condition * iteration + (1 | participant)   (iteration as a factor: interaction F and
//                                                      condition F, type III, Wald)
//     y ~ condition * iteration + (1 | participant)   (iteration as a linear trend: the t of the
//                                                      slope difference condition<B>:iteration)
//
// Their F and t distributions (Satterthwaite df) assume that the model's covariance is right: one
// variance between participants and independent trials within them (compound symmetry). Where the
// trials of a participant are correlated in time, the interaction F is too liberal (the split-plot
// ANOVA's sphericity problem), and where the participant variance is estimated at 0 the condition F
// forgets that trials are clustered. Relabelling whole participants between the two conditions
// (each keeps all of their trials) and refitting gives each statistic's distribution under the
// null that the condition changes nothing, whatever the dependence within a participant:
//
//     p = #{labellings b : s_b >= s_obs} / B_total,   s = F (interaction, condition) or |t| (slope)
//
// over every labelling when there are at most `permutations + 1`, else the observed one and
// `permutations` uniform draws (stats::for_each_labelling; seeded, the same on every machine).
//
// Each relabelling is a full REML refit, made fast by the models' structure: in the cell-means
// parametrisation (one mean per condition x iteration cell, or an intercept and a slope per
// condition) X'V^-1 X is block-diagonal by condition, and with V = sigma^2 (I + theta^2 Z Z') every
// term is a sum over participants of their counts and sums (the Fuller–Battese weights
// c_i = theta^2 / (1 + n_i theta^2)), so that one REML evaluation costs O(m^2) per condition plus
// O(m^2) per participant with missing trials, and theta is found by Brent's method. The observed
// statistics equal fit_mixed_model's F and t (tested to 1e-6).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "feint/models/mixed_model.hpp"

namespace feint::models {

struct RelabellingOptions {
  std::uint64_t permutations = 9999;  ///< relabellings drawn when not enumerated exactly
  std::uint64_t seed = 20261126;
};

/// The observed statistics and their relabelling p-values. A statistic is empty when the observed
/// data cannot give it (an empty condition x iteration cell, a single iteration); a relabelling
/// that cannot give it (it empties a cell) counts as reaching the observed value (conservative),
/// and `not_computable` counts those.
struct RelabelledConditionTests {
  std::optional<double> interaction_f;       ///< condition x iteration, iteration as a factor
  std::optional<double> condition_f;         ///< condition, iteration as a factor
  std::optional<double> slope_difference_t;  ///< group_levels[1] minus group_levels[0], linear trend
  std::optional<double> p_interaction, p_condition, p_slope_difference;
  std::uint64_t labellings = 0;  ///< labellings counted, the observed one included
  bool exact = false;            ///< every labelling enumerated
  std::uint64_t not_computable = 0;
};

/// Relabels the participants of `data` between the two conditions `group_levels` (the first is
/// the reference of the slope difference) and refits both random-intercept models under each
/// labelling. Throws InvalidData when a participant has trials in both conditions or in a
/// condition not named, and UsageError unless there are exactly two levels, each with a
/// participant, or when permutations == 0.
RelabelledConditionTests relabel_condition_tests(const LongData& data, const std::vector<std::string>& group_levels,
                                                 const RelabellingOptions& options = {});

}  // namespace feint::models

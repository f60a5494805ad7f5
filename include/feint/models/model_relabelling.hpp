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
// over every labelling when there are at most `permutations + 1`. Otherwise the labellings are
// drawn uniformly (stats::for_each_labelling_while; seeded, the same on every machine) and each
// test's p-value is Besag & Clifford's sequential one (stats::SequentialPValue): a test stops once
// `exceedances` (h) drawn labellings reach its observed statistic, p = h / l after l draws, or
// after `permutations` draws with g < h reaching it, p = (g + 1) / (permutations + 1) (the fixed-n
// p-value). Both are exact under exchangeability; a p-value far above alpha stops after about h / p
// draws, and one below h / (permutations + 1) is the fixed-n one from the same draws.
//
// Each relabelling is a full REML refit, made cheap by the models' structure: in the cell-means
// parametrisation X'V^-1 X is block-diagonal by condition, and with V = sigma^2 (I + theta^2 Z Z')
// it is D - U W U' (D the trials per cell, U the few distinct patterns of a participant's trials
// over the iterations, W their Fuller–Battese weights c_n = theta^2 / (1 + n theta^2) times their
// participants), so that by Woodbury one REML evaluation factorises an r x r matrix, r = the
// patterns present (1 when every participant has every trial), and the linear trend's is 2 x 2 per
// condition. theta is found by Brent's method, or in closed form when every participant has every
// trial (the REML criterion then splits into two strata). The observed statistics equal fit_mixed_model's F
// and t (tested to 1e-6).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "feint/models/mixed_model.hpp"

namespace feint::models {

struct RelabellingOptions {
  std::uint64_t permutations = 9999;  ///< relabellings drawn at most when not enumerated exactly
  std::uint64_t seed = 20261126;
  /// Besag & Clifford's h: a test's draws stop once h of them reach its observed statistic
  /// (0 = never: every test counts all `permutations` draws). With h = 50 a true p outside
  /// [alpha / 1.5, 1.5 alpha] gets the other side of alpha with probability below 0.4 %
  /// (docs/findings.md, "Mixed models: relabelling p-values").
  std::uint64_t exceedances = 50;
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
  std::uint64_t labellings = 0;  ///< labellings visited, the observed one included (the most of any test)
  bool exact = false;            ///< every labelling enumerated
  /// Labellings each p-value counts, the observed one included: all of them when exact, else the
  /// observed one and the draws until the test stopped (RelabellingOptions::exceedances).
  std::uint64_t labellings_interaction = 0, labellings_condition = 0, labellings_slope = 0;
  /// Whether each test stopped early: then its p-value is exceedances / (labellings_* - 1), that
  /// many of the drawn labellings reaching the observed statistic.
  bool stopped_interaction = false, stopped_condition = false, stopped_slope = false;
  std::uint64_t exceedances = 0;  ///< RelabellingOptions::exceedances when sampled, 0 when exact
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

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
// forgets that trials are clustered. Relabelling and refitting gives each statistic's distribution
// under the null that the condition changes nothing, whatever the dependence within a participant:
// between participants, whole participants are permuted between the conditions (each keeps all of
// their trials; the group sizes are kept); within participants, each participant's own conditions
// are permuted among themselves (a block of trials keeps its trials and moves to another condition
// of the same participant: with two conditions, a swap or not per participant, 2^P labellings):
//
//     p = #{labellings b : s_b >= s_obs} / B_total,   s = F (interaction, condition) or |t| (slope)
//
// With C >= 3 conditions the slope family has C - 1 tests (each condition's slope minus the first
// condition's), each with its own p-value from the same labellings: the findings Holm-adjust them
// with the two F tests, as they do the models' own p-values, rather than merging them into one
// max|t| that would need a separate answer to "which slope differs".
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
// trial (the REML criterion then splits into two strata). That fast path is for two conditions
// between participants; within participants and with three or more conditions each labelling is
// a dense refit in the cell-means parametrisation (X'V^-1 X = sum_i X_i'X_i - sum_k c_k A_k with
// A_k the label-dependent sums of u_i u_i' per size class, one K x K Cholesky factor per REML
// evaluation, theta by Brent's method; src/models/relabelling_general.cpp). The observed
// statistics equal fit_mixed_model's F and t (tested to 1e-6).
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
  /// The conditions are within participants: a labelling permutes each participant's own
  /// conditions among themselves (all trials of a condition move together; with two conditions a
  /// swap or not per participant), instead of moving whole participants between the conditions.
  bool within = false;
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
  /// The slope family, one entry per condition but the first (group_levels[k] minus
  /// group_levels[0], k = 1, 2, ...), each test with its own relabelling p-value from the same
  /// labellings (the findings Holm-adjust them with the F tests). With two conditions, entry 0
  /// equals slope_difference_t, p_slope_difference, labellings_slope and stopped_slope.
  std::vector<std::optional<double>> slope_differences_t, p_slope_differences;
  std::vector<std::uint64_t> labellings_slopes;
  std::vector<bool> stopped_slopes;
};

/// Relabels `data` between the conditions `group_levels` (the first is the reference of the slope
/// differences) and refits both random-intercept models under each labelling. Between
/// participants (options.within false) whole participants are permuted between the conditions,
/// the group sizes kept: P! / (n_1! ... n_C!) labellings; with two conditions by the fast refit
/// above, with three or more by a dense refit (K x K, K = conditions x iterations). Within
/// participants each participant's own conditions are permuted among themselves, all of a
/// condition's trials moving together: prod_i (C_i)! labellings (2^P with two conditions), each a
/// dense refit. Throws InvalidData when a participant has trials in a condition not named or
/// (between) in two conditions, and UsageError for fewer than two levels, a condition without a
/// participant (between), or permutations == 0.
RelabelledConditionTests relabel_condition_tests(const LongData& data, const std::vector<std::string>& group_levels,
                                                 const RelabellingOptions& options = {});

}  // namespace feint::models

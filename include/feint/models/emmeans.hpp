// feint/models/emmeans.hpp - estimated marginal means and their contrasts from a fitted mixed
// model (iteration as a factor), as R's emmeans on an lmer fit (Lenth, emmeans 1.8.4) with
// lmer.df = "satterthwaite" or "kenward-roger" (the fit's spec.ddf).
//
// The reference grid is every condition x iteration cell; a marginal mean averages the cells'
// predictions with equal weights (emmeans' default), e.g. the mean of condition A is
// (1/K) sum_j x(A, j)' beta. Every mean and contrast is a linear function L' beta, tested by
// contrast() (its SE, df, t and p are Satterthwaite's or Kenward-Roger's).
//
// Contrast families (each by-group is its own family for the adjustment):
//   pairwise_condition      pairwise ~ condition               (averaged over iterations)
//   pairwise_iteration      pairwise ~ iteration               (averaged over conditions)
//   condition_at_iteration  pairwise ~ condition | iteration   (simple effects)
//   iteration_in_condition  pairwise ~ iteration | condition   (simple effects)
//   poly_iteration          poly ~ iteration                   (orthogonal polynomials)
//   poly_in_condition       poly ~ iteration | condition
// Adjustments (emmeans' `adjust`): none; holm (p by Holm, intervals by Bonferroni, as emmeans
// does because Holm has no intervals); tukey (p = P(Q > |t| sqrt 2) and intervals
// estimate -+ qtukey(conf, k, df) / sqrt 2 * SE, k the number of means of the family).
#pragma once

#include <string>
#include <vector>

#include "feint/models/design.hpp"
#include "feint/models/mixed_model.hpp"

namespace feint::models {

enum class EmmTerm { cells, condition, iteration };
enum class EmmFamily {
  pairwise_condition,
  pairwise_iteration,
  condition_at_iteration,
  iteration_in_condition,
  poly_iteration,
  poly_in_condition,
};
enum class EmmAdjust { none, holm, tukey };

/// One estimated mean or contrast. `by` is the level the family is conditioned on ("" when none):
/// an iteration ("3") or a condition ("adaptive").
struct EmmRow {
  std::string label;  ///< "adaptive", "adaptive|3" (cells), "adaptive - random",
                      ///< "iteration1 - iteration2", "linear", ...
  std::string by;
  double estimate = 0, std_error = 0, df = 0, statistic = 0;
  double p_value = 1;       ///< with the family's adjustment (emmeans' p.value)
  double p_unadjusted = 1;  ///< from Student's t
  double conf_low = 0, conf_high = 0;  ///< with the family's adjustment (contrasts)
  bool computed = true;
  std::string note;
};

/// A table of estimated marginal means or of one contrast family (for reports).
struct EmmTable {
  std::string term;    ///< "condition:iteration", ..., or "pairwise ~ iteration | condition"
  std::string adjust;  ///< contrasts: the adjustment applied
  std::vector<EmmRow> rows;
};

/// The estimated marginal means of `term` with `conf_level` intervals (t vs 0 and p too, as
/// emmeans' summary(infer = TRUE)). UsageError unless iteration is a factor and the group is
/// condition.
std::vector<EmmRow> estimated_means(const MixedModelFit& fit, EmmTerm term,
                                    double conf_level = 0.95);

/// The contrasts of `family` with `adjust` applied within each by-group. Tukey needs a pairwise
/// family (UsageError otherwise, as its distribution is that of the range of the means).
std::vector<EmmRow> emm_contrasts(const MixedModelFit& fit, EmmFamily family, EmmAdjust adjust,
                                  double conf_level = 0.95);

/// The same for the repeated-measures ANOVA (complete cases, `feint anova`), as emmeans on an
/// afex::aov_ez object with its default multivariate model: cell means, each mean or contrast's
/// variance from the covariance of the iterations pooled within conditions,
/// var(w) = sum_g w_g' S w_g / n_g with S = E / (N - a), and df = N - a (Student's t).
std::vector<EmmRow> estimated_means(const WideDesign& design, EmmTerm term,
                                    double conf_level = 0.95);
std::vector<EmmRow> emm_contrasts(const WideDesign& design, EmmFamily family, EmmAdjust adjust,
                                  double conf_level = 0.95);

/// emmeans' poly.emmc: orthogonal polynomial contrasts of `k` equally spaced levels, each column
/// scaled to small integers (degree 1 .. min(6, k - 1)); rows = degrees.
std::vector<std::vector<double>> poly_contrasts(std::size_t k);

/// emmeans-style name of a family, e.g. "pairwise ~ iteration | condition", "poly ~ iteration".
std::string to_string(EmmFamily family);
/// Name of a mean term: "condition:iteration", "condition", "iteration".
std::string to_string(EmmTerm term);
std::string to_string(EmmAdjust adjust);

/// "none", "holm", "tukey" (UsageError otherwise).
EmmAdjust parse_emm_adjust(const std::string& text);

}  // namespace feint::models

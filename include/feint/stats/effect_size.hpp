// feint/stats/effect_size.hpp - confidence intervals of effect sizes, as R's effectsize (0.8) defines
// them, but with exact roots.
//
// d, d_z, g: the noncentral-t pivot (Steiger & Fouladi 1997; effectsize's cohens_d/hedges_g):
//   find ncp_lo, ncp_hi with pt(t, df, ncp_lo) = 1 - a/2 and pt(t, df, ncp_hi) = a/2, then
//   d bounds = ncp * sqrt(1/n) (one-sample, paired) or ncp * sqrt(1/n1 + 1/n2) (two-sample, pooled);
//   g bounds = d bounds * J(df). One-sided (alternative greater/less): the two-sided interval at
//   level 2 conf - 1, with the other side infinite (effectsize's .adjust_ci/.limit_ci).
// Partial eta squared from F (effectsize's F_to_eta2): eta2 = F df1 / (F df1 + df2); bounds
//   ncp / (ncp + df2) with pf(F, df1, df2, ncp) = 1 - a/2 (lower), a/2 (upper), a bound being 0 when F
//   is below the matching central quantile; the default alternative is "greater": level 2 conf - 1,
//   upper bound 1.
// Rank-biserial r (effectsize's rank_biserial): Fisher's z, tanh(atanh(r) -/+ z_{1-a/2} SE) with
//   SE = sqrt((2n^3 + 3n^2 + n)/6) / (n(n+1)/2) (one-sample/paired, n = non-zero differences) or
//   sqrt((n1 + n2 + 1) / (3 n1 n2)) (two-sample). r = +-1 gives the degenerate interval [r, r].
// Roots by TOMS 748 on Boost.Math's non_central_t / non_central_f to full double precision, not by
// effectsize's optim() search (see docs/effect-sizes.md for how far that is off).
#pragma once

#include <cstddef>

#include "feint/stats/htest.hpp"

namespace feint::stats {

struct EffectInterval {
  double low, high;
};

/// The noncentral-t confidence interval of the ncp given an observed t with df degrees of freedom.
EffectInterval noncentral_t_ncp_interval(double t, double df, double conf_level = 0.95,
                                         Alternative alternative = Alternative::two_sided);

/// d (or d_z) interval of a one-sample or paired test with n values: ncp interval / sqrt(n).
EffectInterval cohen_d_interval_one_sample(double t, std::size_t n, double conf_level = 0.95,
                                           Alternative alternative = Alternative::two_sided);

/// d interval of a two-sample test from the pooled t (df = n1 + n2 - 2): ncp * sqrt(1/n1 + 1/n2).
EffectInterval cohen_d_interval_two_sample(double t_pooled, std::size_t n1, std::size_t n2,
                                           double conf_level = 0.95,
                                           Alternative alternative = Alternative::two_sided);

struct EtaSquared {
  double estimate, low, high;
};

/// Partial eta squared with its noncentral-F interval (effectsize's F_to_eta2; default alternative
/// "greater", a one-sided interval with upper bound 1).
EtaSquared f_to_eta2(double f, double df1, double df2, double conf_level = 0.95,
                     Alternative alternative = Alternative::greater);

/// Generalized eta squared with effectsize's interval (eta_squared(model, generalized = TRUE) on an
/// afex model, effectsize 0.8): the pseudo-F of ges, F* = (ges / df1) / ((1 - ges) / df2), with the
/// effect's df1 and its error stratum's df2, both uncorrected for sphericity, and f_to_eta2's
/// interval of F* (estimate = ges). docs/effect-sizes.md says why this is a convention, not an
/// exact interval for ges. Throws InvalidData for ges outside [0, 1) or df <= 0.
EtaSquared generalized_eta2(double ges, double df1, double df2, double conf_level = 0.95,
                            Alternative alternative = Alternative::greater);

/// Rank-biserial r interval (Fisher z). n2 = 0: one-sample/paired with n1 non-zero differences.
EffectInterval rank_biserial_interval(double r, std::size_t n1, std::size_t n2, double conf_level = 0.95,
                                      Alternative alternative = Alternative::two_sided);

/// Fills the effect-size intervals of a computed test from its own fields, at its conf_level and
/// alternative: d and g (t tests; the Welch row uses the pooled-sd d and the pooled t, as its d),
/// r (rank tests; needs `n_nonzero` for the signed-rank test, else n1 is used), eta squared
/// (anova: from F, df, df2, alternative "greater"). Leaves them empty where they do not apply.
void add_effect_size_intervals(TestResult& test, std::size_t n_nonzero = 0);

}  // namespace feint::stats

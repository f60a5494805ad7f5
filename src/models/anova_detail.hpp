// Pieces shared by the mixed ANOVA (mixed_anova.cpp) and the all-within ANOVA (within_anova.cpp):
// F and chi-squared upper tails, orthonormal contrasts, and the sphericity statistics of one error
// SSP matrix (formulas in feint/models/mixed_anova.hpp and within_anova.hpp).
#pragma once

#include <Eigen/Dense>

namespace feint::models::detail {

/// Upper tail of F(df1, df2) at f (Boost complement: no cancellation for small p).
double f_upper(double f, double df1, double df2);

/// Upper tail of chi-squared(df) at x.
double chisq_upper(double x, double df);

/// Orthonormal Helmert contrasts, k x (k - 1): column j compares level j+1 with levels 1..j.
Eigen::MatrixXd orthonormal_contrasts(Eigen::Index k);

/// Greenhouse-Geisser and Huynh-Feldt (Lecoutre, uncapped) epsilons and Mauchly's test of a
/// regular p x p error SSP matrix with eigenvalues `lambda` and `dfe` error df, as
/// car:::summary.Anova.mlm computes them; `columns` is car's nrow(P), the number of response
/// columns of the multivariate model (it enters Mauchly's second-order term as `3 * columns`).
struct SphericityStatistics {
  double gg = 1, hf = 1, mauchly_w = 1, mauchly_p = 1;
};
SphericityStatistics sphericity_statistics(const Eigen::VectorXd& lambda, double dfe,
                                           double columns);

}  // namespace feint::models::detail

// feint/stats/bayes_factor.hpp - the JZS default Bayes factor for t tests (Rouder et al. 2009).
//
// H0: delta = 0 (the standardised effect); H1: delta ~ Cauchy(0, r), optionally restricted to an
// interval [lo, hi] (BayesFactor's `nullInterval`: the prior is truncated to the interval and
// renormalised). The data enter only through t, the effective sample size N and df nu:
//   one-sample / paired: N = n, nu = n - 1;   two-sample (pooled): N = n1 n2 / (n1 + n2), nu = n1 + n2 - 2.
//
// Point alternative (two-sided), Rouder et al. (2009) eq. 1 with g ~ inverse-gamma(1/2, r^2/2):
//   BF10 = int_0^inf (1 + N g)^(-1/2) (1 + t^2 / ((1 + N g) nu))^(-(nu+1)/2)
//          r / sqrt(2 pi) g^(-3/2) exp(-r^2 / (2 g)) dg  /  (1 + t^2/nu)^(-(nu+1)/2)
// One-sided (delta > 0 or < 0): the same integral times a skew-t factor 2 T_{nu+1}(...).
// Interval alternative:
//   BF_I0 = int_I p(t | delta) cauchy(delta; r) d delta / (P(delta in I) p(t | 0)),
//   p(t | delta) the noncentral t density with ncp delta sqrt(N), integrated over theta =
//   atan(delta / r) with the likelihood ratio written as E[exp(ncp t s - ncp^2 / 2)] over the chi
//   scale s of t (docs/bayes-factors.md).
// All are integrated exactly (Gauss–Kronrod on pieces walked out from the integrand's peak, in
// logs, so BF = e^345000 or e^-1000 neither overflows nor underflows: log_bf10 is exact where
// bf10() is +inf or 0), not approximated, in milliseconds at |t| up to 1e4 and n up to 1e5: the
// goldens (tests/golden/bayes/make_bf_golden.R, R's integrate at rel.tol 1e-12) agree to 1e-6
// relative in BF, and high-precision references at |t| = 0 to 1e4, n = 2 to 1e5
// (tests/stats/test_bayes_factor_extremes.cpp) to 1e-8 relative in log BF (see
// docs/bayes-factors.md for where BayesFactor::ttestBF is off).
//
// References: Rouder, J. N., Speckman, P. L., Sun, D., Morey, R. D., Iverson, G. (2009). Bayesian t
// tests for accepting and rejecting the null hypothesis. Psychonomic Bulletin & Review 16(2),
// 225–237. Morey, R. D., Rouder, J. N. (2011). Bayes factor approaches for testing interval null
// hypotheses. Psychological Methods 16(4), 406–419.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "feint/stats/htest.hpp"

namespace feint::stats {

/// BayesFactor's "medium" prior scale, sqrt(2)/2.
inline constexpr double kJzsMediumScale = 0.70710678118654752440;

/// A Bayes factor of H1 against H0, held in logs (natural log).
struct BayesFactor {
  double log_bf10 = std::numeric_limits<double>::quiet_NaN();
  double r = kJzsMediumScale;  ///< Cauchy prior scale
  double lo = -std::numeric_limits<double>::infinity();  ///< H1's interval for delta
  double hi = std::numeric_limits<double>::infinity();
  double bf10() const { return std::exp(log_bf10); }
  double bf01() const { return std::exp(-log_bf10); }
  /// "Cauchy prior r = 0.707, H1: delta > 0" and the like.
  std::string describe() const;
};

/// log BF of H1 (delta ~ Cauchy(0, r) truncated to [lo, hi]) against delta = 0, given t, the
/// effective sample size n_eff and the degrees of freedom df. Throws UsageError for r <= 0,
/// lo >= hi, n_eff <= 0 or df <= 0 (and InvalidData for a non-finite t).
double jzs_log_bf(double t, double n_eff, double df, double r = kJzsMediumScale,
                  double lo = -std::numeric_limits<double>::infinity(),
                  double hi = std::numeric_limits<double>::infinity());

/// log BF of the complement of [lo, hi] (delta outside it, Cauchy prior truncated to the outside)
/// against delta = 0: BayesFactor's second element with `nullInterval = c(lo, hi)`.
double jzs_log_bf_complement(double t, double n_eff, double df, double r, double lo, double hi);

/// The Bayes factor that goes with a one-sample or paired t test with this alternative:
/// two_sided: delta != 0; greater: delta > 0; less: delta < 0 (each against delta = 0).
BayesFactor jzs_bf_one_sample(double t, std::size_t n, Alternative alternative = Alternative::two_sided,
                              double r = kJzsMediumScale);
/// The same for two independent samples (N = n1 n2 / (n1 + n2), df = n1 + n2 - 2; the pooled t).
BayesFactor jzs_bf_two_sample(double t, std::size_t n1, std::size_t n2,
                              Alternative alternative = Alternative::two_sided,
                              double r = kJzsMediumScale);

/// An interval null: H0: delta in [-margin, margin] against H1: delta outside it (both with the
/// Cauchy(0, r) prior truncated), log BF10 = log BF(outside : 0) - log BF(inside : 0).
BayesFactor jzs_bf_interval_null(double t, double n_eff, double df, double margin,
                                 double r = kJzsMediumScale);

/// Fills test.bayes_factor from a computed t test (one_sample_t, paired_t: one-sample form;
/// student_t and welch_t: the two-sample form from the pooled t, as ttestBF, which has no Welch
/// version). Leaves it empty for other tests or when the test was not computed.
void add_bayes_factor(TestResult& test, double r = kJzsMediumScale);

/// The prior as a table note states it: "r = 0.707 (medium)", "r = 1 (wide)", "r = 1.414
/// (ultrawide)" (BayesFactor's names, within 1e-12), otherwise "r = 0.5".
std::string jzs_prior_text(double r);

}  // namespace feint::stats

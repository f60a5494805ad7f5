// feint/models/studentized_range.hpp - the studentized range distribution (Tukey's HSD), which
// Boost 1.74 lacks: ptukey and qtukey as R's, from the integral of Copenhaver & Holland (1988),
// "Computation of the distribution of the maximum studentized range statistic with application to
// multiple significance testing of simple effects", J. Stat. Comput. Simul. 30, 1-15.
//
//   P(range of k iid N(0,1) <= w) = k * int phi(z) [Phi(z + w) - Phi(z)]^(k-1) dz
//   ptukey(q, k, df) = int_0^inf P(range <= q s) f_df(s) ds,  s = sqrt(chi2_df / df),
//   f_df(s) = 2 (df/2)^(df/2) s^(df-1) exp(-df s^2 / 2) / Gamma(df/2)
//
// Both integrals by piecewise 20-point Gauss-Legendre rules; the outer one in u = log s, and
// P(range <= w) read from per-k Chebyshev tables of its quadrature (built once per k, ~1 ms), so a
// call costs a few microseconds. Absolute error below 1e-15 (5.5e-16 measured) in P and in 1 - P
// against 34-digit quadrature for q 0.01..50, k 2..100, df 2..infinity, whole or not
// (tests/models/test_studentized_range_reference.cpp); Phi's complement is used where Phi is near
// 1 (no cancellation). qtukey inverts ptukey by bracketing and TOMS 748 to ~1e-12 relative.
// R's qtukey stops its secant iteration at |dq| < 1e-4, so it is only that precise
// (docs/mixed-model.md); feint's is exact to the quadrature.
//
// The upper tail (the Tukey p-value) as its own integral, not 1 - ptukey (which is exact to
// ~1e-16 absolute only, so 0 or all noise for p below ~1e-15; R's ptukey(lower.tail = FALSE),
// which emmeans uses, is 1 - P internally: 1.757850e-8 for the exact 1.757859e-8 at q = 12,
// k = 5, df = 30, 0 for 1.2e-14 at q = 12, k = 20, df = 1160):
//   P(range > w) = k int phi(z) Q(z)^(k-1) [1 - (1 - r)^(k-1)] dz,  r = Q(z + w) / Q(z)
// (the smallest of the k is at z with density k phi(z) Q(z)^(k-1); the range exceeds w unless the
// other k - 1 lie in [z, z + w]), with 1 - (1 - r)^(k-1) = -expm1((k - 1) log1p(-r)), and
//   ptukey_upper(q, k, df) = int_0^inf P(range > q s) f_df(s) ds.
// Every term is positive and to full relative precision: 1.2e-13 relative (P's condition number
// in q, ~q^2/2, is the limit) for P down to 1e-300 against 34-digit quadrature of the same
// identity, and within 7.8e-16 of 1 - ptukey on the 1,768-point grid; ~2x ptukey's time.
#pragma once

namespace feint::models {

/// P(Q <= q) for the range of `nmeans` >= 2 means studentized by an independent estimate with
/// `df` > 0 degrees of freedom (df = infinity: the range of normals). q <= 0 gives 0.
double ptukey(double q, double nmeans, double df);

/// P(Q > q), the upper tail (a Tukey p-value), computed as its own integral: to ~1e-13 relative
/// or better however small it is (down to 1e-300), where 1 - ptukey is only ~1e-16 absolute.
/// q <= 0 gives 1.
double ptukey_upper(double q, double nmeans, double df);

/// The quantile: the q with ptukey(q, nmeans, df) = p, p in (0, 1).
double qtukey(double p, double nmeans, double df);

}  // namespace feint::models

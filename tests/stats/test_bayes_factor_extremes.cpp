// JZS Bayes factors at the extremes (docs/bayes-factors.md): every kind feint computes (one-sample
// and paired, two-sample; two-sided, one-sided, interval, its complement, the interval null) at
// |t| = 0 to 1e4, n (n1, n2) = 2 to 1e5 and r = sqrt(2)/2, 1, against references computed here,
// independently of src/stats/bayes_factor.cpp:
//  * the definition: the noncentral t density integrated over its chi scale s (adaptive
//    Gauss–Kronrod, 61 points), then over theta = atan(delta / r), where the Cauchy prior is
//    uniform (tanh-sinh), in long double, on windows found from the integrands' unimodality; the
//    production code takes the one- and two-sided ones from Rouder's g integral, and the intervals
//    from the likelihood ratio written as an expectation over a Gamma law, in double;
//  * two-sided also by Rouder et al.'s (2009) g integral in 50 significant digits
//    (cpp_bin_float_50: the integrand as a product of powers, its exponent range holds e^345000),
//    which checks the first.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/tools/minima.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include "feint/stats/bayes_factor.hpp"

using namespace feint::stats;

namespace {

using Real = long double;
using Mp = boost::multiprecision::cpp_bin_float_50;

const Real kPiL = 3.141592653589793238462643383279502884L;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// t, N, nu, r and the constant of log(phi(t s - ncp) s f_S(s)) - log p(t | 0).
struct RefModel {
  Real t, n, nu, r, log_const;
};

RefModel ref_model(Real t, Real n, Real nu, Real r) {
  using std::lgamma, std::log, std::log1p;
  const Real log_p0 =
      lgamma((nu + 1) / 2) - lgamma(nu / 2) - log(nu * kPiL) / 2 - (nu + 1) / 2 * log1p(t * t / nu);
  // s = sqrt(V / nu), V ~ chi^2_nu: s f_S(s) = 2 (nu/2)^(nu/2) s^nu e^(-nu s^2 / 2) / Gamma(nu/2)
  const Real c = log(Real(2)) + nu / 2 * log(nu / 2) - lgamma(nu / 2) - log(2 * kPiL) / 2;
  return {t, n, nu, r, c - log_p0};
}

/// The end of the window from `mode` towards `end` for a unimodal log integrand that is `top` at
/// the mode: the first point, stepping out from the mode (doubling) and then on towards the end
/// (halving the rest), where it is 120 below the peak. Beyond it the integrand is smaller still.
template <class LogF>
Real window_end(LogF&& log_f, Real mode, Real top, Real end, Real first) {
  const Real span = end - mode;
  for (Real part = first; part < 0.5L; part *= 2)
    if (log_f(mode + part * span) < top - 120) return mode + part * span;
  for (Real rest = 0.5L; rest > 1e-18L; rest /= 2)
    if (log_f(end - rest * span) < top - 120) return end - rest * span;
  return end;
}

/// Adaptive Gauss–Kronrod (61 points) in long double from the mode to each window end.
template <class F>
Real integrate_around(F&& f, Real lo, Real mode, Real hi, Real tol) {
  using Rule = boost::math::quadrature::gauss_kronrod<Real, 61>;
  Real sum = 0;
  if (lo < mode) sum += Rule::integrate(f, lo, mode, 8, tol);
  if (mode < hi) sum += Rule::integrate(f, mode, hi, 8, tol);
  return sum;
}

/// log p(t | delta sqrt(N)) - log p(t | 0), p(t | ncp) = int_0^inf phi(t s - ncp) s f_S(s) ds. The
/// log integrand has second derivative -(t^2 + nu) - nu / s^2 < 0: one mode (a quadratic's root).
Real ref_log_lr(const RefModel& m, Real delta) {
  const Real ncp = delta * std::sqrt(m.n), a = m.t * m.t + m.nu, b = m.t * ncp;
  const Real disc = std::sqrt(b * b + 4 * a * m.nu);
  const Real mode = b >= 0 ? (b + disc) / (2 * a) : 2 * m.nu / (disc - b);
  const Real z0 = m.t * mode - ncp;
  const Real top = -z0 * z0 / 2 + m.nu * std::log(mode) - m.nu * mode * mode / 2;
  // relative to the mode, so that terms of 1e19 (huge ncp) do not round to noise of order 1
  auto lw = [&](Real s) {
    if (!(s > 0)) return -std::numeric_limits<Real>::infinity();
    const Real ds = s - mode;
    return -m.t * ds * (m.t * (s + mode) - 2 * ncp) / 2 + m.nu * std::log(s / mode) -
           m.nu * ds * (s + mode) / 2;
  };
  auto f = [&](Real s) { return std::exp(lw(s)); };
  // the curvature bounds the integrand's width: within 13 / sqrt(t^2 + nu) it has fallen by 84
  const Real width = 13 / std::sqrt(a), first = 1e-3L / std::sqrt(a + m.nu / (mode * mode)) / width;
  const Real lo = window_end(lw, mode, Real(0), std::max(Real(0), mode - width), first);
  const Real hi = window_end(lw, mode, Real(0), mode + width, first);
  // (the tolerance is on Boost's error estimate, which is far above the error: from a depth of 0 to
  // 8 the result moves by 1e-12 where the estimate says 1e-11, the rounding of nu log(s / mode))
  Real sum = integrate_around(f, lo, mode, hi, 1e-10L);
  // at an ncp of 1e19 (theta next to +-pi/2) the window is below the resolution of s; LR is
  // e^-1e30 there, and any width will do
  if (!(sum > 0)) sum = 1 / std::sqrt(a);
  return top + std::log(sum) + m.log_const;
}

/// log LR at theta = atan(delta / r); at +-pi/2 (rounded, tan may even have the wrong sign) its
/// limit, 0 for LR (log LR is concave in delta).
Real ref_log_lr_theta(const RefModel& m, Real theta) {
  return std::fabs(theta) < kPiL / 2 ? ref_log_lr(m, m.r * std::tan(theta))
                                     : -std::numeric_limits<Real>::infinity();
}

/// The theta where LR is largest. log LR is concave in delta, so LR is unimodal in theta: Brent's
/// minimisation finds its one mode.
Real ref_theta_mode(const RefModel& m) {
  auto minus = [&](Real theta) { return -ref_log_lr_theta(m, theta); };
  return boost::math::tools::brent_find_minima(minus, -kPiL / 2, kPiL / 2, 50).first;
}

/// log of int LR(r tan theta) d theta over theta in [atan(lo / r), atan(hi / r)], given the mode of
/// LR on the whole line: on the piece its mode is the nearer end if the mode is outside.
Real ref_log_theta(const RefModel& m, Real lo, Real hi, Real line_mode) {
  const Real a = std::atan(lo / m.r), b = std::atan(hi / m.r), mode = std::clamp(line_mode, a, b);
  auto log_f = [&](Real theta) { return ref_log_lr_theta(m, theta); };
  const Real top = log_f(mode);
  // tanh-sinh: near the poles of tan the integrand in theta has an essential singularity, which it
  // resolves (and windows: no nodes crowd at the poles, where delta is 1e19). Boost's two-argument
  // form (x, distance to the nearer end) is the one that may evaluate at an end.
  auto f = [&](Real theta, Real) { return std::exp(log_f(theta) - top); };
  // (not const: Boost 1.74's integrate is not a const member.) Nodes stop 1e-30 of the length from
  // the ends, not 1e-4930 (long double's least): half the nodes, and the integrand there is either
  // below e^-120 (a window's end) or smooth (the mode).
  static boost::math::quadrature::tanh_sinh<Real> rule(15, 1e-30L);
  Real sum = 0;
  if (mode > a) sum += rule.integrate(f, window_end(log_f, mode, top, a, 1e-9L), mode, 1e-11L);
  if (mode < b) sum += rule.integrate(f, mode, window_end(log_f, mode, top, b, 1e-9L), 1e-11L);
  return top + std::log(sum);
}

/// log(sum of exp(x)) over xs.
Real log_sum_exp(const std::vector<Real>& xs) {
  const Real m = *std::max_element(xs.begin(), xs.end());
  Real s = 0;
  for (Real x : xs) s += std::exp(x - m);
  return m + std::log(s);
}

/// Two-sided log BF10 by Rouder et al.'s (2009) eq. 1 over x = log g, in 50 digits: the window from
/// a long-double scan (the integrand falls like exp(-r^2 e^-x / 2) to the left and like e^-x to the
/// right), then tanh-sinh on each side of the peak.
Real ref_log_bf_two_sided_g(Real t, Real n, Real nu, Real r) {
  auto log_f = [&](Real x) {
    const Real g = std::exp(x);
    return -std::log1p(n * g) / 2 -
           (nu + 1) / 2 * (std::log1p(t * t / ((1 + n * g) * nu)) - std::log1p(t * t / nu)) -
           x / 2 - r * r / (2 * g);
  };
  Real best = -std::numeric_limits<Real>::infinity(), xm = 0;
  for (Real x = -60; x <= 160; x += 0.05L)
    if (log_f(x) > best) best = log_f(x), xm = x;
  Real lo = xm, hi = xm;
  while (log_f(lo) > best - 90) lo -= 0.25L;
  while (log_f(hi) > best - 90) hi += 0.25L;
  const Mp mt = Mp(t), mn = Mp(n), mnu = Mp(nu), mr = Mp(r), mbest = Mp(best);
  const Mp null_part = pow(1 + mt * mt / mnu, (mnu + 1) / 2);
  auto f = [&](const Mp& x, const Mp&) {
    const Mp g = exp(x), s2 = 1 + mn * g;
    return pow(1 + mt * mt / (s2 * mnu), -(mnu + 1) / 2) * null_part / sqrt(s2 * g) *
           exp(-mr * mr / (2 * g) - mbest);
  };
  // (not const: Boost 1.74's integrate is not a const member; nodes stop 1e-40 from the ends, not
  // at cpp_bin_float_50's least number, 2^-2^31, which makes every row of nodes long)
  static boost::math::quadrature::tanh_sinh<Mp> rule(15, Mp(1e-40));
  const Mp sum =
      rule.integrate(f, Mp(lo), Mp(xm), Mp(1e-13)) + rule.integrate(f, Mp(xm), Mp(hi), Mp(1e-13));
  // the prior's constant r / sqrt(2 pi) (the g^-3/2 of the prior and the dg = g dx leave g^-1/2)
  return best + static_cast<Real>(log(sum)) + std::log(r) - std::log(2 * kPiL) / 2;
}

/// The log BF10 of each kind, by the reference.
struct Kinds {
  Real two_sided, greater, less, inside, outside, range;
};

constexpr double kMargin = 0.1;                   // the interval [-0.1, 0.1] and its complement
constexpr double kRangeLo = 0.2, kRangeHi = 0.5;  // an interval away from 0

/// Every kind from five pieces of the theta line: delta below -0.1, in [-0.1, 0], [0, 0.1], above
/// 0.1, and in [0.2, 0.5].
Kinds reference_kinds(double t, double n, double nu, double r) {
  const RefModel m = ref_model(t, n, nu, r);
  const Real mode = ref_theta_mode(m);
  const Real below = ref_log_theta(m, -kInf, -kMargin, mode),
             inside_less = ref_log_theta(m, -kMargin, 0, mode),
             inside_greater = ref_log_theta(m, 0, kMargin, mode),
             above = ref_log_theta(m, kMargin, kInf, mode),
             range = ref_log_theta(m, kRangeLo, kRangeHi, mode);
  auto theta = [&](Real d) { return std::atan(d / Real(r)); };
  const Real inside_mass = theta(kMargin) - theta(-kMargin);
  Kinds k{};
  k.two_sided = log_sum_exp({below, inside_less, inside_greater, above}) - std::log(kPiL);
  k.less = log_sum_exp({below, inside_less}) - std::log(kPiL / 2);
  k.greater = log_sum_exp({inside_greater, above}) - std::log(kPiL / 2);
  k.inside = log_sum_exp({inside_less, inside_greater}) - std::log(inside_mass);
  k.outside = log_sum_exp({below, above}) - std::log(kPiL - inside_mass);
  k.range = range - std::log(theta(kRangeHi) - theta(kRangeLo));
  return k;
}

struct Design {
  bool two_sample;
  std::size_t n1, n2;
  double n_eff() const {
    const double a = static_cast<double>(n1), b = static_cast<double>(n2);
    return two_sample ? a * b / (a + b) : a;
  }
  double df() const {
    return two_sample ? static_cast<double>(n1 + n2) - 2 : static_cast<double>(n1) - 1;
  }
  std::string name() const {
    return two_sample ? "two-sample n1=" + std::to_string(n1) + " n2=" + std::to_string(n2)
                      : "one-sample n=" + std::to_string(n1);
  }
};

/// feint's log BF10 of each kind, through the public functions (a paired test is the one-sample
/// one on the differences).
Kinds feint_kinds(const Design& d, double t, double r) {
  auto point = [&](Alternative alt) {
    return d.two_sample ? jzs_bf_two_sample(t, d.n1, d.n2, alt, r).log_bf10
                        : jzs_bf_one_sample(t, d.n1, alt, r).log_bf10;
  };
  Kinds k{};
  k.two_sided = point(Alternative::two_sided);
  k.greater = point(Alternative::greater);
  k.less = point(Alternative::less);
  k.inside = jzs_log_bf(t, d.n_eff(), d.df(), r, -kMargin, kMargin);
  k.outside = jzs_log_bf_complement(t, d.n_eff(), d.df(), r, -kMargin, kMargin);
  k.range = jzs_log_bf(t, d.n_eff(), d.df(), r, kRangeLo, kRangeHi);
  return k;
}

const std::vector<double> kTs{0, 1e-3, 1, 5, 30, 500, 1e4};
const std::vector<double> kRs{kJzsMediumScale, 1.0};

std::vector<Design> one_sample_designs() {
  std::vector<Design> out;
  for (std::size_t n : {2u, 3u, 10u, 1000u, 100000u}) out.push_back({false, n, 0});
  return out;
}

std::vector<Design> two_sample_designs() {
  std::vector<Design> out;
  for (std::size_t n : {2u, 3u, 10u, 1000u, 100000u}) out.push_back({true, n, n});
  out.push_back({true, 2, 100000});
  out.push_back({true, 10, 1000});
  return out;
}

/// |got - want| relative to max(1, |want|): relative error of BF where log BF is small, of log BF
/// where it is large.
double error(Real got, Real want) {
  return static_cast<double>(std::fabs(got - want) / std::max(Real(1), std::fabs(want)));
}

/// Every design x 7 values of t x 2 prior scales x 7 kinds (the interval null is the complement
/// over the inside) against the reference, to 1e-8 (the contract is 1e-6); prints the worst errors.
/// The g-integral reference (the slow one; it checks the reference, not feint) runs where `by_g`
/// says.
template <class ByG>
void check_grid(const std::vector<Design>& designs, ByG&& by_g) {
  const char* names[] = {"two-sided", "greater",    "less",         "inside [-0.1, 0.1]",
                         "outside",   "[0.2, 0.5]", "interval null"};
  double worst[7] = {0}, worst_g = 0;
  for (const Design& d : designs) {
    for (double t : kTs) {
      for (double r : kRs) {
        const std::string what = d.name() + " t=" + std::to_string(t) + " r=" + std::to_string(r);
        const Kinds ref = reference_kinds(t, d.n_eff(), d.df(), r);
        if (by_g(d, r)) {
          const Real g = ref_log_bf_two_sided_g(t, d.n_eff(), d.df(), r);
          worst_g = std::max(worst_g, error(g, ref.two_sided));
          EXPECT_LT(error(g, ref.two_sided), 1e-10) << what << ": the two references";
        }
        const Kinds got = feint_kinds(d, t, r);
        const Real null_got = jzs_bf_interval_null(t, d.n_eff(), d.df(), kMargin, r).log_bf10;
        const Real gots[] = {got.two_sided, got.greater, got.less, got.inside,
                             got.outside,   got.range,   null_got};
        const Real wants[] = {
            ref.two_sided,           ref.greater, ref.less, ref.inside, ref.outside, ref.range,
            ref.outside - ref.inside};
        for (int k = 0; k < 7; ++k) {
          ASSERT_TRUE(std::isfinite(static_cast<double>(gots[k]))) << what << " " << names[k];
          const double e = error(gots[k], wants[k]);
          worst[k] = std::max(worst[k], e);
          EXPECT_LT(e, 1e-8) << what << " " << names[k] << ": feint "
                             << static_cast<double>(gots[k]) << ", reference "
                             << static_cast<double>(wants[k]);
        }
      }
    }
  }
  for (int k = 0; k < 7; ++k) std::printf("JZS %-20s worst error %.1e\n", names[k], worst[k]);
  std::printf("JZS two-sided: the two references differ by at most %.1e\n", worst_g);
}

}  // namespace

// One-sample (and paired: the one-sample test of the differences), n = 2, 3, 10, 1000, 1e5; the
// g-integral reference at r = sqrt(2)/2.
TEST(BayesFactorExtremes, OneSampleEveryKindAgreesWithTheHighPrecisionReference) {
  check_grid(one_sample_designs(), [](const Design&, double r) { return r == kJzsMediumScale; });
}

// Two-sample, n1 = n2 = 2, 3, 10, 1000, 1e5 and (2, 1e5), (10, 1000); the g-integral reference at
// r = sqrt(2)/2.
TEST(BayesFactorExtremes, TwoSampleEveryKindAgreesWithTheHighPrecisionReference) {
  check_grid(two_sample_designs(), [](const Design&, double r) { return r == kJzsMediumScale; });
}

// A negative t mirrors a positive one: BF(delta > 0 | -t) = BF(delta < 0 | t), and an interval
// mirrors its reflection. feint computes each side separately, so this is a check, not an identity.
TEST(BayesFactorExtremes, NegativeTMirrorsPositiveT) {
  for (double n : {3.0, 1e5}) {
    for (double t : {1e-3, 5.0, 500.0, 1e4}) {
      const std::string what = "n=" + std::to_string(n) + " t=" + std::to_string(t);
      auto bf = [&](double tt, double lo, double hi) {
        return jzs_log_bf(tt, n, n - 1, kJzsMediumScale, lo, hi);
      };
      EXPECT_LT(error(bf(-t, 0, kInf), bf(t, -kInf, 0)), 1e-9) << what;
      EXPECT_LT(error(bf(-t, -kRangeHi, -kRangeLo), bf(t, kRangeLo, kRangeHi)), 1e-9) << what;
      EXPECT_LT(error(bf(-t, -kMargin, kMargin), bf(t, -kMargin, kMargin)), 1e-9) << what;
      EXPECT_LT(error(jzs_log_bf_complement(-t, n, n - 1, kJzsMediumScale, -kMargin, kMargin),
                      jzs_log_bf_complement(t, n, n - 1, kJzsMediumScale, -kMargin, kMargin)),
                1e-9)
          << what;
    }
  }
}

// At t = 1e4, n = 1e5 every kind returns (before, the interval integrals ran for minutes there)
// with a finite log BF; where BF itself overflows a double, bf10() is +inf and bf01() 0, the log
// still exact.
TEST(BayesFactorExtremes, EveryKindReturnsAtTheLargestTAndN) {
  const std::size_t n = 100000;
  const double neff = 1e5, df = neff - 1;
  for (double r : kRs) {
    for (double t : {1e4, -1e4}) {
      for (Alternative alt : {Alternative::two_sided, Alternative::greater, Alternative::less}) {
        EXPECT_TRUE(std::isfinite(jzs_bf_one_sample(t, n, alt, r).log_bf10));
        EXPECT_TRUE(std::isfinite(jzs_bf_two_sample(t, n, n, alt, r).log_bf10));
      }
      EXPECT_TRUE(std::isfinite(jzs_log_bf(t, neff, df, r, -kMargin, kMargin)));
      EXPECT_TRUE(std::isfinite(jzs_log_bf(t, neff, df, r, kRangeLo, kRangeHi)));
      EXPECT_TRUE(std::isfinite(jzs_log_bf(t, neff, df, r, -kRangeHi, -kRangeLo)));
      EXPECT_TRUE(std::isfinite(jzs_log_bf_complement(t, neff, df, r, -kMargin, kMargin)));
      const BayesFactor null = jzs_bf_interval_null(t, neff, df, kMargin, r);
      EXPECT_TRUE(std::isfinite(null.log_bf10));
      EXPECT_GT(null.log_bf10, 3e5);  // delta far outside [-0.1, 0.1]: e^335000 for H1
      EXPECT_EQ(null.bf10(), kInf);
      EXPECT_EQ(null.bf01(), 0.0);
    }
  }
}

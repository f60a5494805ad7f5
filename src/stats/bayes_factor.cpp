// The JZS Bayes factor: see feint/stats/bayes_factor.hpp for the formulas and references.
#include "feint/stats/bayes_factor.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include <boost/math/distributions/students_t.hpp>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::stats {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = std::numbers::pi;

void check_args(double t, double n_eff, double df, double r) {
  if (!std::isfinite(t)) throw InvalidData(fmt::format("Bayes factor: t = {} is not finite", t));
  if (!(n_eff > 0) || !std::isfinite(n_eff))
    throw UsageError(fmt::format("Bayes factor: effective sample size {} must be positive", n_eff));
  if (!(df > 0) || !std::isfinite(df))
    throw UsageError(fmt::format("Bayes factor: degrees of freedom {} must be positive", df));
  if (!(r > 0) || !std::isfinite(r))
    throw UsageError(fmt::format("Bayes factor: prior scale r = {} must be positive", r));
}

// Integrals of exp(f) for a unimodal f: from the mode outwards, in pieces over which f changes by
// at most kPieceStep (Gauss–Kronrod 21 on each is then exact to double precision), until f has
// fallen kTailDrop below its peak. No piece is placed by a guess of the width: at |t| in the
// thousands such guesses left a narrow peak to blind bisection for minutes.
constexpr double kPieceStep = 6;  // the log integrand changes by at most this over a piece
constexpr double kTailDrop = 46;  // a walk stops e^-46 = 1e-20 below the peak

template <std::size_t M>
using Sums = std::array<double, M>;

/// Adds Gauss–Kronrod 21 on [a, b] of `values` (M integrands on the same nodes) to `total`; halves
/// the piece (at most three times: beyond, the difference is rounding in the integrand) while the
/// embedded Gauss 10 estimate of the first integrand differs by more than `tol` (relative) +
/// `abs_tol`.
template <std::size_t M, class Values>
void add_gauss_kronrod(Values& values, double a, double b, double tol, double abs_tol,
                       Sums<M>& total, int depth = 0) {
  using Kronrod = boost::math::quadrature::gauss_kronrod<double, 21>;
  using Gauss = boost::math::quadrature::gauss<double, 10>;
  const double c = (a + b) / 2, h = (b - a) / 2;
  Sums<M> k{};
  double gauss = 0;
  for (std::size_t i = 0; i < Kronrod::abscissa().size(); ++i) {
    const double x = Kronrod::abscissa()[i];
    for (int side = 0; side < (x == 0 ? 1 : 2); ++side) {
      const Sums<M> v = values(side == 0 ? c + h * x : c - h * x);
      for (std::size_t m = 0; m < M; ++m) k[m] += Kronrod::weights()[i] * v[m];
      if (i % 2 == 1) gauss += Gauss::weights()[i / 2] * v[0];  // Gauss nodes: odd Kronrod ones
    }
  }
  if (std::fabs(k[0] - gauss) * h > tol * std::fabs(k[0] * h) + abs_tol && depth < 3) {
    add_gauss_kronrod(values, a, c, tol, abs_tol, total, depth + 1);
    add_gauss_kronrod(values, c, b, tol, abs_tol, total, depth + 1);
    return;
  }
  for (std::size_t m = 0; m < M; ++m) total[m] += h * k[m];
}

/// Adds the integral from x0, the mode of a unimodal log integrand f (f(x0) = f0, `values` scaled
/// by e^-f0), towards `end`, starting with pieces of length h. A piece where f is D below its peak
/// may let f change by kPieceStep + D / 2: its error relative to the whole stays below e^-D times
/// its own. A piece is at most half as long as its distance from `pole` (the integrand's
/// singularity beyond `end`, if any), so that Gauss–Kronrod converges on it.
template <std::size_t M, class LogF, class Values>
void walk_from_mode(LogF& log_f, Values& values, double x0, double f0, double end, double h,
                    double tol, double pole, Sums<M>& total) {
  const double abs_tol = tol * 1e-3 * h;  // h is about the peak's width, the whole at least about h
  double x = x0, fx = f0;
  for (int piece = 0; piece < 2000 && x != end; ++piece) {
    double x1 = x, f1 = fx;
    h = std::min(h, std::fabs(pole - x) / 2);
    for (int tries = 0; tries < 100; ++tries) {
      x1 = end > x ? std::min(x + h, end) : std::max(x - h, end);
      f1 = log_f(x1);
      if (std::fabs(f1 - fx) <= kPieceStep + (f0 - std::max(fx, f1)) / 2) break;
      h /= 2;
    }
    if (x1 == x) break;
    add_gauss_kronrod(values, std::min(x, x1), std::max(x, x1), tol, abs_tol, total);
    if (!(f1 >= f0 - kTailDrop)) break;
    if (std::fabs(f1 - fx) < kPieceStep / 2) h *= 2;
    x = x1;
    fx = f1;
  }
}

/// log I_x(a, b), the regularised incomplete beta, for x < (a + 1) / (a + b + 2), by its continued
/// fraction (modified Lentz; Press et al., Numerical Recipes, 3rd ed., sec. 6.4) with the prefactor
/// x^a (1 - x)^b / (a B(a, b)) in logs: exact where I_x itself underflows a double.
double log_ibeta_lower(double a, double b, double x) {
  const double log_front = a * std::log(x) + b * std::log1p(-x) - std::log(a) -
                           (std::lgamma(a) + std::lgamma(b) - std::lgamma(a + b));
  constexpr double kTiny = 1e-300;
  const double qab = a + b, qap = a + 1, qam = a - 1;
  double c = 1, d = 1 - qab * x / qap;
  if (std::fabs(d) < kTiny) d = kTiny;
  d = 1 / d;
  double h = d;
  for (int m = 1; m <= 100000; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((qam + m2) * (a + m2));
    d = 1 + aa * d;
    if (std::fabs(d) < kTiny) d = kTiny;
    c = 1 + aa / c;
    if (std::fabs(c) < kTiny) c = kTiny;
    d = 1 / d;
    h *= d * c;
    aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
    d = 1 + aa * d;
    if (std::fabs(d) < kTiny) d = kTiny;
    c = 1 + aa / c;
    if (std::fabs(c) < kTiny) c = kTiny;
    d = 1 / d;
    const double del = d * c;
    h *= del;
    if (std::fabs(del - 1) < 1e-16) break;
  }
  return log_front + std::log(h);
}

/// log T_nu(z), the Student t CDF in logs, at any z: from the upper tail for z >= 0 (log1p keeps it
/// exact near 1), Boost's CDF in the lower tail while it is a normal double, and beyond that
/// T_nu(z) = I_{nu / (nu + z^2)}(nu / 2, 1 / 2) / 2 in logs (the one-sided Bayes factors multiply
/// a likelihood ratio of e^5000 by such a tail at large t).
double log_t_cdf(const boost::math::students_t_distribution<double>& dist, double nu, double z) {
  if (z >= 0) return std::log1p(-boost::math::cdf(dist, -z));
  const double p = boost::math::cdf(dist, z);
  if (p > 1e-280) return std::log(p);
  return std::log(0.5) + log_ibeta_lower(nu / 2, 0.5, nu / (nu + z * z));
}

/// Rouder's g integral over x = log g, for the whole line (side = 0) or one half of it (side = +1:
/// delta > 0, side = -1: delta < 0).
///
/// The Cauchy(0, r) prior is the mixture delta | g ~ N(0, g), g ~ InvGamma(1/2, r^2 / 2). Given g,
/// the whole line gives Rouder et al.'s (2009) likelihood ratio t_nu(t / sigma) / (sigma t_nu(t)),
/// sigma^2 = 1 + n g. Truncating delta to one side (and doubling the prior there) makes the
/// joint of the numerator's normal and delta a skew normal with shape lambda = sqrt(n g), and its
/// mixture over the chi scale of t Azzalini and Capitanio's (2003) skew t: the one-sided ratio is
/// the whole-line one times 2 T_{nu+1}(side lambda u sqrt((nu + 1) / (u^2 + nu))), u = t / sigma.
/// So a one-sided Bayes factor is one smooth integral over g at any t and n, as the two-sided one;
/// the two halves add up to twice the whole line exactly (T(z) + T(-z) = 1).
double log_bf_point(double t, double n, double nu, double r, int side = 0) {
  const double log_null = -(nu + 1) / 2 * std::log1p(t * t / nu);
  const double c = std::log(r) - 0.5 * std::log(2 * kPi);
  const boost::math::students_t_distribution<double> t_next(nu + 1);
  auto lf = [&](double x) {
    const double g = std::exp(x);
    double v = -0.5 * std::log1p(n * g) - (nu + 1) / 2 * std::log1p(t * t / ((1 + n * g) * nu)) +
               c - 0.5 * x - r * r / (2 * g) - log_null;
    if (side != 0) {
      const double u = t / std::sqrt(1 + n * g);
      const double lambda = std::sqrt(n * g);
      v += std::log(2.0) +
           log_t_cdf(t_next, nu + 1, side * lambda * u * std::sqrt((nu + 1) / (u * u + nu)));
    }
    return v;
  };
  // The integrand is smooth and unimodal in x, its peak at least about 1 wide; locate the peak on a
  // grid and walk out from it (within +-40 it falls below e^-40: like e^-x above, exp(-e^-x)
  // below).
  double best = -kInf, xm = 0;
  for (double x = -40; x <= 40; x += 0.25) {
    const double v = lf(x);
    if (v > best) best = v, xm = x;
  }
  auto log_f = [&](double x) {
    const double v = lf(x) - best;
    return std::isnan(v) ? -kInf : v;
  };
  auto values = [&](double x) { return Sums<1>{std::exp(log_f(x))}; };
  // lf carries rounding of about 1e-15 of log BF: pieces are not split for differences of that
  // order
  const double tol = 1e-10 + 1e-14 * std::fabs(best);
  Sums<1> s{};
  walk_from_mode(log_f, values, xm, 0.0, xm - 40, 0.25, tol, -kInf, s);
  walk_from_mode(log_f, values, xm, 0.0, xm + 40, 0.25, tol, kInf, s);
  return best + std::log(s[0]);
}

// ---- Intervals
// ----------------------------------------------------------------------------------- BF_I0 = int_I
// p(t | delta) cauchy(delta; r) d delta / (P(delta in I) p(t | 0)). In theta = atan(delta / r) the
// Cauchy prior is uniform, so the numerator is int LR(r tan theta) d theta / pi, LR(delta) = p(t |
// ncp = delta sqrt(N)) / p(t | 0) the noncentral t likelihood ratio. Written as a normal mixture (t
// s - ncp ~ N(0, 1) given the chi scale s), with the law of s given t under delta = 0:
//   LR = E[exp(ncp t s - ncp^2 / 2)],  s = s0 sqrt(Y / k),  Y ~ Gamma(k, 1),
// k = (nu + 1) / 2, s0 = sqrt((nu + 1) / (t^2 + nu)). So LR(0) = 1 exactly, and no density is taken
// in its far tail (Boost's and R's noncentral t densities lose their accuracy there). log LR is
// concave in delta (a Gaussian convolved with a log-concave law), so the integrand is unimodal in
// theta, and the inner one in u = log(Y / k) has a single mode in closed form. Both integrals start
// at the mode and walk outwards in pieces over which the log integrand changes by at most
// kPieceStep (Gauss–Kronrod 21 on each is then exact to double precision), until it has fallen
// kTailDrop below its peak: no piece is placed by a guess of the width, which at |t| in the
// thousands used to leave a narrow peak to blind bisection for minutes.

/// log Gamma(k) - ((k - 1/2) log k - k + log(2 pi) / 2), Stirling's remainder, without the
/// cancellation of the difference at large k (series: Abramowitz & Stegun 6.1.41).
double stirling_remainder(double k) {
  if (k < 10) return std::lgamma(k) - ((k - 0.5) * std::log(k) - k + 0.5 * std::log(2 * kPi));
  const double z = 1 / (k * k);
  return (1.0 / 12 - z * (1.0 / 360 - z * (1.0 / 1260 - z * (1.0 / 1680 - z / 1188)))) / k;
}

/// What the interval integrals need of t, N, nu and r.
struct JzsData {
  double t, n, nu, r;
  double k;         ///< (nu + 1) / 2
  double ts0;       ///< t s0, s0 = sqrt((nu + 1) / (t^2 + nu))
  double log_norm;  ///< log of the Gamma(k) density's constant in u = log(Y / k)
  double nu_share;  ///< nu / (t^2 + nu)
  double t_scale;   ///< 2 k / |ts0| (infinite at t = 0)
  JzsData(double t_, double n_, double nu_, double r_) : t(t_), n(n_), nu(nu_), r(r_) {
    k = (nu + 1) / 2;
    ts0 = t * std::sqrt((nu + 1) / (t * t + nu));
    nu_share = nu / (t * t + nu);
    t_scale = 2 * k / std::fabs(ts0);
    log_norm = 0.5 * std::log(k / (2 * kPi)) - stirling_remainder(k);
  }
};

/// log LR(delta) and its first two derivatives in delta.
struct LikelihoodRatio {
  double log_lr, d1, d2;
};

/// e^v - 1 - v without the cancellation of expm1(v) - v at small v (the Taylor series to v^10).
double expm1_minus_v(double v) {
  if (std::fabs(v) > 0.1) return std::expm1(v) - v;
  double term = 1, sum = 1;
  for (int j = 3; j <= 10; ++j) sum += (term *= v / j);
  return v * v / 2 * sum;
}

/// LR(delta) = E[exp(ncp t s - ncp^2 / 2)] over u = log(Y / k), whose log density is
/// -k (e^u - 1 - u) + log_norm. With x = t s - ncp the derivatives come from the same integral:
/// d log LR / d ncp = E_w[x], d^2 / d ncp^2 = Var_w(x) - 1 (w the tilted law), times sqrt(N) and N.
/// The log integrand is taken relative to its mode u0, in v = u - u0: at t = 10^4, N = 10^5 its
/// terms are 10^8 and cancel to 10^5, and from the mode their rounding would be noise of 10^-8.
LikelihoodRatio likelihood_ratio(const JzsData& d, double delta) {
  const double ncp = delta * std::sqrt(d.n), b = ncp * d.ts0, k = d.k;
  // the mode in q = e^(u/2): k q^2 - (b / 2) q - k = 0, its positive root without cancellation
  const double root = std::hypot(b / 4, k);
  const double q0 = b >= 0 ? (b / 4 + root) / k : k / (root - b / 4);
  // x0 = t s - ncp at the mode, ts0 q0 - ncp; with the mode's equation also
  // (2 k / ts0) (1 / q0 - q0 nu / (t^2 + nu)): of the two, the one with the smaller terms (they
  // cancel where the data favour this delta; at t = 10^4, N = 2 the first would leave 10^-12 of
  // 10^4)
  const double x0 =
      std::fabs(d.ts0 * q0) + std::fabs(ncp) <= d.t_scale / q0 + d.t_scale * q0 * d.nu_share
          ? d.ts0 * q0 - ncp
          : (2 * k / d.ts0) * (1 / q0 - q0 * d.nu_share);
  // at the mode, k q0^2 = (b / 2) q0 + k: the log integrand there is b q0 / 2 + 2 k log q0 - ncp^2
  // / 2
  const double f0 = ncp / 2 * x0 + 2 * k * std::log(q0) + d.log_norm;
  const double kq2 = k * q0 * q0, bq = b * q0, linear = k - kq2 + bq / 2;  // linear: 0 but rounding
  auto log_f = [&](double v) {                                             // relative to f0
    const double f = -kq2 * expm1_minus_v(v) + bq * expm1_minus_v(v / 2) + linear * v;
    return std::isnan(f) ? -kInf : f;
  };
  auto values = [&](double v) {
    const double w = std::exp(log_f(v)), x = d.ts0 * q0 * std::expm1(v / 2);  // x - x0
    return Sums<3>{w, w * x, w * x * x};
  };
  // the curvature at the mode is k (q0^2 + 1) / 2; to the left the log density falls like k u, to
  // the right at least with that curvature
  const double sd = std::sqrt(2 / (k * (q0 * q0 + 1)));
  Sums<3> s{};
  walk_from_mode(log_f, values, 0.0, 0.0, -60 - 100 / k, sd, 1e-13, -kInf, s);
  walk_from_mode(log_f, values, 0.0, 0.0, 60.0, sd, 1e-13, kInf, s);
  const double mean = s[1] / s[0];
  return {f0 + std::log(s[0]), std::sqrt(d.n) * (x0 + mean), d.n * (s[2] / s[0] - mean * mean - 1)};
}

/// The delta in [lo, hi] where LR is largest, and LR there: an end if LR falls away from it,
/// otherwise Newton's method on the concave log LR, kept inside a bracket.
std::pair<double, LikelihoodRatio> likelihood_mode(const JzsData& d, double lo, double hi) {
  if (std::isfinite(lo)) {
    const LikelihoodRatio at = likelihood_ratio(d, lo);
    if (at.d1 <= 0) return {lo, at};
  }
  if (std::isfinite(hi)) {
    const LikelihoodRatio at = likelihood_ratio(d, hi);
    if (at.d1 >= 0) return {hi, at};
  }
  double left = lo, right = hi;
  double delta = d.t / std::sqrt(d.n);  // the mode for large nu
  if (!(delta > lo && delta < hi))
    delta = std::isfinite(lo) && std::isfinite(hi) ? (lo + hi) / 2
            : std::isfinite(lo)                    ? lo + 1
                                                   : hi - 1;
  LikelihoodRatio at{};
  for (int it = 0; it < 300; ++it) {
    at = likelihood_ratio(d, delta);
    const double sd = 1 / std::sqrt(std::max(-at.d2, 1e-300));
    if (std::fabs(at.d1) * sd < 1e-3) break;  // within 1e-3 sd of the mode
    (at.d1 > 0 ? left : right) = delta;
    double next = delta - at.d1 / at.d2;
    if (!(next > left && next < right)) {
      if (std::isfinite(left) && std::isfinite(right))
        next = left + (right - left) / 2;
      else if (std::isfinite(left))
        next = left + 2 * std::max(std::fabs(left), sd);
      else
        next = right - 2 * std::max(std::fabs(right), sd);
    }
    if (next == delta) break;
    delta = next;
  }
  return {delta, at};
}

/// log of int LR(r tan theta) d theta over theta from atan(lo / r) to atan(hi / r).
double log_theta_integral(const JzsData& d, double lo, double hi) {
  // a half line by the g integral (as jzs_log_bf), whose theta range has length pi / 2
  if (lo == 0 && std::isinf(hi)) return log_bf_point(d.t, d.n, d.nu, d.r, +1) + std::log(kPi / 2);
  if (std::isinf(lo) && hi == 0) return log_bf_point(d.t, d.n, d.nu, d.r, -1) + std::log(kPi / 2);
  const double a = std::atan(lo / d.r), b = std::atan(hi / d.r);
  const auto [delta0, at] = likelihood_mode(d, lo, hi);
  const double theta0 = std::clamp(std::atan(delta0 / d.r), a, b);
  if (!std::isfinite(at.log_lr)) return -kInf;
  // the first piece from the slope and curvature in theta (d delta / d theta = (r^2 + delta^2) / r)
  const double jac = (d.r * d.r + delta0 * delta0) / d.r;
  const double slope = at.d1 * jac, curv = at.d2 * jac * jac + at.d1 * 2 * delta0 * jac / d.r;
  const double h =
      std::min(b - a, 1 / std::sqrt(std::max({std::fabs(curv), slope * slope, 1e-300})));
  auto log_f = [&](double theta) {
    const double v = likelihood_ratio(d, d.r * std::tan(theta)).log_lr;
    return std::isnan(v) ? -kInf : v;
  };
  auto values = [&](double theta) { return Sums<1>{std::exp(log_f(theta) - at.log_lr)}; };
  Sums<1> s{};
  // log LR carries rounding of about 1e-15 of its size (3e-10 at t = 10^4, N = 10^5): pieces are
  // not split for differences of that order
  const double tol = 1e-10 + 1e-14 * std::fabs(at.log_lr);
  // the poles of tan at -+ pi / 2: near them, pieces shrink geometrically
  walk_from_mode(log_f, values, theta0, at.log_lr, a, h, tol, -kPi / 2, s);
  walk_from_mode(log_f, values, theta0, at.log_lr, b, h, tol, kPi / 2, s);
  return at.log_lr + std::log(s[0]);
}

/// log BF of delta in [lo, hi] against 0.
double log_bf_interval(double t, double n, double nu, double r, double lo, double hi) {
  const double a = std::atan(lo / r), b = std::atan(hi / r);
  return log_theta_integral(JzsData(t, n, nu, r), lo, hi) - std::log(b - a);
}

}  // namespace

std::string BayesFactor::describe() const {
  std::string h1;
  if (std::isinf(lo) && std::isinf(hi))
    h1 = "delta != 0";
  else if (lo == 0 && std::isinf(hi))
    h1 = "delta > 0";
  else if (std::isinf(lo) && hi == 0)
    h1 = "delta < 0";
  else
    h1 = fmt::format("delta in [{:g}, {:g}]", lo, hi);
  return fmt::format("JZS Bayes factor, Cauchy prior r = {:.3g}, H1: {}", r, h1);
}

double jzs_log_bf(double t, double n_eff, double df, double r, double lo, double hi) {
  check_args(t, n_eff, df, r);
  if (!(lo < hi)) throw UsageError(fmt::format("Bayes factor: interval [{}, {}] is empty", lo, hi));
  if (std::isinf(lo) && std::isinf(hi)) return log_bf_point(t, n_eff, df, r);
  // The half lines (one-sided alternatives) by the g integral: exact and fast at any t and n.
  if (lo == 0 && std::isinf(hi)) return log_bf_point(t, n_eff, df, r, +1);
  if (std::isinf(lo) && hi == 0) return log_bf_point(t, n_eff, df, r, -1);
  return log_bf_interval(t, n_eff, df, r, lo, hi);
}

double jzs_log_bf_complement(double t, double n_eff, double df, double r, double lo, double hi) {
  check_args(t, n_eff, df, r);
  if (!(lo < hi)) throw UsageError(fmt::format("Bayes factor: interval [{}, {}] is empty", lo, hi));
  if (std::isinf(lo) && std::isinf(hi))
    throw UsageError("Bayes factor: the whole line has no complement");
  // Integrate each outside piece directly (subtracting from the full BF would cancel).
  const JzsData data(t, n_eff, df, r);
  const double a = std::atan(lo / r), b = std::atan(hi / r);
  double mass = 0;
  std::vector<double> logs;
  if (a > -kPi / 2) {
    logs.push_back(log_theta_integral(data, -kInf, lo));
    mass += a + kPi / 2;
  }
  if (b < kPi / 2) {
    logs.push_back(log_theta_integral(data, hi, kInf));
    mass += kPi / 2 - b;
  }
  const double m = *std::max_element(logs.begin(), logs.end());
  if (!std::isfinite(m)) return -kInf;
  double s = 0;
  for (double l : logs) s += std::exp(l - m);
  return m + std::log(s) - std::log(mass);
}

BayesFactor jzs_bf_one_sample(double t, std::size_t n, Alternative alternative, double r) {
  if (n < 2) throw UsageError(fmt::format("Bayes factor: n = {} (a t test needs at least 2)", n));
  BayesFactor bf;
  bf.r = r;
  if (alternative == Alternative::greater) bf.lo = 0;
  if (alternative == Alternative::less) bf.hi = 0;
  const double nn = static_cast<double>(n);
  bf.log_bf10 = jzs_log_bf(t, nn, nn - 1, r, bf.lo, bf.hi);
  return bf;
}

BayesFactor jzs_bf_two_sample(double t, std::size_t n1, std::size_t n2, Alternative alternative,
                              double r) {
  if (n1 < 1 || n2 < 1 || n1 + n2 < 3)
    throw UsageError(fmt::format("Bayes factor: groups of {} and {} (need n1 + n2 >= 3)", n1, n2));
  BayesFactor bf;
  bf.r = r;
  if (alternative == Alternative::greater) bf.lo = 0;
  if (alternative == Alternative::less) bf.hi = 0;
  const double a = static_cast<double>(n1), b = static_cast<double>(n2);
  bf.log_bf10 = jzs_log_bf(t, a * b / (a + b), a + b - 2, r, bf.lo, bf.hi);
  return bf;
}

BayesFactor jzs_bf_interval_null(double t, double n_eff, double df, double margin, double r) {
  if (!(margin > 0) || !std::isfinite(margin))
    throw UsageError(fmt::format("Bayes factor: interval-null margin {} must be positive", margin));
  BayesFactor bf;
  bf.r = r;
  bf.lo = -margin;
  bf.hi = margin;
  bf.log_bf10 = jzs_log_bf_complement(t, n_eff, df, r, -margin, margin) -
                jzs_log_bf(t, n_eff, df, r, -margin, margin);
  return bf;
}

std::string jzs_prior_text(double r) {
  const std::string name = std::abs(r - kJzsMediumScale) < 1e-12  ? " (medium)"
                           : std::abs(r - 1) < 1e-12              ? " (wide)"
                           : std::abs(r - std::sqrt(2.0)) < 1e-12 ? " (ultrawide)"
                                                                  : "";
  return fmt::format("r = {:.4g}{}", r, name);
}

void add_bayes_factor(TestResult& test, double r) {
  if (!test.computed || !test.statistic || !std::isfinite(*test.statistic)) return;
  BayesFactor bf;
  if (test.test == "one_sample_t" || test.test == "paired_t") {
    if (test.n1 < 2) return;
    bf = jzs_bf_one_sample(*test.statistic, test.n1, test.alternative, r);
  } else if (test.test == "student_t" || test.test == "welch_t") {
    // ttestBF is the pooled-variance model: its t is d * sqrt(N) with the pooled-sd d.
    if (!test.cohen_d) return;
    const double a = static_cast<double>(test.n1), b = static_cast<double>(test.n2);
    const double t = *test.cohen_d * std::sqrt(a * b / (a + b));
    bf = jzs_bf_two_sample(t, test.n1, test.n2, test.alternative, r);
  } else {
    return;
  }
  test.log_bf10 = bf.log_bf10;
  test.bf10 = bf.bf10();
  test.bf01 = bf.bf01();
  test.bf_prior_r = r;
}

}  // namespace feint::stats

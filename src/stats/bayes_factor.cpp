// The JZS Bayes factor: see feint/stats/bayes_factor.hpp for the formulas and references.
#include "feint/stats/bayes_factor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <boost/math/distributions/students_t.hpp>
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

/// Integral of exp(f) over [a, b] cut at `breaks`, with adaptive Gauss–Kronrod (61 points) on each
/// piece; f is given in logs and `scale` (its maximum) is taken out first: returns log of the integral.
template <class F>
double log_integral(F&& log_f, double scale, std::vector<double> breaks, double a, double b,
                    unsigned max_depth = 12, double tol = 1e-10) {
  breaks.push_back(a);
  breaks.push_back(b);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  double total = 0.0;
  auto f = [&](double x) {
    const double v = log_f(x) - scale;
    return std::isfinite(v) ? std::exp(v) : 0.0;
  };
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double lo = breaks[k], hi = breaks[k + 1];
    if (lo < a || hi > b || !(hi > lo)) continue;
    double err = 0;
    total += boost::math::quadrature::gauss_kronrod<double, 61>::integrate(f, lo, hi, max_depth, tol, &err);
  }
  return scale + std::log(total);
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
/// mixture over the chi scale of t Azzalini and Capitanio's (2003) skew t: the one-sided ratio is the
/// whole-line one times 2 T_{nu+1}(side lambda u sqrt((nu + 1) / (u^2 + nu))), u = t / sigma. So a
/// one-sided Bayes factor is one smooth integral over g at any t and n, as the two-sided one; the
/// two halves add up to twice the whole line exactly (T(z) + T(-z) = 1).
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
  // The integrand is smooth and unimodal in x; locate its peak on a grid, integrate +-40 around it
  // (beyond, it falls below e^-40 of the peak on both sides: like e^-x above, like exp(-e^-x) below).
  double best = -kInf, xm = 0;
  for (double x = -40; x <= 40; x += 0.05) {
    const double v = lf(x);
    if (v > best) best = v, xm = x;
  }
  std::vector<double> breaks;
  for (int k = -20; k <= 20; ++k) breaks.push_back(xm + 2.0 * k);
  return log_integral(lf, best, breaks, xm - 40, xm + 40);
}

/// log p(t | delta) - log p(t | 0): the noncentral t likelihood ratio, integrated from its
/// definition (Boost's and R's noncentral t densities lose their accuracy in the far tail):
///   p(t | ncp) = int_0^inf phi(t s - ncp) s h(s) ds,  s = sqrt(V / nu), V ~ chi^2_nu,
/// where log(s h(s)) = log(2 nu) + (nu/2 - 1) log nu + nu log s - nu s^2 / 2 - (nu/2) log 2 - lgamma(nu/2).
/// The log integrand is concave in s with its peak in closed form (A s^2 - B s - nu = 0,
/// A = t^2 + nu, B = t ncp) and curvature at least A, so +-14/sqrt(A) around the peak hold all of it.
/// Beyond |ncp| > `cutoff` the likelihood is below e^-1800 of its peak and is taken as 0.
double log_likelihood_ratio(double t, double n, double nu, double delta, double log_p0,
                            double cutoff) {
  const double ncp = delta * std::sqrt(n);
  if (!std::isfinite(ncp) || std::fabs(ncp) > cutoff) return -kInf;
  const double a = t * t + nu, b = t * ncp;
  const double root = std::sqrt(b * b + 4 * a * nu);
  const double sm = b >= 0 ? (b + root) / (2 * a) : 2 * nu / (root - b);  // no cancellation
  const double c = -0.5 * std::log(2 * kPi) + std::log(2 * nu) + (nu / 2 - 1) * std::log(nu) -
                   (nu / 2) * std::log(2.0) - std::lgamma(nu / 2);
  auto lh = [&](double s) {
    if (!(s > 0)) return -kInf;
    const double z = t * s - ncp;
    return -0.5 * z * z + c + nu * std::log(s) - nu * s * s / 2;
  };
  const double w0 = 1 / std::sqrt(a);
  const double w = 1 / std::sqrt(a + nu / (sm * sm));
  std::vector<double> breaks;
  for (int k = -12; k <= 12; k += 4) breaks.push_back(sm + w * k);
  const double lo = std::max(0.0, sm - 14 * w0), hi = sm + 14 * w0;
  return log_integral(lh, lh(sm), breaks, lo, hi, 3, 1e-11) - log_p0;
}

/// log of int_{theta in [a, b]} p(t | r tan theta) / p(t | 0) d theta (the Cauchy prior is uniform
/// in theta = atan(delta / r)), NOT divided by b - a.
double log_theta_integral(double t, double n, double nu, double r, double a, double b) {
  // the central t density in logs (closed form; finite where the density itself underflows)
  const double log_p0 = std::lgamma((nu + 1) / 2) - std::lgamma(nu / 2) - 0.5 * std::log(nu * kPi) -
                        (nu + 1) / 2 * std::log1p(t * t / nu);
  const double peak = std::atan(t / std::sqrt(n) / r);
  const double ncp_centre = std::fabs(r * std::tan(std::clamp(peak, a, b)) * std::sqrt(n));
  const double cutoff = 60 * (1 + std::fabs(t)) + ncp_centre;
  auto lf = [&](double th) {
    return log_likelihood_ratio(t, n, nu, r * std::tan(th), log_p0, cutoff);
  };
  // The likelihood's width in theta: sd(delta) * d theta / d delta, with d theta / d delta =
  // cos^2(theta) / r and sd(delta) = sd(t | ncp) / sqrt(N), where the noncentral t's spread grows
  // with its centre, Var(t | ncp) ~ 1 + ncp^2 / (2 nu). Without that growth the breaks below
  // covered a fraction of a standard deviation at large t (t = 500, N = 30: 0.6 sd), and the
  // adaptive quadrature subdivided a peak at a piece's edge for minutes.
  const double sd_delta = std::sqrt((1 + t * t / (2 * nu)) / n);
  const double width = std::cos(peak) * std::cos(peak) / r * sd_delta;
  const double centre = std::clamp(peak, a, b);
  const double pad = std::min(1e-12, (b - a) * 1e-6);
  const double scale = lf(std::clamp(centre, a + pad, b - pad));
  std::vector<double> breaks;
  for (int k = -40; k <= 40; k += 5) breaks.push_back(centre + width * k);
  if (!std::isfinite(scale)) return -kInf;
  return log_integral(lf, scale, breaks, a, b);
}

/// log BF of delta in [lo, hi] against 0.
double log_bf_interval(double t, double n, double nu, double r, double lo, double hi) {
  const double a = std::atan(lo / r), b = std::atan(hi / r);
  return log_theta_integral(t, n, nu, r, a, b) - std::log(b - a);
}

}  // namespace

std::string BayesFactor::describe() const {
  std::string h1;
  if (std::isinf(lo) && std::isinf(hi)) h1 = "delta != 0";
  else if (lo == 0 && std::isinf(hi)) h1 = "delta > 0";
  else if (std::isinf(lo) && hi == 0) h1 = "delta < 0";
  else h1 = fmt::format("delta in [{:g}, {:g}]", lo, hi);
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
  const double a = std::atan(lo / r), b = std::atan(hi / r);
  double mass = 0;
  std::vector<double> logs;
  if (a > -kPi / 2) {
    logs.push_back(log_theta_integral(t, n_eff, df, r, -kPi / 2, a));
    mass += a + kPi / 2;
  }
  if (b < kPi / 2) {
    logs.push_back(log_theta_integral(t, n_eff, df, r, b, kPi / 2));
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

// The studentized range distribution (see feint/models/studentized_range.hpp): the integral of
// Copenhaver & Holland (1988), by piecewise 20-point Gauss-Legendre rules (Boost's nodes).
//
// Cost. A Tukey family of 20 means has 190 contrasts, one ptukey each, with one k and nearly one
// df; the integrand's normal tails (erfc) were all of the time. So:
// - R(w) = P(range of k normals <= w) is tabulated once per k, as piecewise Chebyshev
//   interpolants of its quadrature, and ptukey's outer integral reads the table (~30 flops per
//   node instead of ~60 erfc);
// - the quadrature of R(w) uses nodes z that do not depend on w (Phi(z), phi(z) once per k) and
//   visits only the z where its integrand can exceed kNegligible;
// - the outer integral runs over u = log s (no boundary, and a near Gaussian density for large
//   df), in pieces sized by how fast the integrand changes, and takes the s where R(q s) = 1 to
//   kNegligible from the chi distribution's upper tail.
// Accuracy (tests/models/test_studentized_range_reference.cpp, against 34-digit quadrature):
// below 1e-15 absolute for q 0.01..50, df from 2 to infinity, k from 2 to 100.
// ptukey_upper, P(Q > q), takes the same outer integral of U(w) = P(range > w) computed as its own
// integral (no 1 - R), tabulated per k as log U(w) + w^2/4, with relative (not absolute) cuts:
// 1.2e-13 relative or better for P down to 1e-300.
#include "feint/models/studentized_range.hpp"

#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

namespace feint::models {

namespace {

using GL = boost::math::quadrature::gauss<double, 20>;

// Every skipped node or cut-off tail changes P by less than this (absolute), far below the
// rounding of a probability near 1.
constexpr double kNegligible = 1e-19;

// Upper normal tail Q(x) = 1 - Phi(x), accurate in both tails (std::erfc: double precision;
// Boost's erfc<double> goes through long double and was most of the old run time).
double upper_normal(double x) { return 0.5 * std::erfc(x / std::numbers::sqrt2); }

// The x with Q(x) = p.
double upper_normal_quantile(double p) {
  return std::numbers::sqrt2 * boost::math::erfc_inv(2 * p);
}

// Calls f(node, weight) for the 20-point Gauss-Legendre rule on [a, b].
template <class F>
void gauss_nodes(double a, double b, const F& f) {
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  const auto& x = GL::abscissa();
  const auto& w = GL::weights();
  for (std::size_t i = 0; i < x.size(); ++i) {
    f(mid - half * x[i], half * w[i]);
    if (x[i] != 0) f(mid + half * x[i], half * w[i]);
  }
}

double power(double b, int n) {
  double out = 1;
  for (; n > 0; n >>= 1, b *= b)
    if (n & 1) out *= b;
  return out;
}

// ---- R(w) = P(range of k standard normals <= w) = k int phi(z) [Phi(z + w) - Phi(z)]^(k-1) dz

// The nodes z for k means, ascending, on pieces of width h over [-z_max, t]. Beyond t the
// integrand k phi(z) band^(k-1) <= k phi(z) Q(t)^(k-1) integrates to at most k Q(t)^k =
// kNegligible; below -w - t the same bound holds (band <= Phi(z + w) <= Q(t)); below -z_max
// k phi integrates to kNegligible.
struct InnerRule {
  double k = 0, t = 0;
  int power = 0;  // k - 1 when k is a whole number (then band^(k-1) by multiplication)
  std::vector<double> z, weighted_phi, lower, upper;  // k weight phi(z), Phi(z), Q(z)
};

InnerRule make_inner_rule(double k) {
  InnerRule rule;
  rule.k = k;
  rule.t = upper_normal_quantile(std::pow(kNegligible / k, 1.0 / k));
  const double z_max = upper_normal_quantile(kNegligible / k);
  if (k == std::floor(k) && k <= 1000) rule.power = static_cast<int>(k) - 1;
  // The integrand is ~1/sqrt(k) wide in z at small w: pieces of ~9 such widths (at most 2),
  // checked against 34-digit quadrature to 1e-16.
  const double h = std::min(2.0, 8.94 / std::sqrt(k));
  std::vector<std::pair<double, double>> nodes;
  for (double b = rule.t; b > -z_max; b -= h)
    gauss_nodes(b - h, b, [&](double z, double wt) { nodes.emplace_back(z, wt); });
  std::sort(nodes.begin(), nodes.end());
  const double inv_sqrt_2pi = 1.0 / std::sqrt(2.0 * std::numbers::pi);
  for (const auto& [z, wt] : nodes) {
    rule.z.push_back(z);
    rule.weighted_phi.push_back(k * wt * inv_sqrt_2pi * std::exp(-0.5 * z * z));
    rule.lower.push_back(upper_normal(-z));
    rule.upper.push_back(upper_normal(z));
  }
  return rule;
}

const InnerRule& inner_rule(double k) {
  thread_local std::vector<std::unique_ptr<InnerRule>> rules;
  for (const auto& r : rules)
    if (r->k == k) return *r;
  if (rules.size() > 16) rules.clear();
  rules.push_back(std::make_unique<InnerRule>(make_inner_rule(k)));
  return *rules.back();
}

// R(w) by the quadrature of make_inner_rule; long double accumulation keeps the sum of ~100
// terms at the terms' own accuracy (~1e-16 instead of ~1e-15).
double range_cdf_direct(double w, const InnerRule& rule) {
  if (!(w > 0)) return 0.0;
  if (std::isinf(w)) return 1.0;
  const double k = rule.k;
  // band <= w phi(0): the whole integral is below k (w phi(0))^(k-1).
  if ((k - 1) * std::log(w / std::sqrt(2.0 * std::numbers::pi)) + std::log(k) <
      std::log(kNegligible))
    return 0.0;
  const auto first = std::lower_bound(rule.z.begin(), rule.z.end(), -w - rule.t) - rule.z.begin();
  long double out = 0;
  for (auto m = static_cast<std::size_t>(first); m < rule.z.size(); ++m) {
    const double z = rule.z[m];
    // band = Phi(z + w) - Phi(z) from tails that do not cancel. Where it is near 1 (z <= 0 <=
    // z + w) it is 1 - delta with delta = Phi(z) + Q(z + w) known to full relative precision,
    // and exp((k-1) log1p(-delta)) keeps it (1 - delta rounded would put 1e-16 in each factor).
    if (z <= 0 && z + w >= 0) {
      const double delta = rule.lower[m] + upper_normal(z + w);
      out += rule.weighted_phi[m] * std::exp((k - 1) * std::log1p(-delta));
      continue;
    }
    const double band = z > 0 ? rule.upper[m] - upper_normal(z + w)
                              : upper_normal(-(z + w)) - rule.lower[m];
    if (band > 0)
      out += rule.weighted_phi[m] *
             (rule.power > 0 ? power(band, rule.power) : std::pow(band, k - 1));
  }
  return std::min(1.0, static_cast<double>(out));
}

// The w from which P(range > w) <= k (k - 1) Q(w / sqrt 2) (Bonferroni over the pairs) is below
// kNegligible.
double range_upper_cut(double k) {
  return std::numbers::sqrt2 * upper_normal_quantile(kNegligible / (k * (k - 1)));
}

// R(w) for one whole k as Chebyshev interpolants of range_cdf_direct (degree kDegree - 1 on
// pieces of width kWidth of [0, range_upper_cut]; 0 where range_cdf_direct's bound is below
// kNegligible, 1 from the cut on). Built once per k (~560 direct evaluations, ~1 ms); agrees
// with range_cdf_direct to ~2e-16 for k = 2..200. Not for fractional k: R(w) ~ w^(k-1) is then
// not smooth at 0.
class RangeCdfTable {
 public:
  static constexpr int kDegree = 20;
  static constexpr double kWidth = 0.5;

  explicit RangeCdfTable(double k) : k_(k), w_cut_(range_upper_cut(k)) {
    const InnerRule& rule = inner_rule(k);
    w_low_ = std::sqrt(2 * std::numbers::pi) * std::pow(kNegligible / k, 1 / (k - 1));
    const int pieces = static_cast<int>(std::ceil(w_cut_ / kWidth));
    coef_.assign(static_cast<std::size_t>(pieces * kDegree), 0.0);
    std::array<long double, kDegree> f{};
    for (int p = 0; p < pieces; ++p) {
      for (int m = 0; m < kDegree; ++m) {
        const double x = std::cos(std::numbers::pi * (m + 0.5) / kDegree);
        f[static_cast<std::size_t>(m)] = range_cdf_direct(kWidth * (p + 0.5 * (x + 1)), rule);
      }
      // In long double: where R is near 1 the coefficients are differences of values near 1,
      // whose rounding in double would add up to ~1e-15 over the kDegree terms.
      for (int j = 0; j < kDegree; ++j) {
        long double c = 0;
        for (int m = 0; m < kDegree; ++m)
          c += f[static_cast<std::size_t>(m)] *
               std::cos(std::numbers::pi_v<long double> * j * (m + 0.5L) / kDegree);
        coef_[static_cast<std::size_t>(p * kDegree + j)] =
            static_cast<double>((j == 0 ? 1.0L : 2.0L) * c / kDegree);
      }
    }
  }

  double k() const { return k_; }

  double operator()(double w) const {
    if (!(w > w_low_)) return 0.0;
    if (!(w < w_cut_)) return 1.0;
    const double pos = w / kWidth;
    const double piece =
        std::min(std::floor(pos), static_cast<double>(coef_.size() / kDegree - 1));
    const double x = 2 * (pos - piece) - 1;
    const double* c = coef_.data() + static_cast<std::size_t>(piece) * kDegree;
    double b1 = 0, b2 = 0;  // Clenshaw's recurrence
    for (int j = kDegree - 1; j >= 1; --j) {
      const double b0 = 2 * x * b1 - b2 + c[j];
      b2 = b1;
      b1 = b0;
    }
    return std::clamp(x * b1 - b2 + c[0], 0.0, 1.0);
  }

 private:
  double k_, w_cut_, w_low_ = 0;
  std::vector<double> coef_;
};

const RangeCdfTable& range_cdf_table(double k) {
  thread_local std::vector<std::unique_ptr<RangeCdfTable>> tables;
  for (const auto& t : tables)
    if (t->k() == k) return *t;
  if (tables.size() > 16) tables.clear();
  tables.push_back(std::make_unique<RangeCdfTable>(k));
  return *tables.back();
}

// ---- The outer integral over s = sqrt(chi2_df / df), in u = log s

// e^x - 1 - x without cancellation near 0.
double expm1mx(double x) {
  if (std::abs(x) > 0.5) return std::expm1(x) - x;
  double term = x * x / 2, sum = 0;
  for (int n = 3; std::abs(term) > 1e-18 * std::abs(sum); ++n) {
    sum += term;
    term *= x / n;
  }
  return sum;
}

// lgamma(h) - ((h - 1/2) log h - h + log(2 pi) / 2), Stirling's remainder: its series from
// h = 15 on (terms below 1e-17 there), long double arithmetic below.
double stirling_remainder(double h) {
  if (h < 15) {
    const long double x = h;
    return static_cast<double>(std::lgamma(x) - ((x - 0.5L) * std::log(x) - x +
                                                 0.5L * std::log(2 * std::numbers::pi_v<long double>)));
  }
  const double r = 1 / h, r2 = r * r;
  return r * (1.0 / 12 - r2 * (1.0 / 360 - r2 * (1.0 / 1260 - r2 * (1.0 / 1680 - r2 * (1.0 / 1188 -
                                                  r2 * (691.0 / 360360 - r2 / 156))))));
}

// The density of u = log s: f_u(u) = 2 h^h e^(2 h u - h e^(2u)) / Gamma(h), h = df / 2, written
// around its mode u = 0 so that no large terms cancel (h log h - lgamma(h) loses ~1e-16 h):
//   log f_u(u) = log 2 + log(h) / 2 - log(2 pi) / 2 - stirling_remainder(h) - h (e^(2u) - 1 - 2u).
// Near Gaussian with sd 1 / sqrt(2 df) for large df; s = 0 is u = -infinity (no boundary, so a
// fractional df needs no care).
// The density itself is norm * exp(-h (e^(2u) - 1 - 2u)) with norm a product of correctly rounded
// factors: exp(log_norm) would carry log_norm's rounding (~1e-15 relative at df = 1e9, where
// log_norm ~ 10) into every P.
struct ScaleDensity {
  double h, sd, log_norm, norm;
  explicit ScaleDensity(double df)
      : h(0.5 * df),
        sd(1 / std::sqrt(2 * df)),
        log_norm(std::log(2.0) + 0.5 * std::log(h) - 0.5 * std::log(2 * std::numbers::pi) -
                 stirling_remainder(h)),
        norm(2 * std::sqrt(h / (2 * std::numbers::pi)) * std::exp(-stirling_remainder(h))) {}
  double log_density(double u) const { return log_norm - h * expm1mx(2 * u); }
};

// int f_u(u) R(q e^u) du over the support (where the integrand can exceed kNegligible), plus the
// chi tail where R = 1. R is range_cdf (a table, or the direct quadrature for fractional k).
template <class RangeCdf>
double outer_integral(double q, double k, double df, const RangeCdf& range_cdf) {
  const ScaleDensity dens(df);
  const double cut = std::log(kNegligible);
  const double log_q_phi0 = std::log(q) - 0.5 * std::log(2 * std::numbers::pi);
  auto log_bound = [&](double u) {  // log of f_u(u) min(1, k (q e^u phi(0))^(k-1))
    return dens.log_density(u) + std::min(0.0, std::log(k) + (k - 1) * (log_q_phi0 + u));
  };
  double lo = 0, hi = 0;
  while (log_bound(lo) > cut) lo -= dens.sd;
  while (dens.log_density(hi) > cut) hi += dens.sd;
  long double out = 0;
  // From s_full = w_cut / q on R(q s) is 1 to kNegligible: that part is P(s > s_full).
  const double u_full = std::log(range_upper_cut(k) / q);
  if (u_full < hi) {
    out += boost::math::gamma_q(dens.h, dens.h * std::exp(2 * u_full));
    hi = std::max(lo, u_full);
  }
  // Pieces outward from the mode: on each the log of the integrand's bound changes by at most 20
  // (the 20-point rule then errs by < 1e-19 on an exponential), q e^u by at most 3 (R changes on
  // a scale of 1 in w), and u by at most 12 sd of f_u (near Gaussian there) and 1.5 (small df).
  // And by at most 20 / (k - 1): log R(q e^u) rises ~(k - 1) per unit of u also where the bound
  // is already 1 (without this, 2.6e-15 error at k = 100, df = 12.5, q = 2, where P = 1.2e-6).
  auto width = [&](double x, double dir) {
    double w = std::min({1.5, 12 * dens.sd, 20 / (k - 1)});
    const double r = 3 / (q * std::exp(x));
    w = std::min(w, dir > 0 ? std::log1p(r) : r < 1 ? -std::log1p(-r) : w);
    const double psi = log_bound(x);
    for (int i = 0; i < 60 && std::abs(psi - log_bound(x + dir * w)) > 20; ++i) w *= 0.8;
    return w;
  };
  const double weight_cut = std::log(kNegligible / 1000);
  auto integrate = [&](double a, double b) {
    gauss_nodes(a, b, [&](double u, double wt) {
      const double e = dens.h * expm1mx(2 * u);  // log f_u(u) = log_norm - e
      if (std::log(wt) + dens.log_norm - e > weight_cut)
        out += wt * dens.norm * std::exp(-e) * range_cdf(q * std::exp(u));
    });
  };
  const double start = std::clamp(0.0, lo, hi);
  for (double x = start; x < hi; x += width(x, 1)) integrate(x, std::min(hi, x + width(x, 1)));
  for (double x = start; x > lo; x -= width(x, -1)) integrate(std::max(lo, x - width(x, -1)), x);
  return static_cast<double>(out);
}


// ---- U(w) = P(range > w), the upper tail itself (ptukey_upper): no 1 - R(w), which would leave
// only ~1e-16 absolute accuracy. The smallest of the k is at z with density k phi(z) Q(z)^(k-1),
// and the range is at most w when the other k - 1 lie in [z, z + w], so
//   U(w) = k int phi(z) Q(z)^(k-1) [1 - (1 - r)^(k-1)] dz,  r = Q(z + w) / Q(z),
// with 1 - (1 - r)^(k-1) = -expm1((k - 1) log1p(-r)): every factor to full relative precision.
// In long double, whose range (1e-4951) holds U(w) out to w = 56 and beyond.

// An upper bound of log Q(x): Q(x) <= phi(x) / x for x > 0, Q(x) <= 1.
double log_upper_normal_bound(double x) {
  if (x <= 1) return 0.0;
  return -0.5 * x * x - std::log(x * std::sqrt(2 * std::numbers::pi));
}

// Nodes on [-38, 37] (the integrand's mass lies within ~9 of z = -w/2 for large w, and
// phi(38) ~ 1e-314), pieces as make_inner_rule's.
struct UpperRule {
  double k = 0;
  std::vector<double> z, log_weighted_phi, log_tail;
  std::vector<long double> weighted_phi, tail;  // k weight phi(z), Q(z)
};

UpperRule make_upper_rule(double k) {
  UpperRule rule;
  rule.k = k;
  const double h = std::min(2.0, 8.94 / std::sqrt(k));
  std::vector<std::pair<double, double>> nodes;
  for (double b = 37; b > -38; b -= h)
    gauss_nodes(b - h, b, [&](double z, double wt) { nodes.emplace_back(z, wt); });
  std::sort(nodes.begin(), nodes.end());
  for (const auto& [z, wt] : nodes) {
    const long double zl = z;
    const long double wphi = k * wt * std::exp(-0.5L * zl * zl) /
                             std::sqrt(2 * std::numbers::pi_v<long double>);
    const long double tail = 0.5L * std::erfc(zl / std::numbers::sqrt2_v<long double>);
    rule.z.push_back(z);
    rule.weighted_phi.push_back(wphi);
    rule.tail.push_back(tail);
    rule.log_weighted_phi.push_back(static_cast<double>(std::log(wphi)));
    rule.log_tail.push_back(static_cast<double>(std::log(tail)));
  }
  return rule;
}

const UpperRule& upper_rule(double k) {
  thread_local std::vector<std::unique_ptr<UpperRule>> rules;
  for (const auto& r : rules)
    if (r->k == k) return *r;
  if (rules.size() > 16) rules.clear();
  rules.push_back(std::make_unique<UpperRule>(make_upper_rule(k)));
  return *rules.back();
}

// log U(w) by the quadrature of make_upper_rule, visiting only the nodes whose term's bound
// k weight phi(z) Q(z)^(k-2) min(Q(z), (k - 1) Q(z + w)) is within e^-50 of the largest (a term
// is at least ~1/100 of its bound, so the skipped ones are below e^-45 of the sum).
double log_range_upper_direct(double w, const UpperRule& rule) {
  if (!(w > 0)) return 0.0;
  const double k = rule.k;
  const std::size_t n = rule.z.size();
  const double log_km1 = std::log(k - 1);
  thread_local std::vector<double> bound;
  bound.resize(n);
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t m = 0; m < n; ++m) {
    bound[m] = rule.log_weighted_phi[m] + (k - 2) * rule.log_tail[m] +
               std::min(rule.log_tail[m], log_km1 + log_upper_normal_bound(rule.z[m] + w));
    top = std::max(top, bound[m]);
  }
  long double out = 0;
  for (std::size_t m = 0; m < n; ++m) {
    if (bound[m] < top - 50) continue;
    const long double zw = static_cast<long double>(rule.z[m]) + w;
    const long double r = 0.5L * std::erfc(zw / std::numbers::sqrt2_v<long double>) / rule.tail[m];
    out += rule.weighted_phi[m] * std::pow(rule.tail[m], static_cast<long double>(k - 1)) *
           -std::expm1(static_cast<long double>(k - 1) * std::log1p(-r));
  }
  return static_cast<double>(std::log(out));
}

// log U(w) + w^2 / 4 (U falls as ~e^(-w^2/4): the remainder is of order 1, so its interpolants'
// absolute error is U's relative one) for one whole k as RangeCdfTable does R(w), on [0, 56]
// (beyond, U < 1e-320; -infinity is returned).
class RangeUpperTable {
 public:
  static constexpr int kDegree = 20;
  static constexpr double kWidth = 0.5, kEnd = 56;

  // Pieces are built when first read: a call visits a few of the 112, each 20 direct
  // evaluations (the first call for a k: ~30 ms, bench/bench_ptukey.cpp).
  explicit RangeUpperTable(double k)
      : k_(k), rule_(&upper_rule(k)), built_(static_cast<std::size_t>(kEnd / kWidth), false) {
    coef_.assign(built_.size() * kDegree, 0.0);
  }

  void build(std::size_t p) const {
    std::array<long double, kDegree> f{};
    for (int m = 0; m < kDegree; ++m) {
      const double x = std::cos(std::numbers::pi * (m + 0.5) / kDegree);
      const double w = kWidth * (static_cast<double>(p) + 0.5 * (x + 1));
      f[static_cast<std::size_t>(m)] = log_range_upper_direct(w, *rule_) + 0.25 * w * w;
    }
    for (int j = 0; j < kDegree; ++j) {
      long double c = 0;
      for (int m = 0; m < kDegree; ++m)
        c += f[static_cast<std::size_t>(m)] *
             std::cos(std::numbers::pi_v<long double> * j * (m + 0.5L) / kDegree);
      coef_[p * kDegree + static_cast<std::size_t>(j)] =
          static_cast<double>((j == 0 ? 1.0L : 2.0L) * c / kDegree);
    }
    built_[p] = true;
  }

  double k() const { return k_; }

  double operator()(double w) const {  // log U(w)
    if (!(w > 0)) return 0.0;
    if (!(w < kEnd)) return -std::numeric_limits<double>::infinity();
    const double pos = w / kWidth;
    const double piece = std::floor(pos);
    const double x = 2 * (pos - piece) - 1;
    const auto p = static_cast<std::size_t>(piece);
    if (!built_[p]) build(p);
    const double* c = coef_.data() + p * kDegree;
    double b1 = 0, b2 = 0;
    for (int j = kDegree - 1; j >= 1; --j) {
      const double b0 = 2 * x * b1 - b2 + c[j];
      b2 = b1;
      b1 = b0;
    }
    return std::min(0.0, x * b1 - b2 + c[0] - 0.25 * w * w);
  }

 private:
  double k_;
  const UpperRule* rule_;
  mutable std::vector<bool> built_;  // the table is thread_local: no races
  mutable std::vector<double> coef_;
};

const RangeUpperTable& range_upper_table(double k) {
  thread_local std::vector<std::unique_ptr<RangeUpperTable>> tables;
  for (const auto& t : tables)
    if (t->k() == k) return *t;
  if (tables.size() > 16) tables.clear();
  tables.push_back(std::make_unique<RangeUpperTable>(k));
  return *tables.back();
}

// int f_u(u) U(q e^u) du, U = exp(log_upper(w)), to ~1e-15 relative however small: below u0,
// where R(q e^u) <= k (q e^u phi(0))^(k-1) < 1e-17, U is 1 and that part is P(s < e^u0), a
// regularized gamma function; above, the integrand's bound f_u(u) min(1, k (k - 1) Q(q e^u / sqrt
// 2)) (Bonferroni over the pairs, within C(k, 2) of U) is scanned for its largest value, and the
// pieces and nodes where the bound is below e^-60 of it are left out. Pieces as outer_integral's,
// but half as wide: with the full width the error was 2.4e-15 (k = 20, df = 30, q = 4.5), with
// half 2.4e-17 (U's smooth fall from 1 is no longer cut off where R reaches 1).
template <class LogRangeUpper>
double outer_upper_integral(double q, double k, double df, const LogRangeUpper& log_upper) {
  const ScaleDensity dens(df);
  const double log_pairs = std::log(k * (k - 1));
  auto log_bound = [&](double u) {
    return dens.log_density(u) +
           std::min(0.0, log_pairs + log_upper_normal_bound(q * std::exp(u) / std::numbers::sqrt2));
  };
  const double u0 = (std::log(1e-17 / k) / (k - 1) + 0.5 * std::log(2 * std::numbers::pi)) -
                    std::log(q);
  double right = std::max(0.0, u0);
  while (dens.log_density(right) > -800) right += dens.sd;
  double left = std::min(0.0, right);
  while (left > u0 && dens.log_density(left) > -800) left -= dens.sd;
  left = std::max(left, u0);
  const double step = std::min(0.25, dens.sd);
  double top = -std::numeric_limits<double>::infinity(), lo = right, hi = left;
  for (double u = left; u <= right + step; u += step) top = std::max(top, log_bound(u));
  for (double u = left; u <= right + step; u += step)
    if (log_bound(u) > top - 60) {
      lo = std::min(lo, u - step);
      hi = std::max(hi, u + step);
    }
  long double out = 0;
  if (lo <= u0 + step) {
    lo = u0;
    out += boost::math::gamma_p(dens.h, dens.h * std::exp(2 * u0));
  }
  auto width = [&](double x, double dir) {
    double w = 0.5 * std::min({1.5, 12 * dens.sd, 20 / (k - 1)});
    const double r = 3 / (q * std::exp(x));
    w = std::min(w, dir > 0 ? std::log1p(r) : r < 1 ? -std::log1p(-r) : w);
    const double psi = log_bound(x);
    for (int i = 0; i < 60 && std::abs(psi - log_bound(x + dir * w)) > 20; ++i) w *= 0.8;
    return w;
  };
  auto integrate = [&](double a, double b) {
    gauss_nodes(a, b, [&](double u, double wt) {
      if (std::log(wt) + log_bound(u) < top - 60) return;
      const double e = dens.h * expm1mx(2 * u);
      out += wt * dens.norm * std::exp(log_upper(q * std::exp(u)) - e);
    });
  };
  // Outward from f_u's mode, as outer_integral (a piece across the mode would be less exact).
  const double start = std::clamp(0.0, lo, hi);
  for (double x = start; x < hi; x += width(x, 1)) integrate(x, std::min(hi, x + width(x, 1)));
  for (double x = start; x > lo; x -= width(x, -1)) integrate(std::max(lo, x - width(x, -1)), x);
  return static_cast<double>(out);
}
}  // namespace

double ptukey(double q, double nmeans, double df) {
  if (!(nmeans >= 2) || !(df > 0) || std::isnan(q))
    throw std::invalid_argument("ptukey: needs nmeans >= 2, df > 0 and a number q");
  if (!(q > 0)) return 0.0;
  if (std::isinf(q)) return 1.0;
  if (std::isinf(df)) return range_cdf_direct(q, inner_rule(nmeans));
  double p = 0;
  if (nmeans == std::floor(nmeans) && nmeans <= 1000) {
    p = outer_integral(q, nmeans, df, range_cdf_table(nmeans));
  } else {
    const InnerRule& rule = inner_rule(nmeans);
    p = outer_integral(q, nmeans, df, [&rule](double w) { return range_cdf_direct(w, rule); });
  }
  return std::clamp(p, 0.0, 1.0);
}

double ptukey_upper(double q, double nmeans, double df) {
  if (!(nmeans >= 2) || !(df > 0) || std::isnan(q))
    throw std::invalid_argument("ptukey_upper: needs nmeans >= 2, df > 0 and a number q");
  if (!(q > 0)) return 1.0;
  if (std::isinf(q)) return 0.0;
  const bool tabulated = nmeans == std::floor(nmeans) && nmeans <= 1000;
  double p = 0;
  if (tabulated) {
    const RangeUpperTable& table = range_upper_table(nmeans);
    p = std::isinf(df) ? std::exp(table(q)) : outer_upper_integral(q, nmeans, df, table);
  } else {
    const UpperRule& rule = upper_rule(nmeans);
    auto direct = [&rule](double w) { return log_range_upper_direct(w, rule); };
    p = std::isinf(df) ? std::exp(direct(q)) : outer_upper_integral(q, nmeans, df, direct);
  }
  return std::clamp(p, 0.0, 1.0);
}

double qtukey(double p, double nmeans, double df) {
  if (!(p > 0 && p < 1)) throw std::invalid_argument("qtukey: p must be in (0, 1)");
  auto g = [&](double q) { return ptukey(q, nmeans, df) - p; };
  double lo = 0.0, hi = 1.0;
  while (g(hi) < 0) {
    lo = hi;
    hi *= 2;
    if (hi > 1e8) return std::numeric_limits<double>::infinity();
  }
  boost::uintmax_t iters = 200;
  const auto r = boost::math::tools::toms748_solve(
      g, lo, hi, boost::math::tools::eps_tolerance<double>(42), iters);
  return 0.5 * (r.first + r.second);
}

}  // namespace feint::models

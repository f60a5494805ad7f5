// The studentized range distribution (see feint/models/studentized_range.hpp): written from the
// integral representation of Copenhaver & Holland (1988), with piecewise Gauss-Legendre quadrature (Boost).
#include "feint/models/studentized_range.hpp"

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace feint::models {

namespace {

template <class F>
double piecewise(const F& f, double a, double b, int pieces) {
  using GL = boost::math::quadrature::gauss<double, 20>;
  const double h = (b - a) / pieces;
  double out = 0;
  for (int i = 0; i < pieces; ++i) out += GL::integrate(f, a + i * h, a + (i + 1) * h);
  return out;
}

double upper_normal(double z) { return 0.5 * boost::math::erfc(z / std::numbers::sqrt2); }

// P(Phi(z) < N < Phi(z + w)) without cancellation in either tail.
double band(double z, double w) {
  if (z > 0) return upper_normal(z) - upper_normal(z + w);
  return upper_normal(-(z + w)) - upper_normal(-z);
}

// P(range of k standard normals <= w).
double range_cdf(double w, double k) {
  if (!(w > 0)) return 0.0;
  if (std::isinf(w)) return 1.0;
  const double inv_sqrt_2pi = 1.0 / std::sqrt(2.0 * std::numbers::pi);
  auto f = [&](double z) {
    const double b = band(z, w);
    if (!(b > 0)) return 0.0;
    return k * inv_sqrt_2pi * std::exp(-0.5 * z * z + (k - 1) * std::log(b));
  };
  // The integrand is negligible (< 1e-20) outside [-9 - w, 9]: fixed 20-point Gauss-Legendre
  // rules on 6 equal pieces (the integrand is smooth; ~1e-13 here).
  return std::min(1.0, piecewise(f, -9.0 - w, 9.0, 6));
}

}  // namespace

double ptukey(double q, double nmeans, double df) {
  if (!(nmeans >= 2) || !(df > 0) || std::isnan(q))
    throw std::invalid_argument("ptukey: needs nmeans >= 2, df > 0 and a number q");
  if (!(q > 0)) return 0.0;
  if (std::isinf(q)) return 1.0;
  if (std::isinf(df) || df > 1e7) return range_cdf(q, nmeans);
  // log f_df(s).
  const double h = 0.5 * df;
  const double log_c = std::log(2.0) + h * std::log(h) - std::lgamma(h);
  auto dens = [&](double s) {
    if (!(s > 0)) return 0.0;
    return std::exp(log_c + (df - 1) * std::log(s) - h * s * s);
  };
  auto f = [&](double s) {
    const double d = dens(s);
    return d > 0 ? d * range_cdf(q * s, nmeans) : 0.0;
  };
  // s concentrates near 1 with sd ~ 1/sqrt(2 df): integrate over pieces around the mode and out to
  // where the density is below 1e-30 of its peak.
  const double sd = 1.0 / std::sqrt(2.0 * df);
  const double mode = df > 1 ? std::sqrt((df - 1) / df) : 0.0;
  double upper = mode + 10 * sd + 1.0;
  while (dens(upper) > 1e-30 * std::max(dens(mode), 1e-300)) upper *= 1.5;
  const double a = std::max(0.0, mode - 8 * sd), b = mode + 8 * sd;
  double out = 0;
  // Outside mode -+ 8 sd the density is monotone: skip a tail piece whose inner edge is already
  // below 1e-25 of the peak (its contribution is below that times its width).
  const double peak = std::max(dens(mode), 1e-300);
  if (a > 0 && dens(a) > 1e-25 * peak) out += piecewise(f, 0.0, a, 2);
  out += piecewise(f, a, b, 5);
  if (dens(b) > 1e-25 * peak) out += piecewise(f, b, upper, 4);
  return std::min(1.0, std::max(0.0, out));
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

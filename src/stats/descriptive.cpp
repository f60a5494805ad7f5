#include "feint/stats/descriptive.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <boost/math/distributions/students_t.hpp>

#include "feint/error.hpp"
#include "stats_detail.hpp"

namespace feint::stats {

void Summary::add(double x) noexcept {
  // Welford (1962): the running mean and M2 never subtract two large nearly-equal sums.
  ++n;
  const double delta = x - mean;
  mean += delta / static_cast<double>(n);
  m2 += delta * (x - mean);
  min = std::min(min, x);
  max = std::max(max, x);
}

void Summary::merge(const Summary& other) noexcept {
  if (other.n == 0) return;
  if (n == 0) {
    *this = other;
    return;
  }
  // Chan, Golub & LeVeque (1979), eq. 2.1b: M2 = M2a + M2b + delta^2 na nb / (na + nb).
  const double na = static_cast<double>(n);
  const double nb = static_cast<double>(other.n);
  const double nt = na + nb;
  const double delta = other.mean - mean;
  // Weighted mean rather than mean + delta * nb / nt: exact when the means are equal, and
  // symmetric in the two parts.
  mean = (na * mean + nb * other.mean) / nt;
  if (!std::isfinite(mean)) mean = (n >= other.n ? *this : other).mean + delta * (nb / nt);
  m2 += other.m2 + delta * delta * (na * nb / nt);
  n += other.n;
  min = std::min(min, other.min);
  max = std::max(max, other.max);
}

std::optional<double> Summary::variance() const noexcept {
  if (n < 2) return std::nullopt;
  return m2 / static_cast<double>(n - 1);
}

std::optional<double> Summary::sd() const noexcept {
  auto v = variance();
  if (!v) return std::nullopt;
  return std::sqrt(*v);
}

std::optional<double> Summary::se() const noexcept {
  auto s = sd();
  if (!s) return std::nullopt;
  return *s / std::sqrt(static_cast<double>(n));
}

Summary summarize(std::span<const double> x) {
  Summary s;
  if (x.empty()) return s;
  // Pass 1: the mean, accumulated in extended precision around a shift (the first value), so a
  // sample with many constant leading digits keeps its trailing ones.
  const long double shift = x[0];
  long double sum = 0;
  for (double v : x) {
    sum += static_cast<long double>(v) - shift;
    s.min = std::min(s.min, v);
    s.max = std::max(s.max, v);
  }
  const long double n = static_cast<long double>(x.size());
  const long double dmean = sum / n;  // mean - shift
  // Pass 2: sum of squared deviations with the corrected two-pass algorithm (Chan, Golub &
  // LeVeque 1983, eq. 1.7): the second term removes the rounding error of the mean.
  long double ss = 0, corr = 0;
  for (double v : x) {
    const long double d = (static_cast<long double>(v) - shift) - dmean;
    ss += d * d;
    corr += d;
  }
  s.n = x.size();
  s.mean = static_cast<double>(shift + dmean);
  s.m2 = static_cast<double>(std::max(0.0L, ss - corr * corr / n));
  return s;
}

double quantile_type7(std::span<const double> sorted, double p) {
  if (sorted.empty()) throw InvalidData("quantile of an empty sample");
  if (!(p >= 0.0 && p <= 1.0)) throw UsageError("quantile probability outside [0, 1]");
  // R's quantile.default, type 7, literally: index = 1 + (n - 1) p; (1 - h) x[lo] + h x[hi].
  const double index = static_cast<double>(sorted.size() - 1) * p;  // 0-based
  const double lo = std::floor(index);
  const double hi = std::ceil(index);
  const double qlo = sorted[static_cast<std::size_t>(lo)];
  const double qhi = sorted[static_cast<std::size_t>(hi)];
  if (!(index > lo) || qhi == qlo) return qlo;
  const double h = index - lo;
  return (1 - h) * qlo + h * qhi;
}

std::optional<double> autocorr_lag1(std::span<const double> x) {
  if (x.size() < 2) return std::nullopt;
  const long double shift = x[0];
  long double sum = 0;
  for (double v : x) sum += static_cast<long double>(v) - shift;
  const long double mean = sum / static_cast<long double>(x.size());
  long double num = 0, den = 0;
  long double prev = (static_cast<long double>(x[0]) - shift) - mean;
  den = prev * prev;
  for (std::size_t i = 1; i < x.size(); ++i) {
    const long double d = (static_cast<long double>(x[i]) - shift) - mean;
    num += d * prev;
    den += d * d;
    prev = d;
  }
  if (!(den > 0)) return std::nullopt;
  return static_cast<double>(num / den);
}

namespace {

std::vector<double> finite_values(std::span<const double> x) {
  std::vector<double> v;
  v.reserve(x.size());
  for (double d : x)
    if (!std::isnan(d)) v.push_back(d);
  return v;
}

}  // namespace

Description describe(std::span<const double> x, double conf_level) {
  detail::check_conf_level(conf_level);
  Description d;
  std::vector<double> v = finite_values(x);
  d.n = v.size();
  if (v.empty()) {
    d.note = "no values";
    return d;
  }
  const Summary s = summarize(v);
  std::sort(v.begin(), v.end());
  d.mean = s.mean;
  d.min = v.front();
  d.max = v.back();
  d.q1 = quantile_type7(v, 0.25);
  d.median = quantile_type7(v, 0.5);
  d.q3 = quantile_type7(v, 0.75);
  if (v.size() < 2) {
    d.note = "n < 2: sd, standard error and confidence interval need at least two values";
    return d;
  }
  d.sd = s.sd();
  d.se = s.se();
  const boost::math::students_t dist(static_cast<double>(v.size() - 1));
  const double q = boost::math::quantile(boost::math::complement(dist, (1.0 - conf_level) / 2.0));
  d.conf_low = s.mean - q * *d.se;
  d.conf_high = s.mean + q * *d.se;
  // The sample order is the input order (for autocorrelation): recompute on the unsorted values.
  d.autocorr_lag1 = autocorr_lag1(finite_values(x));
  if (!d.autocorr_lag1) d.note = "constant data: lag-1 autocorrelation undefined";
  return d;
}

}  // namespace feint::stats

#include "feint/stats/descriptive.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include <boost/math/distributions/students_t.hpp>

#include "feint/error.hpp"
#include "shifted.hpp"
#include "stats_detail.hpp"

namespace feint::stats {

void Summary::add(double x) noexcept {
  // Welford (1962): the running mean and M2 never subtract two large nearly-equal sums. The mean
  // is carried in extended precision (mean + mean_lo).
  ++n;
  long double m = static_cast<long double>(mean) + mean_lo;
  const long double delta = x - m;
  m += delta / static_cast<long double>(n);
  m2 += static_cast<double>(delta * (x - m));
  mean = static_cast<double>(m);
  mean_lo = static_cast<double>(m - mean);
  min = std::min(min, x);
  max = std::max(max, x);
}

void Summary::merge(const Summary& other) noexcept {
  if (other.n == 0) return;
  if (n == 0) {
    *this = other;
    return;
  }
  // Chan, Golub & LeVeque (1979), eq. 2.1b: M2 = M2a + M2b + delta^2 na nb / (na + nb). delta is
  // formed from the high parts (exact when the means are within a factor two) plus the low parts.
  const long double na = static_cast<long double>(n);
  const long double nb = static_cast<long double>(other.n);
  const long double nt = na + nb;
  const long double delta = (static_cast<long double>(other.mean) - mean) +
                            (static_cast<long double>(other.mean_lo) - mean_lo);
  const long double m = static_cast<long double>(mean) + mean_lo + delta * (nb / nt);
  m2 = static_cast<double>(static_cast<long double>(m2) + other.m2 + delta * delta * (na * nb / nt));
  mean = static_cast<double>(m);
  mean_lo = static_cast<double>(m - mean);
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

namespace detail {

long double exact_sum(const std::vector<double>& x) {
  // Shewchuk (1997), "Adaptive precision floating-point arithmetic": the partials are
  // non-overlapping doubles whose sum is exactly the sum of x (Python's math.fsum). Their sum in
  // long double, largest last, is the total to ~1e-19 relative.
  std::vector<double> partials;
  for (double v : x) {
    std::size_t i = 0;
    for (double p : partials) {
      if (std::fabs(v) < std::fabs(p)) std::swap(v, p);
      const double hi = v + p;
      const double lo = p - (hi - v);
      if (lo != 0) partials[i++] = lo;
      v = hi;
    }
    partials.resize(i);
    partials.push_back(v);
    if (!std::isfinite(v)) return std::numeric_limits<long double>::quiet_NaN();
  }
  long double total = 0;
  for (const double p : partials) total += p;
  return total;
}

Shifted shift_doubles(const std::vector<double>& x) {
  Shifted s;
  if (x.empty()) return s;
  s.shift = x[0];
  s.a.reserve(x.size());
  for (double v : x) s.a.push_back(static_cast<long double>(v) - s.shift);
  const long double total = exact_sum(x);
  if (std::isfinite(total)) s.total = total;
  return s;
}

Summary summary_of(const Shifted& sh) {
  Summary s;
  if (sh.a.empty()) return s;
  const long double n = static_cast<long double>(sh.a.size());
  // Pass 1: the mean of the shifted values, in extended precision.
  long double sum = 0, lo = sh.a[0], hi = sh.a[0];
  for (long double v : sh.a) {
    sum += v;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  const long double dmean = sum / n;
  // Pass 2: sum of squared deviations with the corrected two-pass algorithm (Chan, Golub &
  // LeVeque 1983, eq. 1.7): the second term removes the rounding error of the mean.
  long double ss = 0, corr = 0;
  for (long double v : sh.a) {
    const long double d = v - dmean;
    ss += d * d;
    corr += d;
  }
  s.n = sh.a.size();
  const long double mean = sh.total ? *sh.total / n / sh.scale : sh.shift + dmean / sh.scale;
  s.mean = static_cast<double>(mean);
  s.mean_lo = static_cast<double>(mean - s.mean);
  s.m2 = static_cast<double>(std::max(0.0L, ss - corr * corr / n) / (sh.scale * sh.scale));
  s.min = static_cast<double>(sh.shift + lo / sh.scale);
  s.max = static_cast<double>(sh.shift + hi / sh.scale);
  return s;
}

std::optional<double> autocorr_of(const Shifted& sh) {
  const auto& a = sh.a;
  if (a.size() < 2) return std::nullopt;
  long double sum = 0;
  for (long double v : a) sum += v;
  const long double mean = sum / static_cast<long double>(a.size());
  long double prev = a[0] - mean;
  long double num = 0, den = prev * prev;
  for (std::size_t i = 1; i < a.size(); ++i) {
    const long double d = a[i] - mean;
    num += d * prev;
    den += d * d;
    prev = d;
  }
  if (!(den > 0)) return std::nullopt;
  return static_cast<double>(num / den);
}

}  // namespace detail

Summary summarize(std::span<const double> x) {
  Summary s = detail::summary_of(detail::shift_doubles(std::vector<double>(x.begin(), x.end())));
  if (!x.empty()) {  // min and max exactly as given
    s.min = *std::min_element(x.begin(), x.end());
    s.max = *std::max_element(x.begin(), x.end());
  }
  return s;
}

double quantile_type7(std::span<const double> sorted, double p) {
  if (sorted.empty()) throw InvalidData("quantile of an empty sample");
  if (!(p >= 0.0 && p <= 1.0)) throw UsageError("quantile probability outside [0, 1]");
  // R's quantile.default, type 7, literally (1-based index, so h rounds exactly as in R):
  // index = 1 + (n - 1) p; lo = floor(index); (1 - h) x[lo] + h x[hi], h = index - lo.
  const double index = 1.0 + static_cast<double>(sorted.size() - 1) * p;
  const double lo = std::floor(index);
  const double hi = std::ceil(index);
  const double qlo = sorted[static_cast<std::size_t>(lo) - 1];
  const double qhi = sorted[static_cast<std::size_t>(hi) - 1];
  if (!(index > lo) || qhi == qlo) return qlo;
  const double h = index - lo;
  return (1 - h) * qlo + h * qhi;
}

std::optional<double> autocorr_lag1(std::span<const double> x) {
  return detail::autocorr_of(detail::shift_doubles(std::vector<double>(x.begin(), x.end())));
}

namespace {

std::vector<double> without_nan(std::span<const double> x) {
  std::vector<double> v;
  v.reserve(x.size());
  for (double d : x)
    if (!std::isnan(d)) v.push_back(d);
  return v;
}

}  // namespace

namespace detail {

Description describe_from(std::vector<double> sorted, const Summary& s,
                          const std::function<std::optional<double>()>& autocorr,
                          double conf_level) {
  check_conf_level(conf_level);
  Description d;
  d.n = sorted.size();
  if (sorted.empty()) {
    d.note = std::string("no values");
    return d;
  }
  std::sort(sorted.begin(), sorted.end());
  d.mean = s.mean;
  d.min = sorted.front();
  d.max = sorted.back();
  d.q1 = quantile_type7(sorted, 0.25);
  d.median = quantile_type7(sorted, 0.5);
  d.q3 = quantile_type7(sorted, 0.75);
  if (sorted.size() < 2) {
    d.note = std::string("n < 2: sd, standard error and confidence interval need at least two values");
    return d;
  }
  d.sd = s.sd();
  d.se = s.se();
  if (!std::isfinite(*d.sd)) {
    // Squared deviations beyond the largest double (values near 1e300): not computable, never Inf.
    d.sd.reset();
    d.se.reset();
    d.note = std::string("the sum of squared deviations exceeds the largest double: sd, standard "
                         "error and confidence interval not computable");
    return d;
  }
  if (!(*d.sd > 0)) {
    d.note = std::string("constant data: confidence interval and lag-1 autocorrelation undefined");
    return d;
  }
  const boost::math::students_t dist(static_cast<double>(sorted.size() - 1));
  const double q = boost::math::quantile(boost::math::complement(dist, (1.0 - conf_level) / 2.0));
  d.conf_low = s.mean - q * *d.se;
  d.conf_high = s.mean + q * *d.se;
  d.autocorr_lag1 = autocorr();
  return d;
}

}  // namespace detail

Description describe(std::span<const double> x, double conf_level) {
  detail::check_conf_level(conf_level);
  std::vector<double> v = without_nan(x);
  const Summary s = summarize(v);
  // Autocorrelation follows the input order, not the sorted one.
  return detail::describe_from(v, s, [&] { return autocorr_lag1(v); }, conf_level);
}

}  // namespace feint::stats

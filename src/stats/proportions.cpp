// Proportions of a yes/no answer and their comparison: see feint/stats/proportions.hpp.
#include "feint/stats/proportions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <fmt/format.h>

#include "feint/error.hpp"
#include "stats_detail.hpp"

namespace feint::stats {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double log_choose(double n, double k) {
  return std::lgamma(n + 1) - std::lgamma(k + 1) - std::lgamma(n - k + 1);
}

/// Fisher's noncentral hypergeometric law of the yes count of condition 1 given the margins.
class NoncentralHypergeometric {
 public:
  explicit NoncentralHypergeometric(const YesNoTable& t) {
    const double yes = static_cast<double>(t.yes1 + t.yes2);
    const double no = static_cast<double>((t.n1 - t.yes1) + (t.n2 - t.yes2));
    const double n1 = static_cast<double>(t.n1);
    lo_ = static_cast<long>(std::max(0.0, n1 - no));
    hi_ = static_cast<long>(std::min(n1, yes));
    for (long k = lo_; k <= hi_; ++k) {
      const double kd = static_cast<double>(k);
      log_c_.push_back(log_choose(yes, kd) + log_choose(no, n1 - kd));
    }
  }
  long lo() const { return lo_; }
  long hi() const { return hi_; }

  /// log P(X = k; psi) for every k of the support, psi = exp(log_psi).
  std::vector<double> log_density(double log_psi) const {
    std::vector<double> d(log_c_.size());
    double top = -kInf;
    for (std::size_t i = 0; i < d.size(); ++i) {
      d[i] = log_c_[i] + log_psi * static_cast<double>(lo_ + static_cast<long>(i));
      top = std::max(top, d[i]);
    }
    double sum = 0;
    for (const double v : d) sum += std::exp(v - top);
    const double log_norm = top + std::log(sum);
    for (double& v : d) v -= log_norm;
    return d;
  }
  double mean(double log_psi) const {
    const auto d = log_density(log_psi);
    double m = 0;
    for (std::size_t i = 0; i < d.size(); ++i) m += static_cast<double>(lo_ + static_cast<long>(i)) * std::exp(d[i]);
    return m;
  }
  /// P(X <= x; psi) (lower) or P(X >= x; psi) (upper), summed from the tail itself.
  double tail(long x, double log_psi, bool upper) const {
    const auto d = log_density(log_psi);
    double p = 0;
    for (std::size_t i = 0; i < d.size(); ++i) {
      const long k = lo_ + static_cast<long>(i);
      if (upper ? k >= x : k <= x) p += std::exp(d[i]);
    }
    return std::min(1.0, p);
  }

 private:
  long lo_ = 0, hi_ = 0;
  std::vector<double> log_c_;
};

/// The log psi where the increasing function f crosses `target` (bracket grown from 0).
template <class F>
double increasing_root(F f, double target) {
  double lo = -1, hi = 1;
  for (int k = 0; f(lo) > target && k < 60; ++k) lo *= 2;
  for (int k = 0; f(hi) < target && k < 60; ++k) hi *= 2;
  std::uintmax_t iters = 300;
  const auto r = boost::math::tools::toms748_solve([&](double v) { return f(v) - target; }, lo, hi,
                                                   boost::math::tools::eps_tolerance<double>(50), iters);
  return 0.5 * (r.first + r.second);
}

void check_table(const YesNoTable& t) {
  if (t.yes1 > t.n1 || t.yes2 > t.n2)
    throw UsageError(fmt::format("a yes count exceeds its answers ({} of {}, {} of {})", t.yes1, t.n1,
                                 t.yes2, t.n2));
}

void fill_fisher_p(TestResult& r, const NoncentralHypergeometric& law, long x, Alternative alt) {
  if (alt == Alternative::less) {
    r.p_value = law.tail(x, 0, false);
  } else if (alt == Alternative::greater) {
    r.p_value = law.tail(x, 0, true);
  } else {
    // R: the tables no more probable than the one observed, with a relative tolerance of 1e-7.
    const auto d = law.log_density(0);
    const double cut = d[static_cast<std::size_t>(x - law.lo())] + std::log1p(1e-7);
    double p = 0;
    for (const double v : d)
      if (v <= cut) p += std::exp(v);
    r.p_value = std::min(1.0, p);
  }
}

/// What both comparisons of two proportions report alike: the settings, the sizes and the
/// proportions of yes (as mean1, mean2).
TestResult two_proportions(const char* test, const char* method, const YesNoTable& t, const TestOptions& options,
                           double mu) {
  TestResult r;
  r.test = test;
  r.method = method;
  r.alternative = options.alternative;
  r.conf_level = options.conf_level;
  r.mu = mu;
  r.n1 = t.n1;
  r.n2 = t.n2;
  r.mean1 = static_cast<double>(t.yes1) / static_cast<double>(t.n1);
  r.mean2 = static_cast<double>(t.yes2) / static_cast<double>(t.n2);
  return r;
}

}  // namespace

Proportion describe_proportion(std::size_t x, std::size_t n, double conf_level) {
  detail::check_conf_level(conf_level);
  if (x > n) throw UsageError(fmt::format("{} yes answers among {} answers", x, n));
  Proportion p{x, n, conf_level, kNaN, kNaN, kNaN, kNaN, kNaN};
  if (n == 0) return p;
  const double xd = static_cast<double>(x), nd = static_cast<double>(n);
  const double alpha = 1 - conf_level;
  p.estimate = xd / nd;
  p.exact_low = x == 0 ? 0.0 : boost::math::ibeta_inv(xd, nd - xd + 1, alpha / 2);
  p.exact_high = x == n ? 1.0 : boost::math::ibetac_inv(xd + 1, nd - xd, alpha / 2);
  const double z = boost::math::quantile(boost::math::normal(), 1 - alpha / 2);
  const double centre = xd + z * z / 2, half = z * std::sqrt(xd * (nd - xd) / nd + z * z / 4);
  p.wilson_low = std::max(0.0, (centre - half) / (nd + z * z));
  p.wilson_high = std::min(1.0, (centre + half) / (nd + z * z));
  return p;
}

TestResult fisher_exact(const YesNoTable& t, const TestOptions& options) {
  detail::check_conf_level(options.conf_level);
  check_table(t);
  const char* method = "Fisher's Exact Test for Count Data";
  if (t.n1 == 0 || t.n2 == 0)
    return TestResult::not_computable("fisher_exact", method, "a condition has no answer");
  TestResult r = two_proportions("fisher_exact", method, t, options, 1.0);  // H0: odds ratio 1
  const NoncentralHypergeometric law(t);
  const long x = static_cast<long>(t.yes1);
  fill_fisher_p(r, law, x, options.alternative);
  if (law.lo() == law.hi()) {  // one table only: every odds ratio fits it equally well (R: 0)
    r.note = "the margins allow one table only (every answer is the same): no odds ratio";
    r.conf_low = 0.0;
    r.conf_high = kInf;
    return r;
  }
  auto mean = [&](double v) { return law.mean(v); };
  r.estimate = x == law.lo() ? 0.0 : x == law.hi() ? kInf : std::exp(increasing_root(mean, static_cast<double>(x)));
  const bool two = options.alternative == Alternative::two_sided;
  const double alpha = two ? (1 - options.conf_level) / 2 : 1 - options.conf_level;
  // psi_L: P(X >= x; psi) = alpha (increasing in psi); psi_U: P(X <= x; psi) = alpha (decreasing).
  auto lower = [&] {
    if (x == law.lo()) return 0.0;
    return std::exp(increasing_root([&](double v) { return law.tail(x, v, true); }, alpha));
  };
  auto upper = [&] {
    if (x == law.hi()) return kInf;
    return std::exp(increasing_root([&](double v) { return -law.tail(x, v, false); }, -alpha));
  };
  r.conf_low = options.alternative == Alternative::less ? 0.0 : lower();
  r.conf_high = options.alternative == Alternative::greater ? kInf : upper();
  return r;
}

TestResult prop_test(const YesNoTable& t, const TestOptions& options, bool correct) {
  detail::check_conf_level(options.conf_level);
  check_table(t);
  const char* method = correct ? "2-sample test for equality of proportions with continuity correction"
                               : "2-sample test for equality of proportions without continuity correction";
  if (t.n1 == 0 || t.n2 == 0) return TestResult::not_computable("prop_test", method, "a condition has no answer");
  const double n1 = static_cast<double>(t.n1), n2 = static_cast<double>(t.n2);
  const double y1 = static_cast<double>(t.yes1), y2 = static_cast<double>(t.yes2);
  const double pooled = (y1 + y2) / (n1 + n2);
  if (pooled == 0 || pooled == 1)
    return TestResult::not_computable("prop_test", method,
                                      pooled == 0 ? "every answer is no" : "every answer is yes");
  TestResult r = two_proportions("prop_test", method, t, options, 0.0);  // H0: p1 - p2 = 0
  const double p1 = *r.mean1, p2 = *r.mean2, delta = p1 - p2, inv = 1 / n1 + 1 / n2;
  r.estimate = delta;
  const double yates = std::min(correct ? 0.5 : 0.0, std::fabs(delta) / inv);
  const bool two = options.alternative == Alternative::two_sided;
  const double z = boost::math::quantile(boost::math::normal(), two ? (1 + options.conf_level) / 2 : options.conf_level);
  const double width = z * std::sqrt(p1 * (1 - p1) / n1 + p2 * (1 - p2) / n2) + yates * inv;
  r.conf_low = options.alternative == Alternative::less ? -1.0 : std::max(delta - width, -1.0);
  r.conf_high = options.alternative == Alternative::greater ? 1.0 : std::min(delta + width, 1.0);
  const double observed[4] = {y1, n1 - y1, y2, n2 - y2};
  const double expected[4] = {n1 * pooled, n1 * (1 - pooled), n2 * pooled, n2 * (1 - pooled)};
  double x2 = 0;
  bool small = false;
  for (int i = 0; i < 4; ++i) {
    x2 += std::pow(std::fabs(observed[i] - expected[i]) - yates, 2) / expected[i];
    small = small || expected[i] < 5;
  }
  r.statistic = x2;
  r.statistic_name = "X-squared";
  r.df = 1.0;
  if (two) {
    r.p_value = boost::math::cdf(boost::math::complement(boost::math::chi_squared(1.0), x2));
  } else {
    const double zs = (delta > 0 ? 1.0 : delta < 0 ? -1.0 : 0.0) * std::sqrt(x2);
    const boost::math::normal normal;
    r.p_value = options.alternative == Alternative::less ? boost::math::cdf(normal, zs)
                                                         : boost::math::cdf(boost::math::complement(normal, zs));
  }
  if (small) r.note = "Chi-squared approximation may be incorrect (an expected count is below 5)";
  return r;
}

}  // namespace feint::stats

#include "feint/stats/ttest.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/stats/descriptive.hpp"
#include "stats_detail.hpp"

namespace feint::stats {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

std::vector<double> drop_nan(std::span<const double> x) {
  std::vector<double> v;
  v.reserve(x.size());
  for (double d : x)
    if (!std::isnan(d)) v.push_back(d);
  return v;
}

TestResult base(std::string test, std::string method, double mu, const TestOptions& options) {
  detail::check_conf_level(options.conf_level);
  TestResult r;
  r.test = std::move(test);
  r.method = std::move(method);
  r.alternative = options.alternative;
  r.conf_level = options.conf_level;
  r.mu = mu;
  r.statistic_name = std::string("t");
  return r;
}

void cannot(TestResult& r, std::string reason) {
  r.computed = false;
  r.note = std::move(reason);
}

/// Fills statistic, df, p, CI from t = (estimate - mu) / stderr (R's t.test arithmetic).
void finish_t(TestResult& r, double estimate, double stderr_, double df) {
  const double t = (estimate - *r.mu) / stderr_;
  r.estimate = estimate;
  r.statistic = t;
  r.df = df;
  r.p_value = detail::t_p_value(t, df, r.alternative);
  const auto ci = detail::t_interval(t, df, stderr_, *r.mu, r.conf_level, r.alternative);
  r.conf_low = ci.low;
  r.conf_high = ci.high;
}

void set_effect(TestResult& r, double d, double df_j) {
  r.cohen_d = d;
  const double j = detail::hedges_j(df_j);
  if (std::isfinite(j)) r.hedges_g = d * j;
}

TestResult one_sample_impl(std::vector<double> v, double mu, const TestOptions& options,
                           std::string test, std::string method) {
  TestResult r = base(std::move(test), std::move(method), mu, options);
  r.n1 = v.size();
  if (v.size() < 2) {
    cannot(r, fmt::format("not enough observations: n = {} (a t-test needs at least 2)", v.size()));
    if (v.size() == 1) r.mean1 = v[0];
    return r;
  }
  const Summary s = summarize(v);
  const double n = static_cast<double>(s.n);
  const double sd = *s.sd();
  const double stderr_ = sd / std::sqrt(n);
  r.mean1 = s.mean;
  r.sd1 = sd;
  // R: stop("data are essentially constant") when stderr < 10 eps |mean|.
  if (!std::isfinite(stderr_) || !std::isfinite(s.mean)) {
    cannot(r, "infinite values in the data");
    return r;
  }
  if (stderr_ < 10 * kEps * std::fabs(s.mean) || stderr_ == 0) {
    cannot(r, "data are essentially constant");
    return r;
  }
  finish_t(r, s.mean, stderr_, n - 1);
  set_effect(r, (s.mean - mu) / sd, n - 1);
  return r;
}

TestResult two_sample_impl(std::span<const double> xs, std::span<const double> ys,
                           const TestOptions& options, double mu, bool var_equal) {
  TestResult r = base(var_equal ? "student_t" : "welch_t",
                      var_equal ? "Two Sample t-test" : "Welch Two Sample t-test", mu, options);
  const std::vector<double> x = drop_nan(xs), y = drop_nan(ys);
  r.n1 = x.size();
  r.n2 = y.size();
  const Summary sx = summarize(x), sy = summarize(y);
  if (!x.empty()) r.mean1 = sx.mean;
  if (!y.empty()) r.mean2 = sy.mean;
  r.sd1 = sx.sd();
  r.sd2 = sy.sd();
  if (x.empty() || y.empty()) {
    cannot(r, fmt::format("empty group ({})", x.empty() ? "x" : "y"));
    return r;
  }
  if (var_equal) {
    if (x.size() + y.size() < 3) {
      cannot(r, "not enough observations: n1 + n2 < 3");
      return r;
    }
  } else if (x.size() < 2 || y.size() < 2) {
    cannot(r, fmt::format("not enough observations in {}: n = 1 (Welch's test needs at least 2 "
                          "per group)",
                          x.size() < 2 ? "x" : "y"));
    return r;
  }
  const double nx = static_cast<double>(x.size()), ny = static_cast<double>(y.size());
  const double vx = sx.variance().value_or(0.0), vy = sy.variance().value_or(0.0);
  double stderr_ = 0, df = 0;
  if (var_equal) {
    df = nx + ny - 2;
    double v = 0;
    if (x.size() > 1) v += (nx - 1) * vx;
    if (y.size() > 1) v += (ny - 1) * vy;
    v /= df;
    stderr_ = std::sqrt(v * (1 / nx + 1 / ny));
  } else {
    const double sex2 = vx / nx, sey2 = vy / ny;
    stderr_ = std::sqrt(sex2 + sey2);
    df = (stderr_ * stderr_) * (stderr_ * stderr_) /
         (sex2 * sex2 / (nx - 1) + sey2 * sey2 / (ny - 1));
  }
  if (!std::isfinite(stderr_) || !std::isfinite(sx.mean) || !std::isfinite(sy.mean)) {
    cannot(r, "infinite values in the data");
    return r;
  }
  if (stderr_ < 10 * kEps * std::max(std::fabs(sx.mean), std::fabs(sy.mean)) || stderr_ == 0) {
    cannot(r, "data are essentially constant");
    return r;
  }
  finish_t(r, sx.mean - sy.mean, stderr_, df);
  // Cohen's d with the pooled sd of both groups (for Welch's test too), df for J: n1 + n2 - 2.
  const double pooled_df = nx + ny - 2;
  if (pooled_df > 0) {
    const double sp = std::sqrt(((nx - 1) * vx + (ny - 1) * vy) / pooled_df);
    if (sp > 0) set_effect(r, (sx.mean - sy.mean - mu) / sp, pooled_df);
  }
  return r;
}

std::vector<double> paired_differences(std::span<const double> x, std::span<const double> y,
                                       std::vector<double>* xs, std::vector<double>* ys) {
  if (x.size() != y.size())
    throw InvalidData(fmt::format("paired t-test: x has {} values but y has {}; pairs must match",
                                  x.size(), y.size()));
  std::vector<double> d;
  d.reserve(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (std::isnan(x[i]) || std::isnan(y[i])) continue;  // R's complete.cases
    d.push_back(x[i] - y[i]);
    xs->push_back(x[i]);
    ys->push_back(y[i]);
  }
  return d;
}

double check_tost(double delta, const TestOptions& options) {
  detail::check_conf_level(options.conf_level);
  if (!(delta > 0) || !std::isfinite(delta))
    throw UsageError(fmt::format("equivalence margin {} must be positive and finite", delta));
  if (!(options.conf_level > 0.5))
    throw UsageError(fmt::format(
        "TOST needs a confidence level above 0.5 (the interval is at 1 - 2 alpha), got {}",
        options.conf_level));
  return 1.0 - 2.0 * (1.0 - options.conf_level);
}

/// Combines the lower test (H0: true <= mu - delta) and the upper test (H0: true >= mu + delta)
/// with the two-sided estimate at 1 - 2 alpha.
TestResult combine_tost(TestResult lower, TestResult upper, TestResult centre, double mu,
                        double delta, std::string method) {
  TestResult r = std::move(centre);
  r.test = std::string("tost");
  r.method = std::move(method);
  r.mu = mu;
  r.margin = delta;
  r.alternative = Alternative::two_sided;
  if (!lower.computed || !upper.computed || !r.computed) {
    r.computed = false;
    r.statistic.reset();
    r.df.reset();
    r.p_value.reset();
    r.conf_low.reset();
    r.conf_high.reset();
    if (r.note.empty()) r.note = lower.note;
    return r;
  }
  const TestResult& worse = *lower.p_value >= *upper.p_value ? lower : upper;
  r.statistic = worse.statistic;
  r.df = worse.df;
  r.p_value = worse.p_value;
  return r;
}

}  // namespace

TestResult t_test_one_sample(std::span<const double> x, double mu, const TestOptions& options) {
  return one_sample_impl(drop_nan(x), mu, options, "one_sample_t", "One Sample t-test");
}

TestResult t_test_welch(std::span<const double> x, std::span<const double> y,
                        const TestOptions& options, double mu) {
  return two_sample_impl(x, y, options, mu, false);
}

TestResult t_test_student(std::span<const double> x, std::span<const double> y,
                          const TestOptions& options, double mu) {
  return two_sample_impl(x, y, options, mu, true);
}

TestResult t_test_paired(std::span<const double> x, std::span<const double> y,
                         const TestOptions& options, double mu) {
  std::vector<double> xs, ys;
  std::vector<double> d = paired_differences(x, y, &xs, &ys);
  TestResult r = one_sample_impl(std::move(d), mu, options, "paired_t", "Paired t-test");
  // group 1/2 describe the two conditions; the test itself is on the differences.
  r.n1 = r.n2 = xs.size();
  const Summary sx = summarize(xs), sy = summarize(ys);
  r.mean1.reset();
  if (!xs.empty()) {
    r.mean1 = sx.mean;
    r.mean2 = sy.mean;
  }
  r.sd1 = sx.sd();
  r.sd2 = sy.sd();
  return r;
}

TestResult tost_one_sample(std::span<const double> x, double mu, double delta,
                           const TestOptions& options) {
  const double inner = check_tost(delta, options);
  return combine_tost(
      t_test_one_sample(x, mu - delta, {Alternative::greater, options.conf_level}),
      t_test_one_sample(x, mu + delta, {Alternative::less, options.conf_level}),
      t_test_one_sample(x, mu, {Alternative::two_sided, inner}), mu, delta,
      "One Sample TOST equivalence test (two one-sided t-tests)");
}

TestResult tost_two_sample(std::span<const double> x, std::span<const double> y, double delta,
                           bool var_equal, const TestOptions& options) {
  const double inner = check_tost(delta, options);
  const auto test = var_equal ? t_test_student : t_test_welch;
  return combine_tost(test(x, y, {Alternative::greater, options.conf_level}, -delta),
                      test(x, y, {Alternative::less, options.conf_level}, delta),
                      test(x, y, {Alternative::two_sided, inner}, 0.0), 0.0, delta,
                      var_equal ? "Two Sample TOST equivalence test (two one-sided t-tests)"
                                : "Welch Two Sample TOST equivalence test (two one-sided t-tests)");
}

TestResult tost_paired(std::span<const double> x, std::span<const double> y, double delta,
                       const TestOptions& options) {
  const double inner = check_tost(delta, options);
  return combine_tost(t_test_paired(x, y, {Alternative::greater, options.conf_level}, -delta),
                      t_test_paired(x, y, {Alternative::less, options.conf_level}, delta),
                      t_test_paired(x, y, {Alternative::two_sided, inner}, 0.0), 0.0, delta,
                      "Paired TOST equivalence test (two one-sided t-tests)");
}

}  // namespace feint::stats

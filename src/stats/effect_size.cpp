// Effect-size intervals: see feint/stats/effect_size.hpp.
#include "feint/stats/effect_size.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/non_central_f.hpp>
#include <boost/math/distributions/non_central_t.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/tools/roots.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <fmt/format.h>

#include "feint/error.hpp"
#include "stats_detail.hpp"

namespace feint::stats {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Two-sided level that gives the one-sided interval (effectsize's .adjust_ci).
double adjusted_level(double conf_level, Alternative alternative) {
  detail::check_conf_level(conf_level);
  return alternative == Alternative::two_sided ? conf_level : 2 * conf_level - 1;
}

/// Root of g(x) = 0 for g decreasing in x, bracketed by expanding from `start` by `step`.
template <class G>
double decreasing_root(G g, double start, double step) {
  double lo = start - step, hi = start + step;
  for (int k = 0; g(lo) < 0 && k < 200; ++k) lo -= step *= 2;
  step = std::max(1.0, std::fabs(start) * 0.1);
  for (int k = 0; g(hi) > 0 && k < 200; ++k) hi += step *= 2;
  std::uintmax_t iters = 300;
  auto tol = boost::math::tools::eps_tolerance<double>(52);
  auto res = boost::math::tools::toms748_solve(g, lo, hi, tol, iters);
  return 0.5 * (res.first + res.second);
}

}  // namespace

EffectInterval noncentral_t_ncp_interval(double t, double df, double conf_level, Alternative alternative) {
  if (!std::isfinite(t) || !(df > 0)) throw InvalidData(fmt::format("ncp interval: t = {}, df = {}", t, df));
  const double level = adjusted_level(conf_level, alternative);
  if (!(level > 0)) throw UsageError(fmt::format("one-sided interval needs a level above 0.5, got {}", conf_level));
  const double a = (1 - level) / 2;
  auto cdf_minus = [&](double p) {
    return [=](double ncp) { return boost::math::cdf(boost::math::non_central_t(df, ncp), t) - p; };
  };
  const double step = 1 + std::fabs(t) * 0.1;
  EffectInterval out{decreasing_root(cdf_minus(1 - a), t, step), decreasing_root(cdf_minus(a), t, step)};
  if (alternative == Alternative::greater) out.high = kInf;
  if (alternative == Alternative::less) out.low = -kInf;
  return out;
}

EffectInterval cohen_d_interval_one_sample(double t, std::size_t n, double conf_level, Alternative alternative) {
  if (n < 2) throw InvalidData(fmt::format("d interval: n = {} (needs at least 2)", n));
  EffectInterval i = noncentral_t_ncp_interval(t, static_cast<double>(n) - 1, conf_level, alternative);
  const double s = std::sqrt(1.0 / static_cast<double>(n));
  return {i.low * s, i.high * s};
}

EffectInterval cohen_d_interval_two_sample(double t, std::size_t n1, std::size_t n2, double conf_level,
                                           Alternative alternative) {
  if (n1 < 1 || n2 < 1 || n1 + n2 < 3) throw InvalidData(fmt::format("d interval: groups of {} and {}", n1, n2));
  const double a = static_cast<double>(n1), b = static_cast<double>(n2);
  EffectInterval i = noncentral_t_ncp_interval(t, a + b - 2, conf_level, alternative);
  const double s = std::sqrt(1 / a + 1 / b);
  return {i.low * s, i.high * s};
}

EtaSquared generalized_eta2(double ges, double df1, double df2, double conf_level, Alternative alternative) {
  if (!(ges >= 0 && ges < 1) || !(df1 > 0) || !(df2 > 0))
    throw InvalidData(fmt::format("generalized eta squared: ges = {}, df = {}, {}", ges, df1, df2));
  EtaSquared out = f_to_eta2((ges / df1) / ((1 - ges) / df2), df1, df2, conf_level, alternative);
  out.estimate = ges;  // F* maps back to ges; keep it exact
  return out;
}

EtaSquared f_to_eta2(double f, double df1, double df2, double conf_level, Alternative alternative) {
  if (!std::isfinite(f) || f < 0 || !(df1 > 0) || !(df2 > 0))
    throw InvalidData(fmt::format("eta squared: F = {}, df = {}, {}", f, df1, df2));
  if (alternative == Alternative::less)
    throw UsageError("eta squared: alternative 'less' is not meaningful (eta squared >= 0)");
  const double level = adjusted_level(conf_level, alternative);
  const double a = (1 - level) / 2;
  EtaSquared out{f * df1 / (f * df1 + df2), 0, 1};
  const boost::math::fisher_f central(df1, df2);
  auto root = [&](double p) {
    auto g = [=](double ncp) {
      return boost::math::cdf(boost::math::non_central_f(df1, df2, ncp), f) - p;
    };
    // g(0) = pf(F) - p > 0 is checked by the caller; the root lies above 0
    double hi = std::max(1.0, f * df1);
    for (int k = 0; g(hi) > 0 && k < 200; ++k) hi *= 2;
    std::uintmax_t iters = 300;
    auto tol = boost::math::tools::eps_tolerance<double>(52);
    auto res = boost::math::tools::toms748_solve(g, 0.0, hi, tol, iters);
    return 0.5 * (res.first + res.second);
  };
  const double pf0 = boost::math::cdf(central, f);
  // effectsize: a bound is 0 when F is at or below the central quantile (pf(F, ncp = 0) <= p).
  if (pf0 > 1 - a) {
    const double ncp = root(1 - a);
    out.low = ncp / (ncp + df2);
  }
  if (alternative == Alternative::two_sided) {
    if (pf0 > a) {
      const double ncp = root(a);
      out.high = ncp / (ncp + df2);
    } else {
      out.high = 0;
    }
  }
  return out;
}

EffectInterval rank_biserial_interval(double r, std::size_t n1, std::size_t n2, double conf_level,
                                      Alternative alternative) {
  if (!(r >= -1 && r <= 1)) throw InvalidData(fmt::format("rank-biserial r = {} outside [-1, 1]", r));
  const double level = adjusted_level(conf_level, alternative);
  double se = 0;
  if (n2 == 0) {
    const double n = static_cast<double>(n1);
    if (n1 < 1) throw InvalidData("rank-biserial interval: no non-zero differences");
    se = std::sqrt((2 * n * n * n + 3 * n * n + n) / 6) / ((n * n + n) / 2);
  } else {
    const double a = static_cast<double>(n1), b = static_cast<double>(n2);
    se = std::sqrt((a + b + 1) / (3 * a * b));
  }
  const double z = boost::math::quantile(boost::math::complement(boost::math::normal(), (1 - level) / 2));
  EffectInterval out{r, r};  // r = +-1: atanh is infinite and the interval degenerates to [r, r]
  if (std::fabs(r) < 1) {
    const double rf = std::atanh(r);
    out = {std::tanh(rf - z * se), std::tanh(rf + z * se)};
  }
  if (alternative == Alternative::greater) out.high = 1;
  if (alternative == Alternative::less) out.low = -1;
  return out;
}

void add_effect_size_intervals(TestResult& test, std::size_t n_nonzero) {
  if (!test.computed) return;
  const double level = test.conf_level;
  const Alternative alt = test.alternative;
  if (alt != Alternative::two_sided && !(level > 0.5)) return;
  if ((test.test == "one_sample_t" || test.test == "paired_t") && test.statistic && test.cohen_d) {
    const auto n = test.n1;
    if (n < 2) return;
    // d = (mean - mu)/sd and t = d sqrt(n): the pivot's t is the test's t.
    const auto i = cohen_d_interval_one_sample(*test.statistic, n, level, alt);
    test.cohen_d_low = i.low;
    test.cohen_d_high = i.high;
    if (test.hedges_g) {
      const double j = detail::hedges_j(static_cast<double>(n) - 1);
      test.hedges_g_low = i.low * j;
      test.hedges_g_high = i.high * j;
    }
  } else if ((test.test == "student_t" || test.test == "welch_t") && test.cohen_d) {
    const double a = static_cast<double>(test.n1), b = static_cast<double>(test.n2);
    const double t = *test.cohen_d / std::sqrt(1 / a + 1 / b);  // the pooled t
    const auto i = cohen_d_interval_two_sample(t, test.n1, test.n2, level, alt);
    test.cohen_d_low = i.low;
    test.cohen_d_high = i.high;
    if (test.hedges_g) {
      const double j = detail::hedges_j(a + b - 2);
      test.hedges_g_low = i.low * j;
      test.hedges_g_high = i.high * j;
    }
  } else if (test.rank_biserial && (test.test == "wilcoxon_signed_rank" || test.test == "mann_whitney")) {
    const bool one = test.test == "wilcoxon_signed_rank";
    const std::size_t n = one ? (n_nonzero ? n_nonzero : test.n1) : test.n1;
    if (n == 0 || (!one && test.n2 == 0)) return;
    const auto i = rank_biserial_interval(*test.rank_biserial, n, one ? 0 : test.n2, level, alt);
    test.rank_biserial_low = i.low;
    test.rank_biserial_high = i.high;
  } else if (test.test == "anova" && test.statistic && test.df && test.df2) {
    const auto e = f_to_eta2(*test.statistic, *test.df, *test.df2, level, Alternative::greater);
    test.eta_squared_low = e.low;
    test.eta_squared_high = e.high;
  }
}

}  // namespace feint::stats

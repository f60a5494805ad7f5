// Analytic t-test power (see power.hpp).
#include "feint/models/power.hpp"

#include <fmt/format.h>

#include <boost/math/distributions/non_central_t.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <limits>

#include "feint/error.hpp"

namespace feint::models {

namespace detail {
namespace {

struct Noncentral {
  double df = 0, ncp = 0;
};

double alpha_per_test(const TTestPowerSpec& s) { return s.alpha / s.tests; }

Noncentral noncentral(const TTestPowerSpec& s, double n, double delta) {
  Noncentral t;
  switch (s.design) {
    case TTestDesign::one_sample:
    case TTestDesign::paired:
      t.df = n - 1;
      t.ncp = std::sqrt(n) * delta / s.sd;
      break;
    case TTestDesign::two_sample: {
      const double n2 = s.ratio * n;
      if (!s.welch) {
        t.df = n + n2 - 2;
        t.ncp = delta / (s.sd * std::sqrt(1 / n + 1 / n2));
      } else {
        const double sd2 = s.sd2.value_or(s.sd);
        const double v1 = s.sd * s.sd / n, v2 = sd2 * sd2 / n2;
        t.df = (v1 + v2) * (v1 + v2) / (v1 * v1 / (n - 1) + v2 * v2 / (n2 - 1));
        t.ncp = delta / std::sqrt(v1 + v2);
      }
      break;
    }
  }
  return t;
}

double power_at(const TTestPowerSpec& s, double n, double delta) {
  namespace bm = boost::math;
  const Noncentral t = noncentral(s, n, delta);
  const double a = alpha_per_test(s);
  const bm::non_central_t dist(t.df, t.ncp);
  const bm::students_t central(t.df);
  switch (s.alternative) {
    case stats::Alternative::two_sided: {
      const double q = bm::quantile(bm::complement(central, a / 2));
      return bm::cdf(bm::complement(dist, q)) + bm::cdf(dist, -q);
    }
    case stats::Alternative::greater:
      return bm::cdf(bm::complement(dist, bm::quantile(bm::complement(central, a))));
    case stats::Alternative::less: {
      // delta is the size of the effect in the hypothesised direction: a true difference of
      // -delta (pwr::pwr.t.test with d < 0), the mirror image of `greater`.
      const bm::non_central_t mirrored(t.df, -t.ncp);
      return bm::cdf(mirrored, -bm::quantile(bm::complement(central, a)));
    }
  }
  return 0;
}

/// The root of f (increasing) in [lo, hi], hi doubled until f(hi) >= 0.
template <class F>
double increasing_root(F f, double lo, double hi, double hi_limit, const char* what) {
  if (f(lo) >= 0) return lo;  // the smallest allowed value already reaches the target
  while (f(hi) < 0) {
    lo = hi;
    hi *= 2;
    if (hi > hi_limit)
      throw UsageError(fmt::format("no {} up to {} reaches the power asked for", what, hi_limit));
  }
  std::uintmax_t iterations = 200;
  const auto r = boost::math::tools::toms748_solve(
      f, lo, hi, boost::math::tools::eps_tolerance<double>(52), iterations);
  return (r.first + r.second) / 2;
}

double n_minimum(const TTestPowerSpec& s) {
  // Two observations per group at least (one-sample/paired: n - 1 >= 1 df; Welch: n2 >= 2 too).
  if (s.design == TTestDesign::two_sample && s.welch) return std::max(2.0, 2.0 / s.ratio);
  if (s.design == TTestDesign::two_sample) return std::max(2.0, 1.0 / s.ratio);
  return 2.0;
}

}  // namespace
}  // namespace detail

TTestDesign parse_t_test_design(std::string_view text) {
  if (text == "one-sample" || text == "one.sample") return TTestDesign::one_sample;
  if (text == "two-sample" || text == "two.sample") return TTestDesign::two_sample;
  if (text == "paired") return TTestDesign::paired;
  throw UsageError(fmt::format("--type '{}': expected one-sample, two-sample or paired", text));
}

std::string_view to_string(TTestDesign design) noexcept {
  switch (design) {
    case TTestDesign::one_sample:
      return "one-sample";
    case TTestDesign::two_sample:
      return "two-sample";
    case TTestDesign::paired:
      return "paired";
  }
  return "";
}

double t_test_power(const TTestPowerSpec& s) {
  if (!s.n || !s.delta) throw UsageError("t_test_power needs n and delta");
  return detail::power_at(s, *s.n, *s.delta);
}

namespace {

/// The options that do not depend on the one solved for.
void check_options(const TTestPowerSpec& spec) {
  const int missing = !spec.n + !spec.delta + !spec.power;
  if (missing != 1) {
    throw UsageError(
        "give exactly two of --n, --delta (or --d) and --power; the third is solved for");
  }
  if (!(spec.alpha > 0 && spec.alpha < 1))
    throw UsageError(fmt::format("--alpha {}: expected a number in (0, 1)", spec.alpha));
  if (spec.tests < 1)
    throw UsageError(fmt::format("--tests {}: expected a whole number >= 1", spec.tests));
  if (!(spec.sd > 0) || !std::isfinite(spec.sd) ||
      (spec.sd2 && !(*spec.sd2 > 0 && std::isfinite(*spec.sd2)))) {
    throw UsageError("--sd and --sd2 must be positive numbers");
  }
  if (!(spec.ratio > 0) || !std::isfinite(spec.ratio))
    throw UsageError(fmt::format("--ratio {}: expected a positive number", spec.ratio));
  if (spec.sd2 && !spec.welch)
    throw UsageError("--sd2 needs --welch (Student's test assumes one common sd)");
  if ((spec.welch || spec.ratio != 1.0) && spec.design != TTestDesign::two_sample) {
    throw UsageError("--welch and --ratio apply to --type two-sample only");
  }
}

/// The two of n, delta and power that are given (`a`: alpha per test).
void check_given(const TTestPowerSpec& spec, double a, double nmin) {
  if (spec.n && !(*spec.n >= nmin && std::isfinite(*spec.n))) {
    throw UsageError(fmt::format("--n {}: expected at least {} per group", *spec.n, nmin));
  }
  if (spec.delta && !(*spec.delta > 0 && std::isfinite(*spec.delta))) {
    throw UsageError(fmt::format(
        "--delta {}: expected a positive difference (the direction is set by --alternative)",
        *spec.delta));
  }
  if (spec.power && !(*spec.power > a && *spec.power < 1)) {
    throw UsageError(
        fmt::format("--power {}: expected a number in (alpha per test = {}, 1)", *spec.power, a));
  }
}

/// Fills in the one of n, delta and power that `s` lacks.
void solve_missing(TTestPowerSpec& s, double nmin) {
  if (!s.power) {
    s.power = detail::power_at(s, *s.n, *s.delta);
  } else if (!s.n) {
    const double target = *s.power;
    s.n =
        detail::increasing_root([&](double n) { return detail::power_at(s, n, *s.delta) - target; },
                                nmin, std::max(nmin * 2, 8.0), 1e9, "sample size");
  } else {
    const double target = *s.power;
    const double hi0 = s.sd;
    s.delta =
        detail::increasing_root([&](double d) { return detail::power_at(s, *s.n, d) - target; },
                                1e-9 * hi0, hi0, 1e9 * hi0, "difference");
  }
}

/// A solved n rounded up to whole participants, and the power there.
void round_up_participants(TTestPowerResult& r) {
  const TTestPowerSpec& s = r.spec;
  r.n1_ceiling = std::ceil(r.n1);
  if (s.design == TTestDesign::two_sample) {
    r.n2_ceiling = std::ceil(s.ratio * *r.n1_ceiling);
  }
  // Power at whole participants: group 2 rounded up on its own (never below the target).
  TTestPowerSpec whole = s;
  whole.n = *r.n1_ceiling;
  if (r.n2_ceiling) whole.ratio = *r.n2_ceiling / *r.n1_ceiling;
  r.power_at_ceiling = detail::power_at(whole, *whole.n, *s.delta);
}

const char* method_name(const TTestPowerSpec& s) {
  switch (s.design) {
    case TTestDesign::one_sample:
      return "One-sample t test power calculation";
    case TTestDesign::paired:
      return "Paired t test power calculation";
    case TTestDesign::two_sample:
      return s.welch ? "Two-sample t test power calculation (Welch, approximate)"
                     : "Two-sample t test power calculation (Student)";
  }
  return "";
}

}  // namespace

TTestPowerResult solve_t_test_power(const TTestPowerSpec& spec) {
  check_options(spec);
  const double a = spec.alpha / spec.tests;
  const double nmin = detail::n_minimum(spec);
  check_given(spec, a, nmin);

  TTestPowerResult r;
  r.spec = spec;
  r.alpha_per_test = a;
  TTestPowerSpec& s = r.spec;
  solve_missing(s, nmin);
  r.n1 = *s.n;
  r.n2 = s.design == TTestDesign::two_sample ? s.ratio * r.n1 : 0;
  const auto nc = detail::noncentral(s, r.n1, *s.delta);
  r.df = nc.df;
  r.ncp = nc.ncp;
  if (!spec.n) round_up_participants(r);
  r.method = method_name(s);
  return r;
}

}  // namespace feint::models

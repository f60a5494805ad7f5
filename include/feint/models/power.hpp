// feint/models/power.hpp - power and sample size of t-tests from the noncentral t distribution,
// as R's power.t.test(strict = TRUE) and pwr::pwr.t.test / pwr::pwr.t2n.test.
//
// With delta the true difference, sd the standard deviation(s), alpha' = alpha / m (Bonferroni for
// a family of m tests), T ~ noncentral t(nu, ncp) (boost::math::non_central_t):
//   one-sample / paired:    nu = n - 1,        ncp = sqrt(n) delta / sd   (paired: sd of
//   differences) two-sample (Student):   nu = n1 + n2 - 2,  ncp = delta / (sd sqrt(1/n1 + 1/n2))
//   two-sample (Welch):     ncp = delta / sqrt(sd1^2/n1 + sd2^2/n2) and nu the Welch-Satterthwaite
//                           df of the population variances (the approach of
//                           MESS::power_welch_t_test; an approximation: the Welch statistic is not
//                           exactly noncentral t)
//   two.sided: power = P(T > q) + P(T < -q), q = qt(1 - alpha'/2, nu)   (strict = TRUE: both tails)
//   greater:   power = P(T > qt(1 - alpha', nu));  less: P(T < -qt(1 - alpha', nu)).
// Solving for n (per group; n2 = ratio * n1), for delta, or for alpha-level power: a bracketed
// root (TOMS 748) to full double precision (R's uniroot stops at tol = eps^0.25 unless told).
#pragma once

#include <optional>
#include <string>

#include "feint/stats/htest.hpp"

namespace feint::models {

enum class TTestDesign { one_sample, two_sample, paired };

/// "one-sample"/"one.sample", "two-sample"/"two.sample", "paired"; throws UsageError otherwise.
TTestDesign parse_t_test_design(std::string_view text);
std::string_view to_string(TTestDesign design) noexcept;

/// What is given; exactly one of n, delta, power is empty (the one solved for).
struct TTestPowerSpec {
  TTestDesign design = TTestDesign::two_sample;
  std::optional<double> n;      ///< per group (two-sample: group 1); may be fractional
  std::optional<double> delta;  ///< true difference in means (metric units; > 0)
  std::optional<double> power;  ///< in (alpha', 1)
  double sd = 1.0;  ///< sd (two-sample: of group 1, or common); with sd = 1 delta is Cohen's d
  std::optional<double> sd2;  ///< Welch: sd of group 2 (default sd)
  double ratio = 1.0;         ///< two-sample: n2 = ratio * n1
  bool welch = false;         ///< two-sample: Welch's test instead of Student's
  double alpha = 0.05;        ///< family-wise level
  int tests = 1;              ///< m: the tests share alpha by Bonferroni (alpha / m each)
  stats::Alternative alternative = stats::Alternative::two_sided;
};

struct TTestPowerResult {
  TTestPowerSpec spec;  ///< with the solved quantity filled in
  double alpha_per_test = 0.05;
  double n1 = 0, n2 = 0;   ///< exact (fractional) sample sizes; n2 = 0 for one group
  double df = 0, ncp = 0;  ///< of the noncentral t at n1/n2
  // When n was solved: the whole-participant sizes and the power they give (>= the target).
  std::optional<double> n1_ceiling, n2_ceiling, power_at_ceiling;
  std::string method;  ///< e.g. "Two-sample t test power calculation (Student)"
  std::string note;
};

/// Power of the test in `spec` (which must have n and delta).
double t_test_power(const TTestPowerSpec& spec);

/// Solves for the missing one of n, delta, power. Throws UsageError for an impossible request
/// (none or several missing, power <= alpha', n < 2, a negative delta ...).
TTestPowerResult solve_t_test_power(const TTestPowerSpec& spec);

}  // namespace feint::models

// feint/stats/proportions.hpp - a yes/no answer per participant: proportions with their exact and
// Wilson intervals, and two conditions compared by Fisher's exact test and the chi-square test, as
// R's binom.test, prop.test and fisher.test (docs/yes-no.md has the formulas and worked examples).
#pragma once

#include <cstddef>

#include "feint/stats/htest.hpp"

namespace feint::stats {

/// x "yes" among n answers, with two intervals at `conf_level`:
///  * Clopper–Pearson (exact; R's `binom.test(x, n)$conf.int`): the alpha/2 quantile of
///    Beta(x, n - x + 1) and the 1 - alpha/2 quantile of Beta(x + 1, n - x), 0 at x = 0 and 1 at
///    x = n (Clopper & Pearson 1934);
///  * Wilson's score interval without continuity correction (R's
///    `prop.test(x, n, correct = FALSE)$conf.int`): (x + z^2/2 +- z sqrt(x (n - x)/n + z^2/4)) /
///    (n + z^2), z = qnorm(1 - alpha/2) (Wilson 1927).
/// n = 0 gives an empty proportion (`n == 0`; the other fields are NaN).
struct Proportion {
  std::size_t x = 0;
  std::size_t n = 0;
  double conf_level = 0.95;
  double estimate = 0;  ///< x / n
  double exact_low = 0, exact_high = 0;
  double wilson_low = 0, wilson_high = 0;
};

/// Throws UsageError when x > n or conf_level is not in (0, 1).
Proportion describe_proportion(std::size_t x, std::size_t n, double conf_level = 0.95);

/// The 2 x 2 table of a yes/no answer in two conditions: yes1 of n1 in condition 1, yes2 of n2 in
/// condition 2 (rows: conditions; columns: yes, no).
struct YesNoTable {
  std::size_t yes1 = 0, n1 = 0, yes2 = 0, n2 = 0;
};

/// Fisher's exact test of the 2 x 2 table, R's `fisher.test(matrix(c(yes1, yes2, n1 - yes1,
/// n2 - yes2), 2))` with `alternative` and `conf.int` from `options`.
///
/// With the margins fixed, yes1 follows Fisher's noncentral hypergeometric law with odds ratio
/// psi: P(X = k) proportional to C(n1, k) C(n2, m - k) psi^k over max(0, m - n2) <= k <= min(n1, m),
/// m = yes1 + yes2. The p-value is computed at psi = 1: two-sided as R, the sum of P(k) over every
/// k with P(k) <= P(yes1) (1 + 1e-7); one-sided the tail. `estimate` is the conditional maximum-
/// likelihood odds ratio (E[X; psi] = yes1; 0 or +inf at the ends of the support), and the interval
/// inverts the tails (P(X >= yes1; psi_L) = alpha/2, P(X <= yes1; psi_U) = alpha/2). The roots are
/// solved to full double precision; R's `uniroot` stops at tol = 1.2e-4, so R's estimate and
/// interval agree with these only to about 1e-4 relative (docs/yes-no.md).
/// statistic: none; mean1/mean2: the proportions of yes; n1, n2: the condition sizes.
/// Not computable when a condition has no answer.
TestResult fisher_exact(const YesNoTable& table, const TestOptions& options = {});

/// The chi-square test of two proportions, R's `prop.test(c(yes1, yes2), c(n1, n2), correct)`:
/// X^2 = sum over the four cells of (|O - E| - c)^2 / E with E from the pooled proportion and the
/// Yates correction c = min(0.5, |p1 - p2| / (1/n1 + 1/n2)) when `correct`, df 1; one-sided p from
/// sign(p1 - p2) sqrt(X^2) on the normal law. `estimate` = p1 - p2 with R's interval
/// p1 - p2 +- (z sqrt(p1 (1 - p1)/n1 + p2 (1 - p2)/n2) + c (1/n1 + 1/n2)), clipped to [-1, 1].
/// `note` carries R's warning when an expected count is below 5. Not computable when a condition
/// has no answer or every answer is the same (R: p = NaN).
TestResult prop_test(const YesNoTable& table, const TestOptions& options = {}, bool correct = true);

}  // namespace feint::stats

// feint/stats/rank_tests.hpp - Wilcoxon signed-rank and Mann–Whitney U, as R's wilcox.test().
//
// Both tests reproduce R 4.2's `wilcox.test` (statistic, p-value, which path ran, R's `method`
// string) to within 1e-10 relative; see docs/rank-tests.md for the formulas and the golden tests
// in tests/golden/rank/ for the evidence.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "feint/stats/htest.hpp"

namespace feint::stats {

/// One-sample Wilcoxon signed-rank test, R's `wilcox.test(x, mu = mu, correct = correct,
/// exact = exact)`.
///
/// NaN values of x are dropped (R drops NA/NaN; like R, +-Inf are kept and ranked). The differences
/// d = x - mu that are exactly 0 are dropped (R's "zeroes"); the rest are ranked by |d| with average
/// ranks for ties, and V = sum of the ranks of the positive d. With n the number of non-zero d:
///  * exact distribution of V (R's psignrank) when `exact` is true, or when it is not given and
///    n < 50 — but only if there are no ties and no zeros;
///  * otherwise the normal approximation: z = (V - n(n+1)/4 - c) / sigma with
///    sigma^2 = n(n+1)(2n+1)/24 - sum(t^3 - t)/48 over tie groups of size t, and continuity
///    correction c = sign(V - n(n+1)/4)/2 (two-sided), +1/2 (greater), -1/2 (less) when `correct`.
/// Two-sided p = min(1, 2 min(lower, upper)) as R. Tails are summed directly, never as 1 - p.
///
/// Result: statistic V ("V"), p_value, exact (which path ran), mu, n1 (observations of x used,
/// zeros included), mean1, sd1, median1, iqr1 (R's type-7 quantiles), and the matched-pairs
/// rank-biserial correlation r = (V - (S - V)) / S = 2V/S - 1 with S = n(n+1)/2 over the non-zero
/// differences (Kerby 2014). `note` carries R's warnings ("cannot compute exact p-value with
/// ties"/"... zeroes") and how many differences equal to mu were dropped. No confidence interval
/// (R's default conf.int = FALSE). Not computable (computed == false) when x has no non-NaN value
/// (R: error "not enough (non-missing) 'x' observations") or every difference is zero (R returns
/// V = 0 with p-value NaN).
TestResult wilcoxon_signed_rank(std::span<const double> x, double mu, const TestOptions& options = {},
                                bool correct = true, std::optional<bool> exact = std::nullopt);

/// Two-sample Wilcoxon rank-sum (Mann–Whitney U) test, R's `wilcox.test(x, y, correct = correct,
/// exact = exact)`.
///
/// NaN values are dropped from x and y. W = sum of the (average) ranks of x in the pooled sample
/// - n1(n1+1)/2 (= U of x, the number of pairs with x > y, ties counting 1/2).
///  * exact distribution of W (R's pwilcox) when `exact` is true, or when it is not given and both
///    n1 < 50 and n2 < 50 — but only if there are no ties;
///  * otherwise z = (W - n1 n2/2 - c) / sigma with
///    sigma^2 = n1 n2/12 * ((N + 1) - sum(t^3 - t)/(N(N - 1))), N = n1 + n2, and the continuity
///    correction c as in wilcoxon_signed_rank.
///
/// Result: statistic W ("W"), p_value, exact, mu = 0 (R's null location shift), n1/n2, means, sds,
/// medians, IQRs, and the rank-biserial correlation r = 2W/(n1 n2) - 1 (positive when x tends to
/// be larger; Glass 1965, Kerby 2014). Not computable when x or y has no non-NaN value (R: error)
/// or when every pooled value is tied (sigma = 0; R returns p-value NaN).
TestResult mann_whitney(std::span<const double> x, std::span<const double> y,
                        const TestOptions& options = {}, bool correct = true,
                        std::optional<bool> exact = std::nullopt);

/// Friedman rank sum test, R's `friedman.test(y)` for an n x k matrix y (participants x
/// conditions; R's `friedman.test(y ~ condition | participant)` on an unreplicated complete block
/// design is the same test).
///
/// `blocks[i]` holds block i's k values; a block with a NaN value is dropped (R's complete.cases).
/// Values are ranked within each block (average ranks for ties), R_j = the rank sum of condition j,
/// and X^2 = 12 sum_j (R_j - n(k+1)/2)^2 / (n k (k+1) - sum(t^3 - t)/(k - 1)) over the tie groups t
/// of every block, on the chi-square law with k - 1 df (upper tail).
///
/// Result: test "friedman", method "Friedman rank sum test", statistic ("chi-squared"), df, p_value,
/// n1 = complete blocks, and Kendall's W = X^2 / (n (k - 1)) (kendalls_w below; effectsize's
/// kendalls_w with its tie correction is the same number). `note` says how many blocks were
/// dropped. Not computable when fewer than 2 conditions, no complete block, or every block is
/// all tied (0/0; R returns NaN).
TestResult friedman_test(std::span<const std::vector<double>> blocks);

/// Kendall's coefficient of concordance W of a Friedman result, X^2 / (n (k - 1)) with n = n1 and
/// k - 1 = df; nullopt when the test was not computed.
std::optional<double> kendalls_w(const TestResult& friedman);

namespace detail {

/// Average ranks of `values` (R's `rank(ties.method = "average")`), and sum over tie groups of
/// t^3 - t (0 when there are no ties).
struct Ranks {
  std::vector<double> rank;
  double tie_sum = 0.0;  ///< sum(t^3 - t)
  bool ties = false;
};
Ranks average_ranks(std::span<const double> values);

/// P(V <= q) (lower_tail) or P(V > q) of the signed-rank statistic of n untied non-zero
/// differences, as R's psignrank(q, n, lower.tail). Each tail is summed directly from the exact
/// distribution (no 1 - p), so tiny tails keep full relative accuracy. n >= 1.
double psignrank(double q, std::size_t n, bool lower_tail);

/// P(W <= q) (lower_tail) or P(W > q) of the rank-sum statistic for samples of m and n untied
/// values, as R's pwilcox(q, m, n, lower.tail). m, n >= 1.
double pwilcox(double q, std::size_t m, std::size_t n, bool lower_tail);

/// R's quantile(x, p, type = 7) of an ascending, non-empty sample (local to the rank tests).
double quantile7(std::span<const double> sorted, double p);

}  // namespace detail

}  // namespace feint::stats

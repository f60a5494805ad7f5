// feint/stats/contingency.hpp - a yes/no answer across three or more conditions: the C x 2 table
// of conditions against yes/no compared by Fisher's exact test (R's fisher.test(table)) and by
// Pearson's chi-square test of independence (R's chisq.test(table, correct = FALSE)) with
// Cramér's V (R's effectsize::cramers_v), and, within participants, Cochran's Q test.
// docs/yes-no.md has the formulas and worked examples.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "feint/stats/htest.hpp"

namespace feint::stats {

/// One condition's row of the C x 2 table: `yes` of `n` answers.
struct YesCount {
  std::size_t yes = 0;
  std::size_t n = 0;
};

/// The most tables fisher_exact_conditions enumerates (see there).
inline constexpr std::uint64_t kFisherTableLimit = 20'000'000;

/// Fisher's exact test of the C x 2 table (C >= 2 rows with answers), R's `fisher.test(table)`.
/// Given the margins (the conditions' sizes n_i and the m answers yes of N), a table x_1..x_C has
/// the multivariate hypergeometric probability P(x) = prod C(n_i, x_i) / C(N, m). The p-value is
/// the sum of P over every table with P(x) <= P(observed), with R's FEXACT tolerance: log P(x) <=
/// log P(observed) + 3.45254e-7. The tables are enumerated exactly: every split of the yes answers
/// over all rows but the two largest, and for those two a hypergeometric tail sum (unimodal, so the
/// tables no more probable are a left and a right tail). When that is more than `max_tables`
/// splits the test is not computed and `note` says so (read the chi-square test instead).
/// statistic: none; n1 = N. Rows with n = 0 count for nothing (R gives the same p); fewer than two
/// rows with answers: not computable.
TestResult fisher_exact_conditions(std::span<const YesCount> table, std::uint64_t max_tables = kFisherTableLimit);

/// Pearson's chi-square test of independence of the C x 2 table, R's `chisq.test(table, correct =
/// FALSE)`: X^2 = sum over the 2C cells of (O - E)^2 / E, E = n_i * (column total) / N, df = C - 1
/// (rows with n = 0 left out, where R gives NaN). `note` carries R's warning when an expected count
/// is below 5. Not computable with fewer than two rows with answers or when every answer is the same.
/// statistic_name "chi-squared"; n1 = N. Cramér's V is in `estimate` with its interval (cramers_v
/// with the default options: bias-corrected, one-sided 95 %).
TestResult chisq_independence(std::span<const YesCount> table, double conf_level = 0.95);

/// Cramér's V of an r x c table from its chi-square statistic, as R's effectsize::cramers_v
/// (effectsize 0.8): phi^2 = X^2 / N, V = sqrt(phi^2 / (min(r, c) - 1)); bias-corrected (`adjust`,
/// effectsize's default; Bergsma 2013): phi^2_adj = max(0, phi^2 - (r - 1)(c - 1)/(N - 1)) over
/// min(r~, c~) - 1 with r~ = r - (r - 1)^2/(N - 1), c~ = c - (c - 1)^2/(N - 1). The interval maps
/// the noncentral chi-square interval of the ncp (pchisq(X^2, df, ncp) = 1 - a and = a; a bound is
/// 0 when X^2 is at or below the central quantile) through the same formula with phi^2 = ncp / N.
/// `alternative` greater (effectsize's default): a one-sided interval at conf_level with upper
/// bound 1; two_sided: both bounds, the upper capped at 1. effectsize finds the ncp with optim
/// (absolute tolerance 1e-9 on the summed probabilities), feint solves it to full precision.
struct CramersV {
  double estimate = 0;
  double low = 0, high = 1;
  double conf_level = 0.95;
  bool adjusted = true;
};
CramersV cramers_v(double chi_squared, std::size_t n, std::size_t rows, std::size_t columns,
                   bool adjust = true, double conf_level = 0.95,
                   Alternative alternative = Alternative::greater);

/// Cochran's Q test of C >= 3 related yes/no answers (each participant answered in each
/// condition): `answers[i][j]` is participant i's answer (1 yes, 0 no) in condition j, every row
/// of the same length C. With G_j the yes count of condition j, L_i participant i's yes count and
/// N = sum G_j, Q = (C - 1)(C sum G_j^2 - N^2) / (C N - sum L_i^2), referred to chi-square with
/// C - 1 df (Cochran 1950). Numerator and denominator are whole numbers, computed exactly. Q equals
/// R's friedman.test on the 0/1 matrix (its tie correction is Cochran's denominator).
/// statistic_name "Q"; n1 = participants; mean1 unused. Not computable with fewer than two
/// participants or when every participant gave one answer in every condition (denominator 0).
TestResult cochran_q(std::span<const std::vector<int>> answers);

}  // namespace feint::stats

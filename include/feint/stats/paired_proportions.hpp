// feint/stats/paired_proportions.hpp - a yes/no answer given by each participant in two conditions
// (within participants): McNemar's test, exact (R's binom.test on the discordant pairs, primary)
// and as R's mcnemar.test (chi-square with continuity correction). docs/yes-no.md has the formulas.
#pragma once

#include <cstddef>

#include "feint/stats/htest.hpp"

namespace feint::stats {

/// The 2 x 2 table of pairs: each participant's answer in condition A against their answer in B.
struct PairedYesNoTable {
  std::size_t yes_yes = 0;  ///< yes in A and in B
  std::size_t yes_no = 0;   ///< yes in A, no in B (discordant: b)
  std::size_t no_yes = 0;   ///< no in A, yes in B (discordant: c)
  std::size_t no_no = 0;    ///< no in A and in B
  std::size_t pairs() const noexcept { return yes_yes + yes_no + no_yes + no_no; }
};

/// The exact McNemar test: under H0 (the same proportion of yes in A and B) b | b + c follows
/// Binomial(b + c, 1/2); R's `binom.test(b, b + c, 0.5, alternative)`. Two-sided p = min(1,
/// 2 min(P(X <= b), P(X >= b))) (R's rule at p = 1/2). `estimate` is the conditional odds ratio
/// b / c (> 1: yes more often in A) with the interval p/(1 - p) of binom.test's Clopper–Pearson
/// interval p of b/(b + c); statistic b ("b"); mean1, mean2: the proportions of yes in A and in B
/// over the pairs; n1 = n2 = pairs. Not computable when there is no discordant pair.
TestResult mcnemar_exact(const PairedYesNoTable& table, const TestOptions& options = {});

/// R's `mcnemar.test(table, correct)`: X^2 = (|b - c| - 1)^2 / (b + c) (without `correct`, or
/// when b = c as R: (b - c)^2 / (b + c)), chi-square with 1 df; two-sided only (R has no
/// alternative).
/// `estimate` = p_A - p_B; mean1, mean2, n1, n2 as above. Not computable when b + c = 0 (R: NaN).
TestResult mcnemar_test(const PairedYesNoTable& table, bool correct = true);

}  // namespace feint::stats

// feint/stats/anova.hpp - one-way ANOVA (classic and Welch) and Kruskal–Wallis.
#pragma once

#include <span>
#include <vector>

#include "feint/stats/htest.hpp"

namespace feint::stats {

/// The classic ANOVA table, anova(lm(y ~ g)).
struct AnovaTable {
  double df_between = 0, ss_between = 0, ms_between = 0;
  double df_within = 0, ss_within = 0, ms_within = 0;
  double f_statistic = 0, p_value = 1, r_squared = 0, residual_sd = 0;
};

/// One sample per group; NaN values dropped, empty groups left out (unused factor levels, as lm()).
/// Sums of squares in extended precision on values shifted by the first one (corrected two-pass
/// within groups, SS_between = sum n_j (mean_j - mean)^2); on parsed doubles the result is exact to
/// what the doubles hold. For NIST SmLs07-09-like data given as text, one_way_anova_table_decimal()
/// (exact_decimal.hpp) reads the decimals exactly: LRE >= 14.5 on every NIST ANOVA quantity.
/// Throws InvalidData when fewer than two non-empty groups or no residual df.
AnovaTable one_way_anova_table(std::span<const std::vector<double>> groups);

/// The same as a TestResult: test "anova", statistic F, df (between), df2 (within), p, r_squared;
/// n1 = all observations. Not computable (with the reason in note) when the table would throw, or
/// the residual sum of squares is 0 (constant within groups), or values are infinite.
TestResult one_way_anova(std::span<const std::vector<double>> groups);

/// oneway.test(y ~ g) (var.equal = FALSE): Welch's F (Welch 1951), df = (k - 1, 1 / (3 tmp)).
/// Not computable when a group has fewer than two values (R: "not enough observations") or zero
/// variance.
TestResult welch_anova(std::span<const std::vector<double>> groups);

/// kruskal.test(y ~ g), tie-corrected chi-squared.
TestResult kruskal_wallis(std::span<const std::vector<double>> groups);

}  // namespace feint::stats

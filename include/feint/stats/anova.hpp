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

/// One sample per group. Accurate for data with many constant leading digits (NIST SmLs07-09:
/// LRE >= 9). Throws InvalidData when fewer than two groups or no residual df.
AnovaTable one_way_anova_table(std::span<const std::vector<double>> groups);

/// The same as a TestResult (test "anova", statistic F, df, df2).
TestResult one_way_anova(std::span<const std::vector<double>> groups);

/// oneway.test(y ~ g) (var.equal = FALSE): Welch's F.
TestResult welch_anova(std::span<const std::vector<double>> groups);

/// kruskal.test(y ~ g), tie-corrected chi-squared.
TestResult kruskal_wallis(std::span<const std::vector<double>> groups);

}  // namespace feint::stats

// feint/tables/tidy.hpp - one tidy row per test: what every report writer renders.
//
// The CSV/JSON columns are fixed: scripts rely on their names and order.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "feint/stats/htest.hpp"

namespace feint::tables {

/// A test in its context: which metric (or Likert item), which iteration, which groups.
struct TidyRow {
  std::string metric;              ///< metric column or Likert item / composite name
  std::optional<int> iteration;    ///< empty for Likert rows
  std::string group1, group2;      ///< the condition(s) tested
  stats::TestResult result;
  std::string label;               ///< inference label: M>R, M<R, M≈R, A>B, ..., "inconclusive"
  std::optional<double> cronbach_alpha;  ///< composite Likert scales only
  std::string apa;                 ///< APA string, filled when asked for (--apa)
};

/// Columns of the tidy CSV/JSON of `feint table`, in order.
/// cohen_d_low ... hedges_g_high: the effect sizes' intervals at the test's level (noncentral t);
/// bf10, bf01: the JZS Bayes factor (Cauchy prior r = 0.707 unless set; feint/stats/bayes_factor.hpp).
inline constexpr std::array<std::string_view, 31> kTableColumns = {
    "metric", "iteration", "test", "method", "alternative", "mu", "group1", "group2", "n1", "n2",
    "mean1", "mean2", "sd1", "sd2", "estimate", "conf_low", "conf_high", "statistic", "df",
    "p_value", "p_adjusted", "cohen_d", "hedges_g", "cohen_d_low", "cohen_d_high",
    "hedges_g_low", "hedges_g_high", "bf10", "bf01", "label", "note"};

/// Extra columns of `feint likert` (appended after kTableColumns).
inline constexpr std::array<std::string_view, 9> kLikertExtraColumns = {
    "median1", "median2", "iqr1", "iqr2", "rank_biserial", "rank_biserial_low",
    "rank_biserial_high", "exact", "cronbach_alpha"};

}  // namespace feint::tables

// feint/tables/describe.hpp - descriptive statistics of one numeric column, optionally by group, as
// a tidy table (`feint describe`).
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "feint/io/scores.hpp"
#include "feint/tables/writers.hpp"
#include "feint/stats/descriptive.hpp"

namespace feint::tables {

/// Columns of `feint describe`, in order.
inline constexpr std::array<std::string_view, 14> kDescribeColumns = {
    "variable", "group", "n",      "mean", "sd",       "se",        "min",
    "q1",       "median", "q3",    "max",  "conf_low", "conf_high", "autocorr_lag1"};

struct DescribeTable {
  std::string source;
  std::string variable;  ///< the column described
  std::string by;        ///< grouping column, "" for none
  double conf_level = 0.95;
  std::vector<std::string> groups;
  std::vector<stats::Description> descriptions;  ///< one per group
  std::vector<std::size_t> missing;              ///< empty cells per group
};

/// stats::describe_decimal (or, for text it cannot read exactly, stats::describe) per group of
/// `column` (n, mean, sd (n - 1), se, min, quartiles as R's
/// quantile(type = 7), max, t-based CI of the mean at `conf_level`, lag-1 autocorrelation in file
/// order).
DescribeTable build_describe(const io::NumericColumn& column, double conf_level = 0.95);

/// Tidy records (kDescribeColumns), numbers in full (round-trip) precision.
std::vector<Record> describe_records(const DescribeTable& table);

/// Significant digits of the statistics in describe's text, Markdown and LaTeX output.
inline constexpr int kPrintDigits = 4;

/// `value` rounded to `digits` significant digits (R's signif()), written as the shortest text of
/// the rounded double: 0.333333 -> "0.3333", 0.3 -> "0.3", 12345.6 -> "12350", 1.23456e-7 ->
/// "1.235e-07".
std::string format_for_print(double value, int digits = kPrintDigits);

/// text/markdown/latex: the tidy columns as an aligned table with a note (missing values, values
/// that could not be computed, the CI level), statistics rounded to kPrintDigits significant
/// digits; csv/json: the tidy records in full precision.
std::string render_describe(const DescribeTable& table, OutputFormat format);

}  // namespace feint::tables

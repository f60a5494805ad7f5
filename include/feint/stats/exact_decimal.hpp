// feint/stats/exact_decimal.hpp - statistics of numbers given as decimal text, read exactly.
//
// A decimal such as 10000000.2 has no exact double: parsing it first already costs the last digits
// of a sample whose values share many leading digits (NIST StRD NumAcc4: the sd of the parsed
// doubles is off at LRE 8.3 however carefully it is computed; ANOVA SmLs09: F off at LRE 4.2).
// These functions read the text exactly instead: every value becomes an integer count of the
// smallest decimal unit present (10^-s), the first value is subtracted exactly (128-bit integers),
// and the small shifted integers are summed in extended precision (long double) by the corrected
// two-pass algorithm. Only the final results are rounded to double.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "feint/stats/anova.hpp"
#include "feint/stats/descriptive.hpp"

namespace feint::stats {

/// summarize() of the numbers written in `text` ("-12.5", "1e-3", "+7"), read exactly.
/// Throws InvalidData for text that is not a plain decimal number or has more than 36 digits.
Summary summarize_decimal(std::span<const std::string> text);

/// autocorr_lag1() of decimal text, read exactly.
std::optional<double> autocorr_lag1_decimal(std::span<const std::string> text);

/// describe() of decimal text: mean, sd, se, CI and lag-1 autocorrelation from the exact reading;
/// min, quartiles and max from the values rounded once to double. No missing values: drop empty
/// fields before calling.
Description describe_decimal(std::span<const std::string> text, double conf_level = 0.95);

/// one_way_anova_table() of decimal text (one vector per group), read exactly.
AnovaTable one_way_anova_table_decimal(std::span<const std::vector<std::string>> groups);

}  // namespace feint::stats

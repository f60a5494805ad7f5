// src/stats/shifted.hpp - the accurate cores shared by the double and the exact-decimal APIs.
//
// A sample is given as x_i = shift + a_i / scale, with a_i exact in long double (small integers
// for decimal text, x_i - x_0 for doubles) and scale = 10^s (1 for doubles). The cores work on a_i
// in extended precision and apply shift and scale only to the final results.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "feint/stats/anova.hpp"
#include "feint/stats/descriptive.hpp"

namespace feint::stats::detail {

struct Shifted {
  std::vector<long double> a;
  long double shift = 0;
  long double scale = 1;
  /// The sum of the x_i * scale, exact or nearly (exact integers for decimal text, Shewchuk's
  /// exact sum for doubles), when known: the mean is then total / n / scale, with no cancellation
  /// error when values of opposite sign cancel ({1e9, -1e9, 1} has mean 1/3 to the last bit).
  std::optional<long double> total;
};

Summary summary_of(const Shifted& s);
std::optional<double> autocorr_of(const Shifted& s);
/// Groups share shift and scale (the ANOVA sums of squares do not depend on the shift).
AnovaTable anova_of(const std::vector<std::vector<long double>>& groups, long double scale);

/// describe() from its parts: the values (any order), their accurate summary, the autocorrelation.
Description describe_from(std::vector<double> values, const Summary& s,
                          const std::function<std::optional<double>()>& autocorr,
                          double conf_level);

/// x - x[0] in long double (exact for doubles within a factor 2^11 of each other).
Shifted shift_doubles(const std::vector<double>& x);

}  // namespace feint::stats::detail

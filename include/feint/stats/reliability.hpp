// feint/stats/reliability.hpp - internal consistency of multi-item scales.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace feint::stats {

struct CronbachAlpha {
  std::optional<double> raw_alpha;               ///< psych::alpha()$total$raw_alpha
  std::vector<std::optional<double>> if_dropped;  ///< raw alpha with item j dropped (psych's alpha.drop)
  std::size_t n = 0;                              ///< respondents used (complete cases)
  std::string note;                               ///< why not computable (k < 2, zero variance, n < 2)
};

/// Cronbach's alpha from item columns of equal length (respondents in the same order, complete
/// cases only): alpha = k/(k-1) * (1 - sum var(item) / var(total)).
CronbachAlpha cronbach_alpha(std::span<const std::vector<double>> items);

}  // namespace feint::stats

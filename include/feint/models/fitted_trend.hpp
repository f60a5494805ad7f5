// feint/models/fitted_trend.hpp - a mixed model's fitted trend with its confidence band, per group
// and time value: the line the model figure draws over the per-iteration means.
#pragma once

#include <string>
#include <vector>

#include "feint/models/mixed_model.hpp"

namespace feint::models {

/// The fitted mean of one cell (group level, time value) and its interval.
struct TrendPoint {
  double time = 0;
  double fit = 0, low = 0, high = 0;
};

struct FittedTrend {
  std::string group;               ///< the group level (condition)
  std::vector<TrendPoint> points;  ///< ascending time
};

/// Per group level and time value of the fit: the fixed-effects prediction x'beta of the cell
/// (x = fit.cell_row) and its interval from contrast(fit, x, conf_level), i.e. with Satterthwaite's
/// df, as emmeans::emmeans(m, ~ group * time) with lmer.df = "satterthwaite" (time as a factor) or
/// at each observed time (linear trend). A cell whose interval cannot be computed keeps its fit
/// and has NaN bounds.
std::vector<FittedTrend> fitted_trend(const MixedModelFit& fit, double conf_level = 0.95);

}  // namespace feint::models

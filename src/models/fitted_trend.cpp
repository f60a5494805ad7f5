// A mixed model's fitted trend with its band (see fitted_trend.hpp).
#include "feint/models/fitted_trend.hpp"

#include <limits>

namespace feint::models {

std::vector<FittedTrend> fitted_trend(const MixedModelFit& fit, double conf_level) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::vector<FittedTrend> out;
  for (std::size_t g = 0; g < fit.group_levels.size(); ++g) {
    FittedTrend t;
    t.group = fit.group_levels[g];
    for (double time : fit.time_levels) {
      const Eigen::VectorXd x = fit.cell_row(g, time);
      const Contrast c = contrast(fit, x, conf_level);
      TrendPoint p;
      p.time = time;
      p.fit = x.dot(fit.beta);
      p.low = c.test.conf_low.value_or(kNaN);
      p.high = c.test.conf_high.value_or(kNaN);
      t.points.push_back(p);
    }
    out.push_back(std::move(t));
  }
  return out;
}

}  // namespace feint::models

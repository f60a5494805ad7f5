// exposure_counts(): see feint/models/exposure.hpp.
#include "feint/models/exposure.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace feint::models {

std::vector<double> exposure_counts(std::span<const std::string> participant,
                                    std::span<const double> iteration,
                                    std::span<const std::string> strategy) {
  const std::size_t n = participant.size();
  if (iteration.size() != n || strategy.size() != n)
    throw std::invalid_argument("exposure_counts: columns of different lengths");
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (participant[a] != participant[b]) return participant[a] < participant[b];
    return iteration[a] < iteration[b];
  });
  std::vector<double> out(n, 0.0);
  std::map<std::pair<std::string, std::string>, double> seen;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k];
    if (k > 0 && participant[order[k - 1]] == participant[i] &&
        iteration[order[k - 1]] == iteration[i])
      throw std::invalid_argument("exposure_counts: participant " + participant[i] +
                                  " has two trials at one iteration");
    double& count = seen[{participant[i], strategy[i]}];
    out[i] = count;
    count += 1;
  }
  return out;
}

}  // namespace feint::models

// ------------------------------------------------------------------------------------------------
// exposure_slopes_by_condition(): see feint/models/exposure.hpp.

#include <cmath>
#include <set>

#include <boost/math/distributions/students_t.hpp>
#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/models/mixed_model.hpp"

namespace feint::models {

ExposureByCondition exposure_slopes_by_condition(std::span<const std::string> participant,
                                                 std::span<const std::string> condition,
                                                 std::span<const std::string> strategy,
                                                 std::span<const double> exposure,
                                                 std::span<const double> y,
                                                 std::vector<std::string> conditions,
                                                 double conf_level) {
  const std::size_t n = participant.size();
  if (condition.size() != n || strategy.size() != n || exposure.size() != n || y.size() != n)
    throw std::invalid_argument("exposure_slopes_by_condition: columns of different lengths");
  if (conditions.empty()) {
    const std::set<std::string> s(condition.begin(), condition.end());
    conditions.assign(s.begin(), s.end());
  }
  const std::set<std::string> strategy_set(strategy.begin(), strategy.end());
  const std::vector<std::string> strategies(strategy_set.begin(), strategy_set.end());
  ExposureByCondition out;
  for (const auto& cond : conditions) {
    LongData d;
    for (std::size_t i = 0; i < n; ++i) {
      if (condition[i] != cond || !std::isfinite(y[i])) continue;
      d.participant.push_back(participant[i]);
      d.group.push_back(strategy[i]);
      d.time.push_back(exposure[i]);
      d.y.push_back(y[i]);
    }
    ModelSpec spec;
    spec.group = "strategy";
    spec.time = "exposure";
    spec.time_scale = TimeScale::linear;
    spec.group_levels = strategies;
    std::optional<MixedModelFit> fit;
    std::string why;
    try {
      fit = fit_mixed_model(d, spec, false);
    } catch (const std::exception& e) {
      why = e.what();
    }
    for (std::size_t s = 0; s < strategies.size(); ++s) {
      ExposureSlope sl;
      sl.strategy = strategies[s];
      sl.condition = cond;
      if (fit) {
        const Eigen::VectorXd L = fit->cell_row(s, 1.0) - fit->cell_row(s, 0.0);
        Contrast c = contrast(*fit, L, conf_level);
        sl.test = std::move(c.test);
        sl.std_error = c.std_error;
      } else {
        sl.test = stats::TestResult::not_computable(
            "lmm_contrast", "exposure slope (lmer)",
            fmt::format("the model of condition '{}' cannot be fitted: {}", cond, why));
      }
      out.slopes.push_back(std::move(sl));
    }
  }
  if (conditions.size() < 2) return out;
  for (std::size_t s = 0; s < strategies.size(); ++s) {
    const ExposureSlope& a = out.slopes[s];
    const ExposureSlope& b = out.slopes[strategies.size() + s];
    ExposureSlope dif;
    dif.strategy = strategies[s];
    dif.condition = conditions[0] + "-" + conditions[1];
    const std::string method = "difference of exposure slopes between conditions (Welch–Satterthwaite)";
    if (!a.test.computed || !b.test.computed || !a.test.estimate || !b.test.estimate || !a.test.df ||
        !b.test.df) {
      dif.test = stats::TestResult::not_computable(
          "slope_difference", method, !a.test.computed ? a.test.note : b.test.note);
      out.differences.push_back(std::move(dif));
      continue;
    }
    const double va = a.std_error * a.std_error, vb = b.std_error * b.std_error;
    const double se = std::sqrt(va + vb);
    const double df = (va + vb) * (va + vb) / (va * va / *a.test.df + vb * vb / *b.test.df);
    const double est = *a.test.estimate - *b.test.estimate;
    const double t = est / se;
    const boost::math::students_t dist(df);
    const double q = boost::math::quantile(boost::math::complement(dist, (1 - conf_level) / 2));
    stats::TestResult& r = dif.test;
    r.test = "slope_difference";
    r.method = method;
    r.conf_level = conf_level;
    r.mu = 0.0;
    r.estimate = est;
    r.statistic = t;
    r.statistic_name = "t";
    r.df = df;
    r.p_value = std::min(1.0, 2 * boost::math::cdf(boost::math::complement(dist, std::fabs(t))));
    r.conf_low = est - q * se;
    r.conf_high = est + q * se;
    dif.std_error = se;
    out.differences.push_back(std::move(dif));
  }
  return out;
}

}  // namespace feint::models

// The condition x exposure figure's data (see exposure_trend.hpp).
#include "feint/metrics/exposure_trend.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>

#include "feint/error.hpp"

namespace feint::metrics {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double t_quantile(double df, double conf_level) {
  return boost::math::quantile(
      boost::math::complement(boost::math::students_t(df), (1 - conf_level) / 2));
}

struct Obs {
  std::string participant;
  double x = 0, y = 0;
};

// Least squares with the participant-clustered (CR1) covariance; see ExposureFit.
ExposureFit fit_line(const std::vector<Obs>& obs, const std::vector<double>& at,
                     double conf_level) {
  ExposureFit f;
  f.n = obs.size();
  std::map<std::string, std::pair<double, double>> score;  // per participant: sum e, sum x e
  for (const auto& o : obs) score.try_emplace(o.participant, 0.0, 0.0);
  f.participants = score.size();
  if (obs.size() < 3 || score.size() < 2) return f;
  const double n = static_cast<double>(obs.size());
  double sx = 0, sy = 0;
  for (const auto& o : obs) {
    sx += o.x;
    sy += o.y;
  }
  const double xbar = sx / n, ybar = sy / n;
  double sxx = 0, sxy = 0;
  for (const auto& o : obs) {
    sxx += (o.x - xbar) * (o.x - xbar);
    sxy += (o.x - xbar) * (o.y - ybar);
  }
  if (!(sxx > 0)) return f;
  f.fitted = true;
  f.slope = sxy / sxx;
  f.intercept = ybar - f.slope * xbar;
  for (const auto& o : obs) {
    const double e = o.y - f.intercept - f.slope * o.x;
    auto& [se, sxe] = score[o.participant];
    se += e;
    sxe += o.x * e;
  }
  // bread = (X'X)^-1 with X = [1, x]; meat = sum over participants of u u', u = X_g' e_g.
  const double sxx_raw = sxx + n * xbar * xbar;  // sum x^2
  const double det = n * sxx_raw - sx * sx;
  const double b00 = sxx_raw / det, b01 = -sx / det, b11 = n / det;
  double m00 = 0, m01 = 0, m11 = 0;
  for (const auto& [who, u] : score) {
    m00 += u.first * u.first;
    m01 += u.first * u.second;
    m11 += u.second * u.second;
  }
  const double g = static_cast<double>(score.size());
  const double c = g / (g - 1) * (n - 1) / (n - 2);
  // V = c B M B (2 x 2, symmetric).
  const double t00 = b00 * m00 + b01 * m01, t01 = b00 * m01 + b01 * m11;
  const double t10 = b01 * m00 + b11 * m01, t11 = b01 * m01 + b11 * m11;
  const double v00 = c * (t00 * b00 + t01 * b01), v01 = c * (t00 * b01 + t01 * b11);
  const double v11 = c * (t10 * b01 + t11 * b11);
  const double q = t_quantile(g - 1, conf_level);
  f.slope_low = f.slope - q * std::sqrt(v11);
  f.slope_high = f.slope + q * std::sqrt(v11);
  for (double x : at) {
    const double yhat = f.intercept + f.slope * x;
    const double half = q * std::sqrt(std::max(0.0, v00 + 2 * x * v01 + x * x * v11));
    f.exposure.push_back(x);
    f.fit.push_back(yhat);
    f.low.push_back(yhat - half);
    f.high.push_back(yhat + half);
  }
  return f;
}

// participant, condition, iteration -> strategy, exposure
using TrialKey = std::tuple<std::string, std::string, long long>;
using Exposures = std::map<TrialKey, std::pair<std::string, long long>>;
using Cell = std::vector<std::pair<std::string, double>>;  // (participant, value)
// strategy -> condition -> exposure -> cell
using CellsByCondition = std::map<std::string, std::map<long long, Cell>>;
using Cells = std::map<std::string, CellsByCondition>;

// Exposure from the labels: per participant, in iteration order, count each strategy.
Exposures exposure_by_trial(const std::vector<TrialLabel>& labels) {
  std::vector<const TrialLabel*> sorted;
  for (const auto& t : labels) sorted.push_back(&t);
  std::stable_sort(sorted.begin(), sorted.end(), [](const TrialLabel* a, const TrialLabel* b) {
    return std::tie(a->participant, a->condition, a->iteration) <
           std::tie(b->participant, b->condition, b->iteration);
  });
  Exposures exposure;
  std::map<std::tuple<std::string, std::string, std::string>, long long> seen;
  for (const TrialLabel* t : sorted) {
    const std::string s = t->strategy.empty() ? "(none)" : t->strategy;
    const long long e = ++seen[{t->participant, t->condition, s}];
    exposure[{t->participant, t->condition, t->iteration}] = {s, e};
  }
  return exposure;
}

// Metric m's finite values per strategy, condition and exposure; counts the scored trials that
// have no label in `unmatched`. A missing value still creates its strategy and cell, so a
// strategy whose values are all missing keeps its (empty) series.
Cells values_by_cell(const io::ScoresTable& scores, int m, const Exposures& exposure,
                     std::size_t& unmatched) {
  Cells values;
  for (const auto& r : scores.records) {
    const auto e = exposure.find({r.participant, r.condition, r.iteration});
    if (e == exposure.end()) {
      ++unmatched;
      continue;
    }
    const auto& v = r.values[static_cast<std::size_t>(m)];
    auto& per_exposure = values[e->second.first][r.condition];
    auto& cell = per_exposure[e->second.second];
    if (v && std::isfinite(*v)) cell.emplace_back(r.participant, *v);
  }
  return values;
}

// A cell's mean with its t interval (NaN bounds below two values).
ExposurePoint mean_point(long long e, const Cell& cell, double conf_level) {
  ExposurePoint p;
  p.exposure = e;
  p.n = cell.size();
  double sum = 0;
  for (const auto& [who, y] : cell) sum += y;
  p.mean = sum / static_cast<double>(cell.size());
  p.conf_low = p.conf_high = kNaN;
  if (cell.size() >= 2) {
    double ss = 0;
    for (const auto& [who, y] : cell) ss += (y - p.mean) * (y - p.mean);
    const double n = static_cast<double>(cell.size());
    const double half = t_quantile(n - 1, conf_level) * std::sqrt(ss / (n - 1) / n);
    p.conf_low = p.mean - half;
    p.conf_high = p.mean + half;
  }
  return p;
}

// One condition's line for a strategy: a point per non-empty exposure, and the line fitted through
// the values themselves (clustered by participant, see fit_line), not through the means.
ExposureSeries condition_series(const CellsByCondition& per_condition, const std::string& c,
                                double conf_level) {
  ExposureSeries series;
  series.condition = c;
  std::vector<Obs> obs;
  std::vector<double> at;
  const auto pc = per_condition.find(c);
  if (pc != per_condition.end()) {
    for (const auto& [e, cell] : pc->second) {
      if (cell.empty()) continue;
      series.points.push_back(mean_point(e, cell, conf_level));
      at.push_back(static_cast<double>(e));
      for (const auto& [who, y] : cell) obs.push_back({who, static_cast<double>(e), y});
    }
  }
  series.fit = fit_line(obs, at, conf_level);
  return series;
}

}  // namespace

ExposureTrend exposure_trend(const io::ScoresTable& scores, const std::vector<TrialLabel>& labels,
                             const std::string& metric, double conf_level) {
  const int m = scores.metric_index(metric);
  if (m < 0) {
    throw InvalidData(fmt::format("exposure figure: metric '{}' is not in the scores", metric));
  }
  ExposureTrend out;
  out.metric = metric;
  out.conf_level = conf_level;
  out.conditions = scores.conditions();

  const Exposures exposure = exposure_by_trial(labels);
  const Cells values = values_by_cell(scores, m, exposure, out.unmatched);
  for (const auto& [strategy, per_condition] : values) {
    ExposureStrategy es;
    es.strategy = strategy;
    for (const auto& c : out.conditions) {
      es.series.push_back(condition_series(per_condition, c, conf_level));
    }
    out.strategies.push_back(std::move(es));
  }
  return out;
}

}  // namespace feint::metrics

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

ExposureFit fit_line(const std::vector<std::pair<double, double>>& xy,
                     const std::vector<double>& at, double conf_level) {
  ExposureFit f;
  f.n = xy.size();
  if (xy.size() < 3) return f;
  const double n = static_cast<double>(xy.size());
  double sx = 0, sy = 0;
  for (const auto& [x, y] : xy) {
    sx += x;
    sy += y;
  }
  const double xbar = sx / n, ybar = sy / n;
  double sxx = 0, sxy = 0;
  for (const auto& [x, y] : xy) {
    sxx += (x - xbar) * (x - xbar);
    sxy += (x - xbar) * (y - ybar);
  }
  if (!(sxx > 0)) return f;
  f.fitted = true;
  f.slope = sxy / sxx;
  f.intercept = ybar - f.slope * xbar;
  double sse = 0;
  for (const auto& [x, y] : xy) {
    const double r = y - f.intercept - f.slope * x;
    sse += r * r;
  }
  const double s = std::sqrt(sse / (n - 2));
  const double q = t_quantile(n - 2, conf_level);
  f.slope_low = f.slope - q * s / std::sqrt(sxx);
  f.slope_high = f.slope + q * s / std::sqrt(sxx);
  for (double x : at) {
    const double yhat = f.intercept + f.slope * x;
    const double half = q * s * std::sqrt(1 / n + (x - xbar) * (x - xbar) / sxx);
    f.exposure.push_back(x);
    f.fit.push_back(yhat);
    f.low.push_back(yhat - half);
    f.high.push_back(yhat + half);
  }
  return f;
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

  // Exposure from the labels: per participant, in iteration order, count each strategy.
  using TrialKey = std::tuple<std::string, std::string, long long>;
  std::vector<const TrialLabel*> sorted;
  for (const auto& t : labels) sorted.push_back(&t);
  std::stable_sort(sorted.begin(), sorted.end(), [](const TrialLabel* a, const TrialLabel* b) {
    return std::tie(a->participant, a->condition, a->iteration) <
           std::tie(b->participant, b->condition, b->iteration);
  });
  std::map<TrialKey, std::pair<std::string, long long>> exposure;  // strategy, exposure
  std::map<std::tuple<std::string, std::string, std::string>, long long> seen;
  for (const TrialLabel* t : sorted) {
    const std::string s = t->strategy.empty() ? "(none)" : t->strategy;
    const long long e = ++seen[{t->participant, t->condition, s}];
    exposure[{t->participant, t->condition, t->iteration}] = {s, e};
  }

  // Values per strategy, condition and exposure.
  std::map<std::string, std::map<std::string, std::map<long long, std::vector<double>>>> values;
  for (const auto& r : scores.records) {
    const auto e = exposure.find({r.participant, r.condition, r.iteration});
    if (e == exposure.end()) {
      ++out.unmatched;
      continue;
    }
    const auto& v = r.values[static_cast<std::size_t>(m)];
    auto& per_exposure = values[e->second.first][r.condition];
    auto& cell = per_exposure[e->second.second];
    if (v && std::isfinite(*v)) cell.push_back(*v);
  }
  for (const auto& [strategy, per_condition] : values) {
    ExposureStrategy es;
    es.strategy = strategy;
    for (const auto& c : out.conditions) {
      ExposureSeries series;
      series.condition = c;
      std::vector<std::pair<double, double>> xy;
      std::vector<double> at;
      const auto pc = per_condition.find(c);
      if (pc != per_condition.end()) {
        for (const auto& [e, ys] : pc->second) {
          if (ys.empty()) continue;
          ExposurePoint p;
          p.exposure = e;
          p.n = ys.size();
          double sum = 0;
          for (double y : ys) sum += y;
          p.mean = sum / static_cast<double>(ys.size());
          p.conf_low = p.conf_high = kNaN;
          if (ys.size() >= 2) {
            double ss = 0;
            for (double y : ys) ss += (y - p.mean) * (y - p.mean);
            const double n = static_cast<double>(ys.size());
            const double half = t_quantile(n - 1, conf_level) * std::sqrt(ss / (n - 1) / n);
            p.conf_low = p.mean - half;
            p.conf_high = p.mean + half;
          }
          series.points.push_back(p);
          at.push_back(static_cast<double>(e));
          for (double y : ys) xy.emplace_back(static_cast<double>(e), y);
        }
      }
      series.fit = fit_line(xy, at, conf_level);
      es.series.push_back(std::move(series));
    }
    out.strategies.push_back(std::move(es));
  }
  return out;
}

}  // namespace feint::metrics

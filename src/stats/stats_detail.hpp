// src/stats/stats_detail.hpp - helpers shared by the stats sources (not installed).
#pragma once

#include <cmath>
#include <limits>

#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/stats/htest.hpp"

namespace feint::stats::detail {

inline void check_conf_level(double conf_level) {
  if (!(conf_level > 0.0 && conf_level < 1.0))
    throw UsageError(fmt::format("confidence level {} is outside (0, 1)", conf_level));
}

/// p-value of a t statistic: upper tails through complements, so p = 1e-200 is not rounded to 0.
inline double t_p_value(double t, double df, Alternative alternative) {
  const boost::math::students_t dist(df);
  switch (alternative) {
    case Alternative::greater: return boost::math::cdf(boost::math::complement(dist, t));
    case Alternative::less: return boost::math::cdf(dist, t);
    case Alternative::two_sided: break;
  }
  return std::min(1.0, 2.0 * boost::math::cdf(boost::math::complement(dist, std::fabs(t))));
}

/// The upper `a` quantile of t(df): qt(1 - a, df), from the complement for accuracy near 1.
inline double t_upper_quantile(double a, double df) {
  const boost::math::students_t dist(df);
  return boost::math::quantile(boost::math::complement(dist, a));
}

/// R's t.test interval: mu + (t -/+ q) * stderr (the same arithmetic, so it agrees to the last bits).
struct Interval {
  double low, high;
};
inline Interval t_interval(double t, double df, double stderr_, double mu, double conf_level,
                           Alternative alternative) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double alpha = 1.0 - conf_level;
  switch (alternative) {
    case Alternative::less: {
      const double q = t_upper_quantile(alpha, df);
      return {-inf, mu + (t + q) * stderr_};
    }
    case Alternative::greater: {
      const double q = t_upper_quantile(alpha, df);
      return {mu + (t - q) * stderr_, inf};
    }
    case Alternative::two_sided: break;
  }
  const double q = t_upper_quantile(alpha / 2.0, df);
  return {mu + (t - q) * stderr_, mu + (t + q) * stderr_};
}

/// Hedges' exact small-sample correction J(df) = Gamma(df/2) / (sqrt(df/2) Gamma((df-1)/2))
/// (Hedges 1981). Boost's tgamma_ratio stays accurate (and finite) for large df, where the
/// difference of two lgamma values would lose digits. Undefined (NaN) for df <= 1.
inline double hedges_j(double df) {
  if (!(df > 1.0)) return std::numeric_limits<double>::quiet_NaN();
  return boost::math::tgamma_ratio(df / 2.0, (df - 1.0) / 2.0) / std::sqrt(df / 2.0);
}

/// p-value of an F statistic (upper tail, complement).
inline double f_p_value(double f, double df1, double df2) {
  const boost::math::fisher_f dist(df1, df2);
  return boost::math::cdf(boost::math::complement(dist, f));
}

}  // namespace feint::stats::detail

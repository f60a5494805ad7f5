// feint/stats/descriptive.hpp - accurate, mergeable descriptive statistics.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <string>

namespace feint::stats {

/// Count, mean and sum of squared deviations (M2), mergeable: partial summaries of several files or
/// threads combine exactly by the pairwise formula of Chan, Golub & LeVeque (1979), without a
/// second pass over the data.
struct Summary {
  std::size_t n = 0;
  double mean = 0.0;
  double m2 = 0.0;  ///< sum of squared deviations from the mean
  /// Low-order part of the mean (mean + mean_lo is the mean to ~1e-19 relative): kept so that
  /// merging summaries of data with many constant leading digits (NIST NumAcc4) loses nothing to
  /// the rounding of each part's mean. Readers use `mean`.
  double mean_lo = 0.0;
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();

  void add(double x) noexcept;                ///< Welford's update
  void merge(const Summary& other) noexcept;  ///< pairwise (Chan et al.) combination
  std::optional<double> variance() const noexcept;  ///< m2 / (n - 1); empty when n < 2
  std::optional<double> sd() const noexcept;
  std::optional<double> se() const noexcept;  ///< sd / sqrt(n)
};

/// Summary of a whole sample computed accurately (two passes: mean, then a compensated sum of
/// squared deviations), so NIST StRD NumAcc4 comes out with LRE >= 13.
Summary summarize(std::span<const double> x);

/// R's `quantile(x, p, type = 7)`; `sorted` must be sorted ascending and non-empty.
double quantile_type7(std::span<const double> sorted, double p);

/// Lag-1 autocorrelation r1 = sum_{i>=2}(y_i - ybar)(y_{i-1} - ybar) / sum (y_i - ybar)^2
/// (NIST StRD's definition); empty when n < 2 or the data are constant.
std::optional<double> autocorr_lag1(std::span<const double> x);

/// Everything `feint describe` prints for one sample. Values that cannot be computed are empty and
/// `note` says why.
struct Description {
  std::size_t n = 0;
  std::optional<double> mean, sd, se, min, q1, median, q3, max, conf_low, conf_high, autocorr_lag1;
  std::string note;
};

/// n, mean, sd (n-1), se, min, quartiles (type 7), max, t-based CI of the mean at `conf_level`,
/// lag-1 autocorrelation.
Description describe(std::span<const double> x, double conf_level = 0.95);

}  // namespace feint::stats

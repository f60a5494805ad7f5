// The Westfall–Young step-down maxF over omnibus F tests of k conditions: see feint/stats/maxf.hpp.
#include "feint/stats/maxf.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/rng.hpp"

namespace feint::stats {

namespace {

constexpr double kNever = -std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The step-down counts over the labellings: the observed statistics fix the order and the
/// thresholds; each labelling's statistics are then compared with them (as maxt_step_down does).
class StepDown {
 public:
  explicit StepDown(const std::vector<double>& observed) : observed_(observed), reach_own_(observed.size(), 0) {
    for (std::size_t j = 0; j < observed.size(); ++j)
      if (!std::isnan(observed[j])) order_.push_back(j);
    std::stable_sort(order_.begin(), order_.end(),
                     [&](std::size_t a, std::size_t b) { return observed[a] > observed[b]; });
    reach_max_.assign(order_.size(), 0);
    // A relabelling's statistic equal to the observed one up to rounding reaches it (the observed
    // labelling itself, and exact ties between labellings).
    threshold_.resize(observed.size());
    for (std::size_t j = 0; j < observed.size(); ++j)
      threshold_[j] = observed[j] - 1e-9 * std::max(1.0, std::fabs(observed[j]));
  }

  void add(const std::vector<double>& s) {
    double u = kNever;
    for (std::size_t r = order_.size(); r-- > 0;) {
      const std::size_t j = order_[r];
      const double v = std::isnan(s[j]) ? kNever : s[j];
      u = std::max(u, v);
      if (u >= threshold_[j]) ++reach_max_[r];
      if (v >= threshold_[j]) ++reach_own_[j];
    }
  }

  MaxTResult result(std::uint64_t total, bool exact) const {
    MaxTResult out;
    const std::size_t J = observed_.size();
    out.statistic.resize(J);
    out.p_raw.resize(J);
    out.p_adjusted.resize(J);
    out.labellings = total;
    out.exact = exact;
    const double n = static_cast<double>(total);
    double running = 0;
    for (std::size_t r = 0; r < order_.size(); ++r) {
      const std::size_t j = order_[r];
      running = std::max(running, static_cast<double>(reach_max_[r]) / n);
      out.statistic[j] = observed_[j];
      out.p_adjusted[j] = running;
      out.p_raw[j] = static_cast<double>(reach_own_[j]) / n;
    }
    return out;
  }

 private:
  std::vector<double> observed_, threshold_;
  std::vector<std::size_t> order_;  // computable tests, largest observed statistic first
  std::vector<std::uint64_t> reach_max_, reach_own_;
};

/// a * b, or a value above `cap` once the product exceeds it.
double times_capped(double a, double b, double cap) { return a > cap || b > cap ? cap * 2 : std::min(a * b, cap * 2); }

/// C(n, k), or a value above `cap`.
double choose_capped(std::size_t n, std::size_t k, double cap) {
  k = std::min(k, n - k);
  double r = 1;
  for (std::size_t i = 1; i <= k; ++i) {
    r = r * static_cast<double>(n - k + i) / static_cast<double>(i);
    if (r > cap) return cap * 2;
  }
  return std::round(r);
}

// ---- between participants ----------------------------------------------------------------------

/// The tests' values centred per column (so that sums of squares do not cancel), and the labels.
struct Between {
  std::size_t P = 0, J = 0, K = 0;
  std::vector<double> x;  // centred, participant-major; NaN = missing
};

Between centred_between(std::span<const double> values, std::size_t columns, std::size_t conditions) {
  Between b{values.size() / columns, columns, conditions, {values.begin(), values.end()}};
  for (std::size_t j = 0; j < b.J; ++j) {
    double s = 0, n = 0;
    for (std::size_t i = 0; i < b.P; ++i)
      if (const double v = b.x[i * b.J + j]; !std::isnan(v)) {
        s += v;
        ++n;
      }
    const double centre = n > 0 ? s / n : 0.0;
    for (std::size_t i = 0; i < b.P; ++i) b.x[i * b.J + j] -= centre;
  }
  return b;
}

/// Welch's F (oneway.test's arithmetic, as stats::welch_anova) of every column under `labels`.
class WelchStatistics {
 public:
  explicit WelchStatistics(const Between& b) : b_(b), n_(b.K * b.J), s_(b.K * b.J), q_(b.K * b.J) {}

  void operator()(std::span<const int> labels, std::vector<double>& f) {
    std::fill(n_.begin(), n_.end(), 0.0);
    std::fill(s_.begin(), s_.end(), 0.0);
    std::fill(q_.begin(), q_.end(), 0.0);
    const std::size_t J = b_.J;
    for (std::size_t i = 0; i < b_.P; ++i) {
      const double* row = &b_.x[i * J];
      const std::size_t at = static_cast<std::size_t>(labels[i]) * J;
      for (std::size_t j = 0; j < J; ++j) {
        if (std::isnan(row[j])) continue;
        n_[at + j] += 1;
        s_[at + j] += row[j];
        q_[at + j] += row[j] * row[j];
      }
    }
    for (std::size_t j = 0; j < J; ++j) f[j] = column(j);
  }

 private:
  double column(std::size_t j) const {
    double k = 0, sum_w = 0, mw = 0, tmp = 0;
    for (std::size_t g = 0; g < b_.K; ++g) {
      const std::size_t c = g * b_.J + j;
      if (n_[c] == 0) continue;  // a condition without values here: left out, as R's factor() drops it
      if (n_[c] < 2) return kNaN;
      const double mean = s_[c] / n_[c];
      const double ss = q_[c] - s_[c] * mean;
      if (!(ss > 1e-12 * q_[c])) return kNaN;  // constant within the condition
      const double w = n_[c] / (ss / (n_[c] - 1));
      ++k;
      sum_w += w;
      mw += w * mean;
    }
    if (k < 2) return kNaN;
    mw /= sum_w;
    double between = 0;
    for (std::size_t g = 0; g < b_.K; ++g) {
      const std::size_t c = g * b_.J + j;
      if (n_[c] == 0) continue;
      const double mean = s_[c] / n_[c];
      const double w = n_[c] / ((q_[c] - s_[c] * mean) / (n_[c] - 1));
      const double u = 1 - w / sum_w;
      tmp += u * u / (n_[c] - 1);
      between += w * (mean - mw) * (mean - mw);
    }
    tmp /= k * k - 1;
    return between / ((k - 1) * (1 + 2 * (k - 2) * tmp));
  }

  const Between& b_;
  std::vector<double> n_, s_, q_;  // per condition x column
};

/// The number of distinct assignments of `labels`, P! / prod n_g!, or a value above `cap`.
double assignments_capped(std::span<const int> labels, std::size_t conditions, double cap) {
  std::vector<std::size_t> sizes(conditions, 0);
  for (int g : labels) ++sizes[static_cast<std::size_t>(g)];
  double count = 1;
  std::size_t left = labels.size();
  for (std::size_t s : sizes) {
    count = times_capped(count, choose_capped(left, s, cap), cap);
    left -= s;
  }
  return count;
}

// ---- within participants -----------------------------------------------------------------------

/// Each participant's values at a column centred on their own mean over the conditions (0 where the
/// participant lacks a condition there: they are left out of that column).
struct Within {
  std::size_t P = 0, K = 0, J = 0;
  std::vector<double> d;           // (i * K + c) * J + j
  std::vector<double> n, total;    // per column: complete participants, sum of d^2
};

Within centred_within(std::span<const double> values, std::size_t conditions, std::size_t columns) {
  Within w{values.size() / (conditions * columns), conditions, columns, std::vector<double>(values.size(), 0.0),
           std::vector<double>(columns, 0.0), std::vector<double>(columns, 0.0)};
  for (std::size_t i = 0; i < w.P; ++i)
    for (std::size_t j = 0; j < w.J; ++j) {
      double s = 0;
      bool complete = true;
      for (std::size_t c = 0; c < w.K; ++c) {
        const double v = values[(i * w.K + c) * w.J + j];
        complete = complete && !std::isnan(v);
        s += v;
      }
      if (!complete) continue;
      const double mean = s / static_cast<double>(w.K);
      w.n[j] += 1;
      for (std::size_t c = 0; c < w.K; ++c) {
        const double v = values[(i * w.K + c) * w.J + j] - mean;
        w.d[(i * w.K + c) * w.J + j] = v;
        w.total[j] += v * v;
      }
    }
  return w;
}

/// The repeated-measures F of every column when participant i's condition c takes the values of
/// its condition order[i * K + c].
class RepeatedF {
 public:
  explicit RepeatedF(const Within& w) : w_(w), sums_(w.K * w.J) {}

  void operator()(std::span<const std::size_t> order, std::vector<double>& f) {
    std::fill(sums_.begin(), sums_.end(), 0.0);
    const std::size_t K = w_.K, J = w_.J;
    for (std::size_t i = 0; i < w_.P; ++i)
      for (std::size_t c = 0; c < K; ++c) {
        const double* from = &w_.d[(i * K + order[i * K + c]) * J];
        double* to = &sums_[c * J];
        for (std::size_t j = 0; j < J; ++j) to[j] += from[j];
      }
    const double k = static_cast<double>(K);
    for (std::size_t j = 0; j < J; ++j) {
      const double n = w_.n[j];
      f[j] = kNaN;
      if (n < 2) continue;
      double ss = 0;
      for (std::size_t c = 0; c < K; ++c) ss += sums_[c * J + j] * sums_[c * J + j] / n;
      const double error = w_.total[j] - ss;
      if (!(error > 1e-13 * w_.total[j])) continue;
      f[j] = (ss / (k - 1)) / (error / ((k - 1) * (n - 1)));
    }
  }

 private:
  const Within& w_;
  std::vector<double> sums_;  // per condition x column
};

}  // namespace

MaxTResult maxf_step_down_between(std::span<const double> values, std::size_t columns, std::span<const int> group,
                                  const MaxFOptions& options) {
  if (columns == 0) throw UsageError("maxf_step_down_between: no tests (0 columns)");
  if (values.size() != group.size() * columns)
    throw UsageError(fmt::format("maxf_step_down_between: {} values for {} participants x {} tests", values.size(),
                                 group.size(), columns));
  if (options.permutations == 0) throw UsageError("maxf_step_down_between: permutations must be >= 1");
  int top = -1;
  for (int g : group) {
    if (g < 0) throw UsageError(fmt::format("maxf_step_down_between: condition label {} is negative", g));
    top = std::max(top, g);
  }
  const auto K = static_cast<std::size_t>(top + 1);
  if (K < 2) throw UsageError("maxf_step_down_between: the participants are in fewer than two conditions");

  const Between b = centred_between(values, columns, K);
  WelchStatistics welch(b);
  std::vector<double> observed(columns), f(columns);
  welch(group, observed);
  StepDown counts(observed);
  const double cap = static_cast<double>(options.permutations) + 1;
  std::vector<int> labels(group.begin(), group.end());
  if (assignments_capped(group, K, cap) <= cap) {
    // Every distinct assignment of the labels, in lexicographic order (the observed one among them).
    std::sort(labels.begin(), labels.end());
    std::uint64_t total = 0;
    do {
      welch(labels, f);
      counts.add(f);
      ++total;
    } while (std::next_permutation(labels.begin(), labels.end()));
    return counts.result(total, true);
  }
  counts.add(observed);  // the observed labelling counts once
  Rng rng(options.seed);
  const std::size_t P = labels.size();
  for (std::uint64_t r = 0; r < options.permutations; ++r) {
    for (std::size_t i = 0; i + 1 < P; ++i)  // Fisher–Yates: a uniform permutation of the labels
      std::swap(labels[i], labels[i + rng.bounded(static_cast<std::uint32_t>(P - i))]);
    welch(labels, f);
    counts.add(f);
  }
  return counts.result(options.permutations + 1, false);
}

MaxTResult maxf_step_down_within(std::span<const double> values, std::size_t conditions, std::size_t columns,
                                 const MaxFOptions& options) {
  if (columns == 0) throw UsageError("maxf_step_down_within: no tests (0 columns)");
  if (conditions < 2) throw UsageError("maxf_step_down_within: fewer than two conditions");
  if (values.empty() || values.size() % (conditions * columns) != 0)
    throw UsageError(fmt::format("maxf_step_down_within: {} values do not fill participants x {} conditions x {} tests",
                                 values.size(), conditions, columns));
  if (options.permutations == 0) throw UsageError("maxf_step_down_within: permutations must be >= 1");
  const Within w = centred_within(values, conditions, columns);
  const std::size_t P = w.P, K = conditions;
  RepeatedF rm(w);
  std::vector<std::size_t> order(P * K);
  for (std::size_t i = 0; i < P; ++i) std::iota(order.begin() + static_cast<std::ptrdiff_t>(i * K),
                                                order.begin() + static_cast<std::ptrdiff_t>((i + 1) * K), std::size_t{0});
  std::vector<double> observed(columns), f(columns);
  rm(order, observed);
  StepDown counts(observed);
  const double cap = static_cast<double>(options.permutations) + 1;
  double orders_per_participant = 1;
  for (std::size_t k = 2; k <= K; ++k) orders_per_participant *= static_cast<double>(k);
  double count = 1;
  for (std::size_t i = 0; i < P; ++i) count = times_capped(count, orders_per_participant, cap);
  if (count <= cap) {
    // Every combination of the participants' orders: an odometer over the k! orders of each.
    std::vector<std::vector<std::size_t>> orders;
    std::vector<std::size_t> o(K);
    std::iota(o.begin(), o.end(), std::size_t{0});
    do orders.push_back(o);
    while (std::next_permutation(o.begin(), o.end()));
    std::vector<std::size_t> digit(P, 0);
    std::uint64_t total = 0;
    for (;;) {
      for (std::size_t i = 0; i < P; ++i) std::copy(orders[digit[i]].begin(), orders[digit[i]].end(),
                                                    order.begin() + static_cast<std::ptrdiff_t>(i * K));
      rm(order, f);
      counts.add(f);
      ++total;
      std::size_t i = 0;
      while (i < P && ++digit[i] == orders.size()) digit[i++] = 0;
      if (i == P) break;
    }
    return counts.result(total, true);
  }
  counts.add(observed);  // the observed labelling counts once
  Rng rng(options.seed);
  for (std::uint64_t r = 0; r < options.permutations; ++r) {
    for (std::size_t i = 0; i < P; ++i) {
      std::size_t* row = &order[i * K];
      for (std::size_t c = 0; c + 1 < K; ++c) std::swap(row[c], row[c + rng.bounded(static_cast<std::uint32_t>(K - c))]);
    }
    rm(order, f);
    counts.add(f);
  }
  return counts.result(options.permutations + 1, false);
}

}  // namespace feint::stats

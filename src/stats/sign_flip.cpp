// The Westfall–Young step-down maxT over sign flips: paired t tests of participants who saw both
// conditions (see feint/stats/permutation.hpp, maxt_step_down_paired).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "feint/error.hpp"
#include "feint/rng.hpp"
#include "feint/stats/permutation.hpp"

namespace feint::stats {

namespace {

constexpr double kNever = -std::numeric_limits<double>::infinity();

double oriented(double t, Alternative a) {
  if (std::isnan(t)) return kNever;
  if (a == Alternative::greater) return t;
  if (a == Alternative::less) return -t;
  return std::fabs(t);
}

/// The columns' differences with what a sign vector leaves unchanged: n and the sum of squares
/// (a flip changes only the sum). The mean is taken out of the sum of squares per labelling.
struct Differences {
  std::size_t participants = 0, columns = 0;
  std::vector<double> d;          // participant-major; NaN = no pair
  std::vector<double> n, sumsq, scale;
};

Differences differences_of(std::span<const double> values, std::size_t columns) {
  Differences c;
  c.columns = columns;
  c.participants = values.size() / columns;
  c.d.assign(values.begin(), values.end());
  c.n.assign(columns, 0.0);
  c.sumsq.assign(columns, 0.0);
  c.scale.assign(columns, 0.0);
  for (std::size_t i = 0; i < c.participants; ++i)
    for (std::size_t j = 0; j < columns; ++j)
      if (const double v = c.d[i * columns + j]; !std::isnan(v)) {
        c.n[j] += 1;
        c.sumsq[j] += v * v;
        c.scale[j] = std::max(c.scale[j], std::fabs(v));
      }
  return c;
}

/// Paired t of every column under the signs `flip` (true = swapped); NaN where not computable.
void paired_t(const Differences& c, const std::vector<char>& flip, std::vector<double>& sum,
              std::vector<double>& t) {
  const std::size_t J = c.columns;
  std::fill(sum.begin(), sum.end(), 0.0);
  for (std::size_t i = 0; i < c.participants; ++i) {
    const double* row = &c.d[i * J];
    const double s = flip[i] ? -1.0 : 1.0;
    for (std::size_t j = 0; j < J; ++j)
      if (!std::isnan(row[j])) sum[j] += s * row[j];
  }
  for (std::size_t j = 0; j < J; ++j) {
    t[j] = std::nan("");
    const double n = c.n[j];
    if (n < 2) continue;
    const double mean = sum[j] / n;
    const double ss = std::max(0.0, c.sumsq[j] - sum[j] * mean);
    const double se = std::sqrt(ss / (n - 1) / n);
    // R's "data are essentially constant" check (t.test: stderr < 10 eps |mean|).
    if (!std::isfinite(se) || se == 0 || se < 10 * std::numeric_limits<double>::epsilon() * std::fabs(mean))
      continue;
    t[j] = mean / se;
  }
}

}  // namespace

MaxTResult maxt_step_down_paired(std::span<const double> differences, std::size_t columns,
                                 const MaxTOptions& options) {
  if (columns == 0) throw UsageError("maxt_step_down_paired: no tests (0 columns)");
  if (differences.empty() || differences.size() % columns != 0)
    throw UsageError(fmt::format("maxt_step_down_paired: {} differences do not fill {} tests per participant",
                                 differences.size(), columns));
  if (options.permutations == 0) throw UsageError("maxt_step_down_paired: permutations must be >= 1");
  const Differences c = differences_of(differences, columns);
  const std::size_t P = c.participants;
  std::vector<char> flip(P, 0);
  std::vector<double> sum(columns), t(columns);
  paired_t(c, flip, sum, t);

  MaxTResult out;
  out.statistic.resize(columns);
  out.p_raw.resize(columns);
  out.p_adjusted.resize(columns);
  std::vector<double> observed(columns, kNever);
  std::vector<std::size_t> order;  // computable columns, largest observed statistic first
  for (std::size_t j = 0; j < columns; ++j) {
    if (std::isnan(t[j])) continue;
    out.statistic[j] = t[j];
    observed[j] = oriented(t[j], options.alternative);
    order.push_back(j);
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return observed[a] > observed[b]; });
  if (order.empty()) return out;
  std::vector<double> threshold(columns);
  for (std::size_t j = 0; j < columns; ++j) threshold[j] = observed[j] - 1e-9 * std::max(1.0, std::fabs(observed[j]));
  const std::size_t m = order.size();
  std::vector<std::uint64_t> reach_max(m, 0), reach_own(columns, 0);
  auto count = [&] {
    paired_t(c, flip, sum, t);
    double u = kNever;
    for (std::size_t r = m; r-- > 0;) {
      const std::size_t j = order[r];
      const double s = oriented(t[j], options.alternative);
      u = std::max(u, s);
      if (u >= threshold[j]) ++reach_max[r];
      if (s >= threshold[j]) ++reach_own[j];
    }
  };
  // Every sign vector (binary counting, the observed all-zero one first) when there are at most
  // permutations + 1 of them; else the observed one and uniform draws.
  const double all = std::ldexp(1.0, static_cast<int>(std::min<std::size_t>(P, 1000)));
  out.exact = P < 40 && all <= static_cast<double>(options.permutations) + 1;
  if (out.exact) {
    const std::uint64_t total = std::uint64_t{1} << P;
    for (std::uint64_t b = 0; b < total; ++b) {
      for (std::size_t i = 0; i < P; ++i) flip[i] = static_cast<char>((b >> i) & 1U);
      count();
    }
    out.labellings = total;
  } else {
    count();  // the observed signs
    Rng rng(options.seed);
    for (std::uint64_t b = 0; b < options.permutations; ++b) {
      for (std::size_t i = 0; i < P; ++i) flip[i] = static_cast<char>(rng() >> 63);
      count();
    }
    out.labellings = options.permutations + 1;
  }
  const double n = static_cast<double>(out.labellings);
  double running = 0;
  for (std::size_t r = 0; r < m; ++r) {
    const std::size_t j = order[r];
    running = std::max(running, static_cast<double>(reach_max[r]) / n);
    out.p_adjusted[j] = running;
    out.p_raw[j] = static_cast<double>(reach_own[j]) / n;
  }
  return out;
}

}  // namespace feint::stats

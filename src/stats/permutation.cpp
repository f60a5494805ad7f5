// The Westfall–Young step-down maxT permutation adjustment: see feint/stats/permutation.hpp.
#include "feint/stats/permutation.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/rng.hpp"

namespace feint::stats {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kNever = -std::numeric_limits<double>::infinity();

/// The data of the tests, centred per column (so that sums of squares do not cancel) with the
/// column totals that a labelling's group-1 sums are taken from.
struct Columns {
  std::size_t participants = 0, columns = 0;
  std::vector<double> x;  // centred, participant-major; NaN = missing
  std::vector<double> centre, n, sum, sumsq;  // per column, over every participant
};

Columns centred(std::span<const double> values, std::size_t columns, std::size_t participants) {
  Columns c;
  c.participants = participants;
  c.columns = columns;
  c.x.assign(values.begin(), values.end());
  c.centre.assign(columns, 0.0);
  c.n.assign(columns, 0.0);
  c.sum.assign(columns, 0.0);
  c.sumsq.assign(columns, 0.0);
  for (std::size_t j = 0; j < columns; ++j) {
    double s = 0, k = 0;
    for (std::size_t i = 0; i < participants; ++i)
      if (const double v = values[i * columns + j]; !std::isnan(v)) {
        s += v;
        ++k;
      }
    c.centre[j] = k > 0 ? s / k : 0.0;
    c.n[j] = k;
    for (std::size_t i = 0; i < participants; ++i) {
      double& v = c.x[i * columns + j];
      if (std::isnan(v)) continue;
      v -= c.centre[j];
      c.sum[j] += v;
      c.sumsq[j] += v * v;
    }
  }
  return c;
}

/// The t statistic of every column for the participants in `members` as group 1 (the others are
/// group 2); NaN where it cannot be computed (too few values, constant data).
void t_statistics(const Columns& c, std::span<const std::size_t> members, bool var_equal,
                  std::vector<double>& n1, std::vector<double>& s1, std::vector<double>& q1,
                  std::vector<double>& t) {
  const std::size_t J = c.columns;
  std::fill(n1.begin(), n1.end(), 0.0);
  std::fill(s1.begin(), s1.end(), 0.0);
  std::fill(q1.begin(), q1.end(), 0.0);
  for (const std::size_t i : members) {
    const double* row = &c.x[i * J];
    for (std::size_t j = 0; j < J; ++j) {
      const double v = row[j];
      if (std::isnan(v)) continue;
      n1[j] += 1;
      s1[j] += v;
      q1[j] += v * v;
    }
  }
  for (std::size_t j = 0; j < J; ++j) {
    const double na = n1[j], nb = c.n[j] - n1[j];
    t[j] = std::nan("");
    if (na < 1 || nb < 1) continue;
    if (var_equal ? na + nb < 3 : (na < 2 || nb < 2)) continue;
    const double sa = s1[j], sb = c.sum[j] - s1[j];
    const double ma = sa / na, mb = sb / nb;
    // Sums of squares about each group's mean (>= 0 up to rounding).
    const double ssa = std::max(0.0, q1[j] - sa * ma), ssb = std::max(0.0, (c.sumsq[j] - q1[j]) - sb * mb);
    double se;
    if (var_equal) {
      se = std::sqrt((ssa + ssb) / (na + nb - 2) * (1 / na + 1 / nb));
    } else {
      se = std::sqrt(ssa / (na - 1) / na + ssb / (nb - 1) / nb);
    }
    // R's "data are essentially constant" check, on the means of the original (uncentred) data.
    const double scale = std::max(std::fabs(ma + c.centre[j]), std::fabs(mb + c.centre[j]));
    if (!std::isfinite(se) || se == 0 || se < 10 * kEps * scale) continue;
    t[j] = (ma - mb) / se;
  }
}

double oriented(double t, Alternative a) {
  if (std::isnan(t)) return kNever;
  switch (a) {
    case Alternative::greater: return t;
    case Alternative::less: return -t;
    case Alternative::two_sided: break;
  }
  return std::fabs(t);
}

/// C(n, k), or a value above `cap` when it exceeds it.
double choose_capped(std::size_t n, std::size_t k, double cap) {
  k = std::min(k, n - k);
  double r = 1;
  for (std::size_t i = 1; i <= k; ++i) {
    r = r * static_cast<double>(n - k + i) / static_cast<double>(i);
    if (r > cap) return r;
  }
  return std::round(r);
}

}  // namespace

bool every_labelling(std::size_t participants, std::size_t members, std::uint64_t permutations) {
  if (members == 0 || members >= participants) return true;
  const double cap = static_cast<double>(permutations) + 1;
  return choose_capped(participants, members, cap) <= cap;
}

Labellings for_each_labelling(std::size_t participants, std::span<const std::size_t> members,
                              std::uint64_t permutations, std::uint64_t seed,
                              const std::function<void(std::span<const std::size_t>)>& visit) {
  return for_each_labelling_while(participants, members, permutations, seed,
                                  [&](std::span<const std::size_t> g) {
                                    visit(g);
                                    return true;
                                  });
}

Labellings for_each_labelling_while(std::size_t participants, std::span<const std::size_t> members,
                                    std::uint64_t permutations, std::uint64_t seed,
                                    const std::function<bool(std::span<const std::size_t>)>& visit) {
  const std::size_t P = participants, k = members.size();
  if (permutations == 0) throw UsageError("for_each_labelling: permutations must be >= 1");
  if (k == 0 || k >= P) throw UsageError("for_each_labelling: both groups need at least one participant");
  Labellings out;
  if (every_labelling(P, k, permutations)) {
    // Every labelling with k participants in group 1, in lexicographic order.
    out.exact = true;
    std::vector<std::size_t> g(k);
    std::iota(g.begin(), g.end(), std::size_t{0});
    for (;;) {
      visit(g);
      ++out.total;
      std::size_t i = k;
      while (i > 0 && g[i - 1] == P - k + (i - 1)) --i;
      if (i == 0) break;
      ++g[i - 1];
      for (std::size_t r = i; r < k; ++r) g[r] = g[r - 1] + 1;
    }
    return out;
  }
  out.total = 1;  // the observed labelling counts once
  if (!visit(members)) return out;
  std::vector<std::size_t> labels(P);
  std::iota(labels.begin(), labels.end(), std::size_t{0});
  Rng rng(seed);
  for (std::uint64_t b = 0; b < permutations; ++b) {
    // Fisher–Yates: the first k of a uniform permutation are a uniform k-subset.
    for (std::size_t i = 0; i < k; ++i) {
      const std::size_t j = i + rng.bounded(static_cast<std::uint32_t>(P - i));
      std::swap(labels[i], labels[j]);
    }
    ++out.total;
    if (!visit(std::span<const std::size_t>(labels.data(), k))) break;
  }
  return out;
}

SequentialPValue::SequentialPValue(std::uint64_t h, std::uint64_t n) : h_(h), n_(n) {
  if (n < 2) throw UsageError("SequentialPValue: needs n >= 2 (at least one sampled labelling)");
}

void SequentialPValue::add(bool reaches) {
  if (done()) return;
  ++sampled_;
  if (reaches) ++reached_;
}

double SequentialPValue::p() const {
  if (stopped_early()) return static_cast<double>(h_) / static_cast<double>(sampled_);
  return static_cast<double>(reached_ + 1) / static_cast<double>(sampled_ + 1);
}

MaxTResult maxt_step_down(std::span<const double> values, std::size_t columns, std::span<const int> group,
                          const MaxTOptions& options) {
  if (columns == 0) throw UsageError("maxt_step_down: no tests (0 columns)");
  if (values.size() != group.size() * columns)
    throw UsageError(fmt::format("maxt_step_down: {} values for {} participants x {} tests", values.size(),
                                 group.size(), columns));
  if (options.permutations == 0) throw UsageError("maxt_step_down: permutations must be >= 1");
  std::vector<std::size_t> members;  // group 1
  for (std::size_t i = 0; i < group.size(); ++i) {
    if (group[i] != 0 && group[i] != 1)
      throw UsageError(fmt::format("maxt_step_down: group label {} of participant {} is not 0 or 1", group[i], i));
    if (group[i] == 1) members.push_back(i);
  }
  const std::size_t P = group.size(), k = members.size();
  if (k == 0 || k == P) throw UsageError("maxt_step_down: both groups need at least one participant");

  const Columns c = centred(values, columns, P);
  std::vector<double> n1(columns), s1(columns), q1(columns), t(columns);
  t_statistics(c, members, options.var_equal, n1, s1, q1, t);

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
  // A relabelling's statistic equal to the observed one up to rounding counts as reaching it
  // (the observed labelling itself, and exact ties between labellings).
  std::vector<double> threshold(columns);
  for (std::size_t j = 0; j < columns; ++j) threshold[j] = observed[j] - 1e-9 * std::max(1.0, std::fabs(observed[j]));

  const std::size_t m = order.size();
  std::vector<std::uint64_t> reach_max(m, 0), reach_own(columns, 0);
  auto count = [&](std::span<const std::size_t> g1) {
    t_statistics(c, g1, options.var_equal, n1, s1, q1, t);
    double u = kNever;
    for (std::size_t r = m; r-- > 0;) {
      const std::size_t j = order[r];
      const double s = oriented(t[j], options.alternative);
      u = std::max(u, s);
      if (u >= threshold[j]) ++reach_max[r];
      if (s >= threshold[j]) ++reach_own[j];
    }
  };

  const Labellings l = for_each_labelling(P, members, options.permutations, options.seed, count);
  out.exact = l.exact;
  const std::uint64_t total = l.total;
  out.labellings = total;
  const double n = static_cast<double>(total);
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

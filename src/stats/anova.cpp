#include "feint/stats/anova.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/stats/descriptive.hpp"
#include "shifted.hpp"
#include "stats_detail.hpp"

namespace feint::stats {

namespace detail {

AnovaTable anova_of(const std::vector<std::vector<long double>>& groups, long double scale) {
  std::size_t k = 0, n = 0;
  long double total = 0;
  for (const auto& g : groups) {
    if (g.empty()) continue;  // an empty group is an unused factor level, as in lm()
    ++k;
    n += g.size();
    for (long double v : g) total += v;
  }
  if (k < 2) throw InvalidData("one-way ANOVA needs at least two non-empty groups");
  if (n <= k)
    throw InvalidData("one-way ANOVA has no residual degrees of freedom (one value per group)");
  const long double grand = total / static_cast<long double>(n);
  long double ssb = 0, ssw = 0;
  for (const auto& g : groups) {
    if (g.empty()) continue;
    const long double m = static_cast<long double>(g.size());
    long double sum = 0;
    for (long double v : g) sum += v;
    const long double mean = sum / m;
    // Corrected two-pass sum of squares within the group (Chan, Golub & LeVeque 1983).
    long double ss = 0, corr = 0;
    for (long double v : g) {
      const long double d = v - mean;
      ss += d * d;
      corr += d;
    }
    ssw += std::max(0.0L, ss - corr * corr / m);
    ssb += m * (mean - grand) * (mean - grand);
  }
  const long double s2 = scale * scale;
  AnovaTable t;
  t.df_between = static_cast<double>(k - 1);
  t.df_within = static_cast<double>(n - k);
  t.ss_between = static_cast<double>(ssb / s2);
  t.ss_within = static_cast<double>(ssw / s2);
  t.ms_between = static_cast<double>(ssb / s2 / static_cast<long double>(k - 1));
  t.ms_within = static_cast<double>(ssw / s2 / static_cast<long double>(n - k));
  // F from the extended-precision sums, not from the rounded mean squares.
  t.f_statistic = static_cast<double>((ssb / static_cast<long double>(k - 1)) /
                                      (ssw / static_cast<long double>(n - k)));
  t.r_squared = static_cast<double>(ssb / (ssb + ssw));
  t.residual_sd = std::sqrt(t.ms_within);
  t.p_value = std::isfinite(t.f_statistic) ? f_p_value(t.f_statistic, t.df_between, t.df_within)
                                           : std::numeric_limits<double>::quiet_NaN();
  if (ssw == 0 && ssb > 0) t.p_value = 0;
  return t;
}

}  // namespace detail

namespace {

std::vector<std::vector<double>> without_nan(std::span<const std::vector<double>> groups) {
  std::vector<std::vector<double>> out(groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (double v : groups[g])
      if (!std::isnan(v)) out[g].push_back(v);
  return out;
}

std::size_t non_empty(const std::vector<std::vector<double>>& groups) {
  std::size_t k = 0;
  for (const auto& g : groups) k += g.empty() ? 0 : 1;
  return k;
}

}  // namespace

AnovaTable one_way_anova_table(std::span<const std::vector<double>> groups) {
  const auto clean = without_nan(groups);
  std::vector<std::vector<long double>> a(clean.size());
  bool have_shift = false;
  long double shift = 0;
  for (std::size_t g = 0; g < clean.size(); ++g) {
    for (double v : clean[g]) {
      if (!have_shift) {
        shift = v;
        have_shift = true;
      }
      a[g].push_back(static_cast<long double>(v) - shift);
    }
  }
  return detail::anova_of(a, 1.0L);
}

// Strings are assigned from temporaries: GCC 12 at -O2 warns falsely (-Wrestrict, GCC bug 105329)
// on std::string = "literal".
TestResult one_way_anova(std::span<const std::vector<double>> groups) {
  TestResult r;
  r.test = std::string("anova");
  r.method = std::string("One-way analysis of means (ANOVA F-test)");
  r.statistic_name = std::string("F");
  const auto clean = without_nan(groups);
  std::size_t n = 0;
  for (const auto& g : clean) n += g.size();
  r.n1 = n;  // all observations
  const std::size_t k = non_empty(clean);
  if (k < 2) {
    r.computed = false;
    r.note = fmt::format("one-way ANOVA needs at least two non-empty groups (got {})", k);
    return r;
  }
  if (n <= k) {
    r.computed = false;
    r.note = std::string("not enough observations: no residual degrees of freedom (one value per group)");
    return r;
  }
  const AnovaTable t = one_way_anova_table(clean);
  if (!std::isfinite(t.ss_within) || !std::isfinite(t.ss_between)) {
    r.computed = false;
    r.note = std::string("infinite values in the data");
    return r;
  }
  if (!(t.ss_within > 0)) {
    r.computed = false;
    r.note = std::string("data are essentially constant within groups (residual sum of squares is 0)");
    return r;
  }
  r.statistic = t.f_statistic;
  r.df = t.df_between;
  r.df2 = t.df_within;
  r.p_value = t.p_value;
  r.r_squared = t.r_squared;
  if (k < clean.size()) r.note = fmt::format("{} empty group(s) left out", clean.size() - k);
  return r;
}

TestResult welch_anova(std::span<const std::vector<double>> groups) {
  TestResult r;
  r.test = std::string("welch_anova");
  r.method = std::string("One-way analysis of means (not assuming equal variances)");
  r.statistic_name = std::string("F");
  const auto clean = without_nan(groups);
  std::size_t n = 0;
  for (const auto& g : clean) n += g.size();
  r.n1 = n;
  std::vector<Summary> s;
  for (const auto& g : clean) {
    if (g.empty()) continue;
    s.push_back(summarize(g));
  }
  auto cannot = [&](std::string why) {
    r.computed = false;
    r.note = std::move(why);
    return r;
  };
  if (s.size() < 2)
    return cannot(fmt::format("Welch ANOVA needs at least two non-empty groups (got {})", s.size()));
  for (const auto& g : s)
    if (g.n < 2) return cannot("not enough observations: a group has fewer than 2 values");
  // oneway.test(y ~ g), var.equal = FALSE (Welch 1951), R's arithmetic.
  const double k = static_cast<double>(s.size());
  double sum_w = 0, mw = 0;
  std::vector<double> w(s.size());
  for (std::size_t j = 0; j < s.size(); ++j) {
    const double v = *s[j].variance();
    if (!std::isfinite(v) || !std::isfinite(s[j].mean)) return cannot("infinite values in the data");
    if (!(v > 0)) return cannot("data are essentially constant within a group (variance 0)");
    w[j] = static_cast<double>(s[j].n) / v;
    sum_w += w[j];
  }
  double tmp = 0;
  for (std::size_t j = 0; j < s.size(); ++j) {
    const double u = 1 - w[j] / sum_w;
    tmp += u * u / static_cast<double>(s[j].n - 1);
    mw += w[j] * s[j].mean;
  }
  tmp /= k * k - 1;
  mw /= sum_w;
  double ss = 0;
  for (std::size_t j = 0; j < s.size(); ++j) ss += w[j] * (s[j].mean - mw) * (s[j].mean - mw);
  const double f = ss / ((k - 1) * (1 + 2 * (k - 2) * tmp));
  const double df2 = 1 / (3 * tmp);
  r.statistic = f;
  r.df = k - 1;
  r.df2 = df2;
  r.p_value = detail::f_p_value(f, k - 1, df2);
  if (s.size() < clean.size()) r.note = fmt::format("{} empty group(s) left out", clean.size() - s.size());
  return r;
}

}  // namespace feint::stats

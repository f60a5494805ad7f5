// Kruskal–Wallis rank sum test, reproducing R 4.2's kruskal.test(y ~ g).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <boost/math/distributions/chi_squared.hpp>
#include <fmt/format.h>

#include "feint/stats/anova.hpp"
#include "feint/stats/rank_tests.hpp"

namespace feint::stats {

TestResult kruskal_wallis(std::span<const std::vector<double>> groups) {
  const std::string test = "kruskal_wallis";
  const std::string method = "Kruskal-Wallis rank sum test";

  // R drops NA/NaN (complete.cases) and, through factor(g), levels left without observations.
  std::vector<double> pooled;
  std::vector<std::size_t> sizes;
  std::size_t empty_groups = 0;
  for (const auto& group : groups) {
    std::size_t size = 0;
    for (double v : group)
      if (!std::isnan(v)) {
        pooled.push_back(v);
        ++size;
      }
    if (size == 0)
      ++empty_groups;
    else
      sizes.push_back(size);
  }
  const std::size_t n = pooled.size();
  const std::size_t k = sizes.size();
  if (n < 2)
    return TestResult::not_computable(test, method,
                                      fmt::format("{} observation(s): at least 2 are needed (R: \"not "
                                                  "enough observations\")",
                                                  n));
  if (k < 2)
    return TestResult::not_computable(
        test, method, "all observations are in the same group (R: the same error)");

  const detail::Ranks ranks = detail::average_ranks(pooled);
  double between = 0.0;  // sum over groups of R_g^2 / n_g
  std::size_t offset = 0;
  for (std::size_t size : sizes) {
    double rank_sum = 0.0;
    for (std::size_t i = 0; i < size; ++i) rank_sum += ranks.rank[offset + i];
    between += rank_sum * rank_sum / static_cast<double>(size);
    offset += size;
  }
  const double nd = static_cast<double>(n);
  const double tie_factor = 1.0 - ranks.tie_sum / (nd * nd * nd - nd);

  TestResult r;
  r.test = test;
  r.method = method;
  r.n1 = n;  // all observations
  r.statistic_name = "chi-squared";
  r.df = static_cast<double>(k - 1);
  if (empty_groups > 0)
    r.note = fmt::format("{} empty group(s) ignored, as R's factor() drops unused levels", empty_groups);
  if (!(tie_factor > 0.0)) {
    r.computed = false;
    if (!r.note.empty()) r.note += "; ";
    r.note += fmt::format("all {} observations are tied: the statistic is 0/0 (R returns NaN)", n);
    r.df.reset();
    return r;
  }
  const double h = (12.0 * between / (nd * (nd + 1.0)) - 3.0 * (nd + 1.0)) / tie_factor;
  r.statistic = h;
  r.rank_epsilon_squared = std::max(0.0, h) / (nd - 1.0);
  // H can come out a rounding error below 0 when the groups' mean ranks are equal; R's pchisq
  // gives 1 there, Boost would reject a negative argument.
  r.p_value = h <= 0.0 ? 1.0
                       : boost::math::cdf(boost::math::complement(
                             boost::math::chi_squared(static_cast<double>(k - 1)), h));
  return r;
}

}  // namespace feint::stats

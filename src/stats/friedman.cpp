// Friedman rank sum test, reproducing R 4.2's friedman.test(y) on a complete block matrix.
#include <cmath>
#include <string>
#include <vector>

#include <boost/math/distributions/chi_squared.hpp>
#include <fmt/format.h>

#include "feint/stats/rank_tests.hpp"

namespace feint::stats {

TestResult friedman_test(std::span<const std::vector<double>> blocks) {
  const std::string test = "friedman";
  const std::string method = "Friedman rank sum test";
  const std::size_t k = blocks.empty() ? 0 : blocks.front().size();
  if (k < 2) return TestResult::not_computable(test, method, "fewer than 2 conditions (R: \"not enough groups\")");
  std::vector<double> rank_sum(k, 0.0);
  double tie_sum = 0.0;
  std::size_t n = 0, dropped = 0;
  for (const auto& block : blocks) {
    bool complete = block.size() == k;
    for (double v : block) complete = complete && !std::isnan(v);
    if (!complete) {
      ++dropped;
      continue;
    }
    const detail::Ranks r = detail::average_ranks(block);
    for (std::size_t j = 0; j < k; ++j) rank_sum[j] += r.rank[j];
    tie_sum += r.tie_sum;
    ++n;
  }
  if (n == 0)
    return TestResult::not_computable(test, method, "no participant answered in every condition (R: \"not enough "
                                                    "complete blocks\")");
  const double nd = static_cast<double>(n), kd = static_cast<double>(k);
  double spread = 0.0;  // sum_j (R_j - n(k+1)/2)^2
  for (double rj : rank_sum) spread += (rj - nd * (kd + 1.0) / 2.0) * (rj - nd * (kd + 1.0) / 2.0);
  const double denominator = nd * kd * (kd + 1.0) - tie_sum / (kd - 1.0);
  TestResult r;
  r.test = test;
  r.method = method;
  r.n1 = n;
  r.statistic_name = "chi-squared";
  if (dropped > 0)
    r.note = fmt::format("{} participant(s) without an answer in every condition left out (complete cases)", dropped);
  if (!(denominator > 0.0)) {
    r.computed = false;
    if (!r.note.empty()) r.note += "; ";
    r.note += "every participant gave the same answer in every condition: the statistic is 0/0 (R returns NaN)";
    return r;
  }
  const double x2 = 12.0 * spread / denominator;
  r.statistic = x2;
  r.df = kd - 1.0;
  r.p_value = x2 <= 0.0 ? 1.0
                        : boost::math::cdf(boost::math::complement(boost::math::chi_squared(kd - 1.0), x2));
  return r;
}

std::optional<double> kendalls_w(const TestResult& friedman) {
  if (!friedman.computed || !friedman.statistic || !friedman.df || friedman.n1 == 0) return std::nullopt;
  return *friedman.statistic / (static_cast<double>(friedman.n1) * *friedman.df);
}

}  // namespace feint::stats

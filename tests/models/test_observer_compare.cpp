// The observer's parameters compared between two conditions on the participants' fits: beta on
// the log scale, tau on its own, Welch's t (with d and the Bayes factor) and Mann–Whitney; the t
// statistic recomputed here from its formula.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "feint/models/observer_fit.hpp"

namespace fm = feint::models;

namespace {

fm::ObserverFit fit(const std::string& condition, double beta, double tau, bool tau_at_zero = false) {
  fm::ObserverFit f;
  f.unit = condition + std::to_string(beta);
  f.condition = condition;
  f.parameters = {{"beta", beta, beta * 0.8, beta * 1.2, false, false},
                  {"tau", tau, tau_at_zero ? 0.0 : tau - 0.01, tau + 0.01, tau_at_zero, false}};
  return f;
}

double welch_t(const std::vector<double>& a, const std::vector<double>& b) {
  auto mean = [](const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size()); };
  auto var = [&](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += (x - mean(v)) * (x - mean(v));
    return s / double(v.size() - 1);
  };
  return (mean(a) - mean(b)) / std::sqrt(var(a) / double(a.size()) + var(b) / double(b.size()));
}

}  // namespace

TEST(ObserverComparison, BetaIsComparedOnTheLogScaleAndTauOnItsOwn) {
  const std::vector<double> beta_a{0.4, 0.5, 0.8, 0.6}, beta_b{0.2, 0.3, 0.25, 0.5, 0.35};
  const std::vector<double> tau_a{0.10, 0.12, 0.0, 0.2}, tau_b{0.1, 0.05, 0.08, 0.09, 0.07};
  std::vector<fm::ObserverFit> fits;
  for (std::size_t i = 0; i < beta_a.size(); ++i) fits.push_back(fit("adaptive", beta_a[i], tau_a[i], tau_a[i] == 0));
  for (std::size_t i = 0; i < beta_b.size(); ++i) fits.push_back(fit("random", beta_b[i], tau_b[i]));
  fits.push_back(fit("third", 9, 9));  // another condition is not mixed in
  const auto c = fm::compare_conditions(fits, "adaptive", "random", 0.95);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].parameter, "log beta");
  std::vector<double> la, lb;
  for (double b : beta_a) la.push_back(std::log(b));
  for (double b : beta_b) lb.push_back(std::log(b));
  EXPECT_NEAR(*c[0].welch.statistic, welch_t(la, lb), 1e-12);
  EXPECT_EQ(c[0].welch.n1, 4u);
  EXPECT_EQ(c[0].welch.n2, 5u);
  EXPECT_TRUE(c[0].welch.cohen_d_low.has_value());
  EXPECT_TRUE(c[0].welch.log_bf10.has_value());
  EXPECT_EQ(c[0].rank.test, "mann_whitney");
  // W counts the pairs (a, b) with a > b, a tie (0.5 against 0.5) as 1/2: 20 - 1 - 0.5 = 18.5.
  EXPECT_EQ(*c[0].rank.statistic, 18.5);
  EXPECT_EQ(c[1].parameter, "tau");
  EXPECT_NEAR(*c[1].welch.statistic, welch_t(tau_a, tau_b), 1e-12);
  EXPECT_EQ(c[1].at_bound, 1u);  // the tau = 0 fit is kept and counted
  EXPECT_EQ(c[0].at_bound, 0u);
}

TEST(ObserverComparison, AConditionWithOneParticipantGivesNoComparison) {
  const std::vector<fm::ObserverFit> fits{fit("adaptive", 0.3, 0.1), fit("adaptive", 0.4, 0.1), fit("random", 0.3, 0.1)};
  EXPECT_TRUE(fm::compare_conditions(fits, "adaptive", "random", 0.95).empty());
}

// The observer's parameters compared between two conditions on the participants' fits: beta on
// the log scale, tau on its own, Welch's t (with d and the Bayes factor) and Mann–Whitney; the t
// statistic recomputed here from its formula, and every number of six generated data sets against
// R (tests/golden/models/observer_compare_golden.R).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include "accuracy.hpp"
#include "feint/models/observer_fit.hpp"
#include "golden_csv.hpp"

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

// Six data sets (observer_compare_golden.R): balanced 8 + 8; unbalanced 5 + 11; a beta of 0 (left
// out of log beta), betas at the range's maximum and taus at 0 (kept, counted); ties (W's normal
// approximation); 2 + 3 with a third condition that is not compared; 30 + 25 far apart (p to 1e-28).
// Tolerances (relative, absolute below 1): Welch, W, the rank-biserial r and its interval 1e-10;
// d, g and their bounds 1e-11 (exact roots of the noncentral t); log BF10 1e-12.
TEST(ObserverComparison, SixDataSetsEqualR) {
  const auto data = feint::test::read_csv(feint::test::kModelGoldenDir + "observer_compare_data.csv");
  std::map<std::string, std::vector<fm::ObserverFit>> sets;
  for (std::size_t i = 1; i < data.size(); ++i) {  // dataset,participant,condition,beta,tau,beta_at_bound,tau_at_bound
    const auto& f = data[i];
    const double beta = std::stod(f[3]), tau = std::stod(f[4]);
    const bool beta_max = f[5] == "1", tau_zero = f[6] == "1";
    fm::ObserverFit o;
    o.unit = f[1];
    o.condition = f[2];
    o.parameters = {{"beta", beta, beta * 0.8, beta_max ? beta : beta * 1.2, false, beta_max},
                    {"tau", tau, tau_zero ? tau : tau * 0.8, tau + 0.01, tau_zero, false}};
    sets[f[0]].push_back(o);
  }
  ASSERT_EQ(sets.size(), 6u);
  std::map<std::tuple<std::string, std::string, std::string>, std::string> golden;
  for (const auto& row : feint::test::read_csv(feint::test::kModelGoldenDir + "observer_compare_golden.csv"))
    if (row.size() == 4 && row[0] != "dataset") golden[{row[0], row[1], row[2]}] = row[3];
  std::size_t checked = 0;
  for (const auto& [name, fits] : sets) {
    const auto c = fm::compare_conditions(fits, "adaptive", "random", 0.95);
    ASSERT_EQ(c.size(), 2u) << name;
    for (const auto& cmp : c) {
      const std::string where = name + " " + cmp.parameter;
      auto want = [&](const char* q) { return std::stod(golden.at({name, cmp.parameter, q})); };
      EXPECT_EQ(cmp.welch.n1, want("n_a")) << where;
      EXPECT_EQ(cmp.welch.n2, want("n_b")) << where;
      EXPECT_EQ(cmp.at_bound, want("at_bound")) << where;
      EXPECT_EQ(*cmp.rank.exact, want("exact") == 1) << where;
      const auto& w = cmp.welch;
      const auto& r = cmp.rank;
      for (const auto& [q, got, tol] : std::vector<std::tuple<const char*, std::optional<double>, double>>{
               {"t", w.statistic, 1e-10},      {"df", w.df, 1e-10},           {"p", w.p_value, 1e-10},
               {"conf_low", w.conf_low, 1e-10}, {"conf_high", w.conf_high, 1e-10}, {"estimate", w.estimate, 1e-10},
               {"d", w.cohen_d, 1e-11},        {"d_low", w.cohen_d_low, 1e-11}, {"d_high", w.cohen_d_high, 1e-11},
               {"g", w.hedges_g, 1e-11},       {"g_low", w.hedges_g_low, 1e-11}, {"g_high", w.hedges_g_high, 1e-11},
               {"log_bf10", w.log_bf10, 1e-12}, {"W", r.statistic, 1e-10},     {"p_mw", r.p_value, 1e-10},
               {"rb", r.rank_biserial, 1e-10}, {"rb_low", r.rank_biserial_low, 1e-10},
               {"rb_high", r.rank_biserial_high, 1e-10}}) {
        ASSERT_TRUE(got.has_value()) << where << " " << q;
        feint::test::record(std::string("observer conditions compared (t.test, wilcox.test, d, BF): ") + q, *got,
                            want(q), where);
        EXPECT_NEAR(*got, want(q), tol * std::max(1.0, std::fabs(want(q)))) << where << " " << q;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 6u * 2u * 18u);
}

// Within participants (someone fitted in both conditions) each participant's two estimates are
// paired; a participant fitted in one condition only is left out and counted. R (4.2.2), with
// a, b = the betas and ta, tb = the taus below:
//   t.test(log(a), log(b), paired = TRUE): t = 3.2014270905391591, df = 4, p = 0.032856086700188136,
//     CI [0.026829720040567342, 0.37739161419062378]; wilcox.test(..., paired = TRUE): V = 14,
//     p = 0.125; exp(ttestBF(log(a), log(b), paired = TRUE)@bayesFactor$bf) = 2.9940859116567093
//   t.test(ta, tb, paired = TRUE): t = 2.2558335591813887, p = 0.087080950102842725;
//     wilcox.test: V = 13.5, p = 0.13621686984456766 (normal approximation: a tie)
TEST(ObserverComparison, WithinParticipantsEachParticipantsPairIsCompared) {
  const std::vector<double> a{0.40, 0.50, 0.80, 0.60, 0.45}, b{0.30, 0.42, 0.61, 0.62, 0.33};
  const std::vector<double> ta{0.30, 0.25, 0.41, 0.20, 0.35}, tb{0.22, 0.27, 0.30, 0.18, 0.21};
  std::vector<fm::ObserverFit> fits;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (const bool first : {true, false}) {
      fm::ObserverFit f = fit(first ? "adaptive" : "random", first ? a[i] : b[i], first ? ta[i] : tb[i]);
      f.unit = "P" + std::to_string(i);
      fits.push_back(f);
    }
  }
  fm::ObserverFit lone = fit("random", 5.0, 5.0);
  lone.unit = "P9";  // fitted in random only
  fits.push_back(lone);
  const auto c = fm::compare_conditions(fits, "adaptive", "random", 0.95);
  ASSERT_EQ(c.size(), 2u);
  for (const auto& x : c) {
    EXPECT_TRUE(x.paired);
    EXPECT_EQ(x.welch.test, "paired_t");
    EXPECT_EQ(x.rank.test, "wilcoxon_signed_rank");
    EXPECT_NE(x.welch.note.find("1 participant(s) without an estimate in both conditions left out"), std::string::npos)
        << x.welch.note;
  }
  EXPECT_NEAR(*c[0].welch.statistic, 3.2014270905391591, 1e-12);
  EXPECT_EQ(*c[0].welch.df, 4.0);
  EXPECT_NEAR(*c[0].welch.p_value, 0.032856086700188136, 1e-14);
  EXPECT_NEAR(*c[0].welch.conf_low, 0.026829720040567342, 1e-14);
  EXPECT_NEAR(*c[0].welch.conf_high, 0.37739161419062378, 1e-14);
  ASSERT_TRUE(c[0].welch.log_bf10.has_value());
  EXPECT_NEAR(std::exp(*c[0].welch.log_bf10), 2.9940859116567093, 1e-9);
  EXPECT_EQ(*c[0].rank.statistic, 14.0);
  EXPECT_NEAR(*c[0].rank.p_value, 0.125, 1e-15);
  EXPECT_NEAR(*c[1].welch.statistic, 2.2558335591813887, 1e-12);
  EXPECT_NEAR(*c[1].welch.p_value, 0.087080950102842725, 1e-14);
  EXPECT_EQ(*c[1].rank.statistic, 13.5);
  EXPECT_NEAR(*c[1].rank.p_value, 0.13621686984456766, 1e-14);
}

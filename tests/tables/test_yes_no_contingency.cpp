// The statistics of a yes/no answer across three or more conditions (feint/stats/contingency.hpp)
// against independent computations: Fisher's exact test of the C x 2 table against a brute-force
// enumeration of every table in long double (and against the 2 x 2 test at C = 2), the worked
// examples of docs/yes-no.md computed by hand (chi-square, Cramér's V, Cochran's Q, whose df = 2
// p-values have the closed form exp(-X^2 / 2)), Cramér's V interval against its defining equation,
// and the limit on the tables enumerated. R's numbers on whole questionnaires are in
// test_yes_no_conditions.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <boost/math/distributions/non_central_chi_squared.hpp>

#include "feint/error.hpp"
#include "feint/stats/contingency.hpp"
#include "feint/stats/proportions.hpp"

namespace fs = feint::stats;

namespace {

long double choose(std::size_t n, std::size_t k) {
  long double c = 1;
  for (std::size_t i = 1; i <= k; ++i) c = c * static_cast<long double>(n - k + i) / static_cast<long double>(i);
  return c;
}

// Every table x_1..x_C with the margins, its probability prod C(n_i, x_i) / C(N, m) in long
// double; the p-value sums those no more probable than the observed one (R's tolerance).
double brute_force_p(const std::vector<fs::YesCount>& t) {
  std::size_t big_n = 0, m = 0;
  for (const auto& r : t) big_n += r.n, m += r.yes;
  auto prob = [&](const std::vector<std::size_t>& x) {
    long double p = 1;
    for (std::size_t i = 0; i < t.size(); ++i) p *= choose(t[i].n, x[i]);
    return p / choose(big_n, m);
  };
  std::vector<std::size_t> obs;
  for (const auto& r : t) obs.push_back(r.yes);
  const long double cut = prob(obs) * std::exp(3.45254e-7L);
  long double p = 0;
  std::vector<std::size_t> x(t.size(), 0);
  // Odometer over x_1..x_{C-1}; x_C takes the rest.
  while (true) {
    std::size_t used = 0;
    for (std::size_t i = 0; i + 1 < t.size(); ++i) used += x[i];
    if (used <= m && m - used <= t.back().n) {
      x.back() = m - used;
      const long double q = prob(x);
      if (q <= cut) p += q;
    }
    std::size_t i = 0;
    while (i + 1 < t.size() && x[i] == t[i].n) x[i++] = 0;
    if (i + 1 == t.size()) break;
    ++x[i];
  }
  return static_cast<double>(std::min(1.0L, p));
}

}  // namespace

TEST(FisherConditions, EqualsTheEnumerationOfEveryTable) {
  const std::vector<std::vector<fs::YesCount>> tables = {
      {{9, 12}, {5, 12}, {3, 12}},            // docs/yes-no.md's worked example
      {{0, 7}, {7, 7}, {3, 9}, {2, 4}},       // the ends of the support, unequal sizes
      {{4, 4}, {0, 6}, {3, 5}, {1, 3}, {2, 6}},
      {{10, 30}, {18, 26}, {12, 34}},         // many tables
      {{6, 10}, {6, 10}, {6, 10}},            // the observed table is the most probable: p = 1
      {{1, 3}, {0, 0}, {2, 5}, {1, 2}},       // a condition without answers counts for nothing
      {{12, 20}, {5, 20}},                    // two conditions: the 2 x 2 test
  };
  for (const auto& t : tables) {
    const auto r = fs::fisher_exact_conditions(t);
    ASSERT_TRUE(r.computed) << r.note;
    const double want = brute_force_p(t);
    EXPECT_NEAR(*r.p_value, want, 1e-13 * std::max(want, 1e-3)) << t.size() << " rows, first " << t[0].yes;
  }
  // C = 2 is the 2 x 2 test of proportions.hpp (R: 0.053550992594374118).
  EXPECT_NEAR(*fs::fisher_exact_conditions(std::vector<fs::YesCount>{{12, 20}, {5, 20}}).p_value,
              *fs::fisher_exact({12, 20, 5, 20}).p_value, 1e-15);
  // The worked example: 126 tables, 96 of them no more probable than the observed; R's FEXACT
  // gives 0.065282335790630225.
  EXPECT_NEAR(*fs::fisher_exact_conditions(tables[0]).p_value, 0.065282335790630225, 1e-15);
  EXPECT_DOUBLE_EQ(*fs::fisher_exact_conditions(tables[4]).p_value, 1.0);
}

TEST(FisherConditions, TooManyTablesAreRefusedWithTheReasonAndNotGuessed) {
  const std::vector<fs::YesCount> t = {{10, 30}, {18, 26}, {12, 34}, {9, 20}};
  // The two largest rows (30, 34) are summed in closed form; the others (20, 26) allow at most
  // 21 x 27 splits of the yes answers.
  const auto r = fs::fisher_exact_conditions(t, 100);
  EXPECT_FALSE(r.computed);
  EXPECT_NE(r.note.find("more than feint's limit of 100"), std::string::npos) << r.note;
  EXPECT_NE(r.note.find("read the chi-square test"), std::string::npos) << r.note;
  EXPECT_TRUE(fs::fisher_exact_conditions(t, 1000).computed);
  EXPECT_FALSE(fs::fisher_exact_conditions(std::vector<fs::YesCount>{{3, 5}, {0, 0}}).computed);
  EXPECT_THROW(fs::fisher_exact_conditions(std::vector<fs::YesCount>{{6, 5}, {1, 2}, {1, 2}}), feint::UsageError);
}

TEST(ChiSquareConditions, WorkedExampleByHand) {
  // 9, 5 and 3 yes of 12: E = 12 * 17 / 36 = 5.667 yes and 6.333 no per row;
  // X^2 = (sum of (O - E)^2 / E) = 6.2414860681114543 (R), df 2, p = exp(-X^2 / 2).
  const std::vector<fs::YesCount> t = {{9, 12}, {5, 12}, {3, 12}};
  const auto r = fs::chisq_independence(t);
  ASSERT_TRUE(r.computed);
  const double e_yes = 12.0 * 17 / 36, e_no = 12.0 * 19 / 36;
  double x2 = 0;
  for (const double o : {9.0, 5.0, 3.0}) x2 += (o - e_yes) * (o - e_yes) / e_yes + (o - e_yes) * (o - e_yes) / e_no;
  EXPECT_NEAR(*r.statistic, x2, 1e-14);
  EXPECT_NEAR(*r.statistic, 6.2414860681114543, 1e-14);
  EXPECT_EQ(*r.df, 2.0);
  EXPECT_NEAR(*r.p_value, std::exp(-x2 / 2), 1e-16);
  // Bias-corrected V: phi^2 = X^2 / 36 less 2 / 35, over min(3 - 4/35, 2 - 1/35) - 1 = 34/35.
  EXPECT_NEAR(*r.estimate, std::sqrt((x2 / 36 - 2.0 / 35) / (34.0 / 35)), 1e-15);
  EXPECT_EQ(*r.conf_high, 1.0);
  EXPECT_TRUE(r.note.empty());  // every expected count >= 5
  EXPECT_FALSE(fs::chisq_independence(std::vector<fs::YesCount>{{4, 4}, {6, 6}, {2, 2}}).computed);  // all yes
  EXPECT_NE(fs::chisq_independence(std::vector<fs::YesCount>{{3, 4}, {1, 6}, {2, 2}}).note.find("below 5"),
            std::string::npos);
}

TEST(CramersV, IntervalSolvesItsDefiningEquation) {
  const double x2 = 14.2, df = 2;
  const std::size_t n = 120;
  for (const bool adjust : {true, false}) {
    const auto one = fs::cramers_v(x2, n, 3, 2, adjust);
    const auto two = fs::cramers_v(x2, n, 3, 2, adjust, 0.95, fs::Alternative::two_sided);
    // Back from V to the ncp: phi^2 = ncp / n (plus the correction), V = phi / div.
    const double k = adjust ? 3 - 4.0 / (n - 1) : 3, l = adjust ? 2 - 1.0 / (n - 1) : 2;
    const double div2 = std::min(k, l) - 1;
    auto ncp = [&](double v) { return n * (v * v * div2 + (adjust ? df / (n - 1) : 0)); };
    auto pchisq = [&](double c) { return boost::math::cdf(boost::math::non_central_chi_squared(df, c), x2); };
    EXPECT_NEAR(pchisq(ncp(one.low)), 0.95, 1e-12);  // one-sided 95 %: pchisq = 1 - 0.05
    EXPECT_EQ(one.high, 1.0);
    EXPECT_NEAR(pchisq(ncp(two.low)), 0.975, 1e-12);
    EXPECT_NEAR(pchisq(ncp(two.high)), 0.025, 1e-12);
    EXPECT_NEAR(one.estimate, std::sqrt((x2 / n - (adjust ? df / (n - 1) : 0)) / div2), 1e-15);
  }
  // Below the central quantile the lower bound is 0 (effectsize's rule).
  EXPECT_EQ(fs::cramers_v(1.0, 50, 3, 2).low, 0.0);
  EXPECT_THROW(fs::cramers_v(1.0, 50, 3, 2, true, 0.95, fs::Alternative::less), feint::UsageError);
}

TEST(CochranQ, WorkedExampleByHand) {
  // docs/yes-no.md: six participants, three conditions. G = (5, 3, 1), N = 9, L = (2, 1, 3, 1, 0, 2):
  // Q = 2 (3 * 35 - 81) / (3 * 9 - 19) = 48 / 8 = 6, df 2, p = exp(-3) (R: friedman.test gives 6).
  const std::vector<std::vector<int>> answers = {{1, 1, 0}, {1, 0, 0}, {1, 1, 1}, {1, 0, 0}, {0, 0, 0}, {1, 1, 0}};
  const auto r = fs::cochran_q(answers);
  ASSERT_TRUE(r.computed);
  EXPECT_EQ(*r.statistic, 6.0);
  EXPECT_EQ(*r.df, 2.0);
  EXPECT_NEAR(*r.p_value, std::exp(-3.0), 1e-16);
  EXPECT_EQ(r.n1, 6u);
  // Everybody answered alike in every condition: nothing to test.
  EXPECT_FALSE(fs::cochran_q(std::vector<std::vector<int>>{{1, 1, 1}, {0, 0, 0}}).computed);
  EXPECT_THROW(fs::cochran_q(std::vector<std::vector<int>>{{1, 1, 1}, {0, 0}}), feint::InvalidData);
  // Two conditions: Q is McNemar's statistic without correction, (b - c)^2 / (b + c).
  const std::vector<std::vector<int>> two = {{1, 0}, {1, 0}, {1, 0}, {0, 1}, {1, 1}, {0, 0}};
  EXPECT_NEAR(*fs::cochran_q(two).statistic, (3.0 - 1) * (3.0 - 1) / 4, 1e-15);
}

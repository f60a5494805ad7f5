// Friedman's rank sum test and Kendall's W (feint/stats/rank_tests.hpp) against hand computation
// and R; McNemar's test, exact and chi-square (feint/stats/paired_proportions.hpp), against R.
// The R golden values of whole questionnaires are in tests/tables/test_likert_within.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "feint/stats/paired_proportions.hpp"
#include "feint/stats/rank_tests.hpp"

namespace fs = feint::stats;

namespace {
const double kNaN = std::numeric_limits<double>::quiet_NaN();
}

TEST(Friedman, HandComputedWithoutTies) {
  // 4 blocks x 3 conditions, ranks per block (1 2 3), (1 3 2), (1 2 3), (2 1 3): R_j = 5, 8, 11;
  // X2 = 12 ((5 - 8)^2 + 0 + (11 - 8)^2) / (4 * 3 * 4) = 216 / 48 = 4.5; p = exp(-4.5 / 2).
  const std::vector<std::vector<double>> y{{1, 2, 3}, {10, 30, 20}, {0.5, 0.7, 0.9}, {5, 4, 6}};
  const auto r = fs::friedman_test(y);
  ASSERT_TRUE(r.computed);
  EXPECT_EQ(r.test, "friedman");
  EXPECT_NEAR(*r.statistic, 4.5, 1e-14);
  EXPECT_EQ(*r.df, 2.0);
  EXPECT_NEAR(*r.p_value, std::exp(-2.25), 1e-15);
  EXPECT_EQ(r.n1, 4u);
  EXPECT_NEAR(*fs::kendalls_w(r), 4.5 / 8.0, 1e-15);
}

TEST(Friedman, TiesWithinABlockAreCorrectedAsR) {
  // R: friedman.test(rbind(c(1, 1, 2), c(1, 2, 3), c(2, 3, 3), c(1, 3, 2), c(NA, 1, 2)))
  //   Friedman chi-squared = 5.57142857142857, df = 2, p-value = 0.061685012567976 (NA block dropped).
  // By hand: ranks (1.5 1.5 3), (1 2 3), (1 2.5 2.5), (1 3 2): R_j = 4.5, 9, 10.5 around n(k+1)/2 = 8:
  // 12.25 + 1 + 6.25 = 19.5; two tie pairs, sum(t^3 - t) = 12; denominator 4*3*4 - 12/2 = 42.
  const std::vector<std::vector<double>> y{{1, 1, 2}, {1, 2, 3}, {2, 3, 3}, {1, 3, 2}, {kNaN, 1, 2}};
  const auto r = fs::friedman_test(y);
  ASSERT_TRUE(r.computed);
  EXPECT_NEAR(*r.statistic, 12.0 * 19.5 / 42.0, 1e-13);
  EXPECT_NEAR(*r.p_value, 0.061685012567976, 1e-14);
  EXPECT_EQ(r.n1, 4u);
  EXPECT_NE(r.note.find("1 participant(s)"), std::string::npos);
}

TEST(Friedman, CannotComputeDegenerateInput) {
  EXPECT_FALSE(fs::friedman_test(std::vector<std::vector<double>>{}).computed);
  EXPECT_FALSE(fs::friedman_test(std::vector<std::vector<double>>{{1}, {2}}).computed);
  EXPECT_FALSE(fs::friedman_test(std::vector<std::vector<double>>{{1, kNaN}, {kNaN, 2}}).computed);
  const auto tied = fs::friedman_test(std::vector<std::vector<double>>{{3, 3, 3}, {5, 5, 5}});
  EXPECT_FALSE(tied.computed);
  EXPECT_FALSE(fs::kendalls_w(tied).has_value());
}

TEST(McNemar, ExactAndChiSquareEqualR) {
  // b = 9, c = 2 of 25 pairs. R: binom.test(9, 11)$p.value = 0.065429687500000042, conf.int
  // [0.48224414763982737, 0.97716880170004039]; mcnemar.test(matrix(c(10, 2, 9, 4), 2)):
  // McNemar's chi-squared = 3.2727272727272729, p-value = 0.070440429272088212.
  const fs::PairedYesNoTable t{10, 9, 2, 4};
  const auto e = fs::mcnemar_exact(t);
  ASSERT_TRUE(e.computed);
  EXPECT_NEAR(*e.p_value, 0.065429687500000042, 1e-15);
  EXPECT_NEAR(*e.estimate, 4.5, 1e-15);
  EXPECT_NEAR(*e.conf_low, 0.48224414763982737 / (1 - 0.48224414763982737), 1e-12);
  EXPECT_NEAR(*e.conf_high, 0.97716880170004039 / (1 - 0.97716880170004039), 1e-9);
  EXPECT_NEAR(*e.mean1, 19.0 / 25.0, 1e-15);
  EXPECT_NEAR(*e.mean2, 12.0 / 25.0, 1e-15);
  const auto c = fs::mcnemar_test(t);
  EXPECT_NEAR(*c.statistic, 3.2727272727272729, 1e-14);
  EXPECT_NEAR(*c.p_value, 0.070440429272088212, 1e-14);
  EXPECT_NEAR(*c.estimate, 7.0 / 25.0, 1e-15);
  // One-sided, greater: binom.test(9, 11, alternative = "greater")$p.value = 0.032714843750000021.
  fs::TestOptions greater;
  greater.alternative = fs::Alternative::greater;
  EXPECT_NEAR(*fs::mcnemar_exact(t, greater).p_value, 0.032714843750000021, 1e-15);
}

TEST(McNemar, BalancedAndEmptyDiscordantPairs) {
  // b = c = 3: binom.test p = 1; mcnemar.test(matrix(c(4, 3, 3, 5), 2)) X2 = 0 (R corrects only
  // an asymmetric table), p = 1.
  const fs::PairedYesNoTable even{4, 3, 3, 5};
  EXPECT_DOUBLE_EQ(*fs::mcnemar_exact(even).p_value, 1.0);
  EXPECT_EQ(*fs::mcnemar_test(even).statistic, 0.0);
  EXPECT_EQ(*fs::mcnemar_test(even).p_value, 1.0);
  const fs::PairedYesNoTable none{6, 0, 0, 4};
  EXPECT_FALSE(fs::mcnemar_exact(none).computed);
  EXPECT_FALSE(fs::mcnemar_test(none).computed);
  // b = 0, c = 5: binom.test(0, 5)$p.value = 0.0625, odds ratio 0 with interval [0, ...).
  const auto zero = fs::mcnemar_exact(fs::PairedYesNoTable{1, 0, 5, 1});
  EXPECT_NEAR(*zero.p_value, 0.0625, 1e-15);
  EXPECT_EQ(*zero.estimate, 0.0);
  EXPECT_EQ(*zero.conf_low, 0.0);
}

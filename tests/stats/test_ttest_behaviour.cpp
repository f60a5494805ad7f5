// t-test and TOST behaviour beyond the R golden values: input checks, missing values, the Hedges
// correction, the TOST decision and tiny p-values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "feint/error.hpp"
#include "feint/stats/ttest.hpp"

namespace fs = feint::stats;

TEST(HedgesG, UsesTheExactGammaCorrection) {
  // J(df) = Gamma(df/2) / (sqrt(df/2) Gamma((df-1)/2)); for df = 4: Gamma(2) / (sqrt 2 Gamma(1.5))
  // = 1 / (sqrt(2) * sqrt(pi) / 2) = 0.7978845608028654.
  const std::vector<double> x = {1.0, 2.0, 4.0, 3.5, 6.0};
  const auto r = fs::t_test_one_sample(x, 0.0);
  ASSERT_TRUE(r.cohen_d && r.hedges_g);
  EXPECT_NEAR(*r.hedges_g / *r.cohen_d, 0.7978845608028654, 1e-15);
  // Large df: J -> 1 - 3 / (4 df - 1) (Hedges' approximation, error ~8e-9 at df = 2000), still
  // finite (Gamma itself would overflow).
  std::vector<double> big(2001);
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = std::sin(static_cast<double>(i)) + 0.1;
  const auto b = fs::t_test_one_sample(big, 0.0);
  ASSERT_TRUE(b.hedges_g.has_value());
  EXPECT_NEAR(*b.hedges_g / *b.cohen_d, 1 - 3.0 / (4 * 2000.0 - 1), 1e-8);
  // df = 1: J undefined (Gamma(0)); g stays empty rather than 0.
  const std::vector<double> two = {1.0, 2.0};
  const auto t = fs::t_test_one_sample(two, 0.0);
  EXPECT_TRUE(t.cohen_d.has_value());
  EXPECT_FALSE(t.hedges_g.has_value());
}

TEST(OneSampleT, DropsMissingValuesAsR) {
  const std::vector<double> with_nan = {0.4, std::nan(""), 0.6, 0.7};
  const std::vector<double> without = {0.4, 0.6, 0.7};
  const auto a = fs::t_test_one_sample(with_nan, 0.5);
  const auto b = fs::t_test_one_sample(without, 0.5);
  EXPECT_EQ(a.n1, 3u);
  EXPECT_EQ(*a.statistic, *b.statistic);
}

TEST(OneSampleT, TinyPValueIsNotRoundedToZero) {
  std::vector<double> x(200);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 10.0 + std::sin(static_cast<double>(i));
  const auto r = fs::t_test_one_sample(x, 0.0, {fs::Alternative::greater, 0.95});
  ASSERT_TRUE(r.computed);
  EXPECT_GT(*r.p_value, 0.0);
  EXPECT_LT(*r.p_value, 1e-150);
  const auto less = fs::t_test_one_sample(x, 0.0, {fs::Alternative::less, 0.95});
  EXPECT_EQ(*less.p_value, 1.0);
}

TEST(PairedT, MismatchedLengthsAreInvalidData) {
  const std::vector<double> x = {1, 2, 3}, y = {1, 2};
  EXPECT_THROW(fs::t_test_paired(x, y), feint::InvalidData);
}

TEST(PairedT, DropsIncompletePairsAndReportsBothConditions) {
  const std::vector<double> x = {1.0, 2.0, std::nan(""), 4.0, 3.0};
  const std::vector<double> y = {0.5, 2.5, 1.0, 3.0, 2.0};
  const auto r = fs::t_test_paired(x, y);
  EXPECT_EQ(r.n1, 4u);
  EXPECT_EQ(r.n2, 4u);
  EXPECT_DOUBLE_EQ(*r.mean1, 2.5);
  EXPECT_DOUBLE_EQ(*r.mean2, 2.0);
  EXPECT_DOUBLE_EQ(*r.estimate, 0.5);
  EXPECT_EQ(r.test, "paired_t");
}

TEST(TwoSampleT, EmptyGroupIsNotComputable) {
  const std::vector<double> x = {1, 2, 3}, none;
  for (const auto& r : {fs::t_test_welch(x, none), fs::t_test_student(none, x)}) {
    EXPECT_FALSE(r.computed);
    EXPECT_NE(r.note.find("empty group"), std::string::npos);
  }
}

TEST(TTest, RejectsConfLevelOutsideUnitInterval) {
  const std::vector<double> x = {1, 2, 3};
  EXPECT_THROW(fs::t_test_one_sample(x, 0, {fs::Alternative::two_sided, 1.0}), feint::UsageError);
  EXPECT_THROW(fs::t_test_welch(x, x, {fs::Alternative::two_sided, -0.1}), feint::UsageError);
}

TEST(Tost, EquivalentExactlyWhenTheIntervalLiesInsideTheMargin) {
  std::vector<double> x(40);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 0.5 + 0.05 * std::sin(static_cast<double>(i) * 1.7);
  for (double delta : {0.005, 0.01, 0.02, 0.05}) {
    const auto r = fs::tost_one_sample(x, 0.5, delta);
    ASSERT_TRUE(r.computed);
    EXPECT_EQ(r.test, "tost");
    EXPECT_DOUBLE_EQ(*r.margin, delta);
    EXPECT_NEAR(r.conf_level, 0.90, 1e-15);  // 1 - 2 alpha
    const bool inside = *r.conf_low > 0.5 - delta && *r.conf_high < 0.5 + delta;
    EXPECT_EQ(*r.p_value < 0.05, inside) << "delta " << delta;
  }
}

TEST(Tost, RejectsBadMarginAndConfLevel) {
  const std::vector<double> x = {1, 2, 3};
  EXPECT_THROW(fs::tost_one_sample(x, 2, 0.0), feint::UsageError);
  EXPECT_THROW(fs::tost_one_sample(x, 2, -1), feint::UsageError);
  EXPECT_THROW(fs::tost_paired(x, x, 1, {fs::Alternative::two_sided, 0.5}), feint::UsageError);
}

TEST(Tost, ConstantDataIsNotComputable) {
  const std::vector<double> c = {0.5, 0.5, 0.5, 0.5};
  const auto r = fs::tost_one_sample(c, 0.5, 0.1);
  EXPECT_FALSE(r.computed);
  EXPECT_EQ(r.note, "data are essentially constant");
  EXPECT_FALSE(r.p_value.has_value());
}

TEST(TTest, InfiniteValuesAreNotComputableRatherThanThrowing) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> x = {1, 2, inf}, y = {1, 2, 3};
  for (const auto& r : {fs::t_test_one_sample(x, 0), fs::t_test_welch(x, y), fs::t_test_student(y, x),
                        fs::t_test_paired(x, y)}) {
    EXPECT_FALSE(r.computed) << r.test;
    EXPECT_FALSE(r.note.empty());
  }
}

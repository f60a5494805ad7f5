// Hand-picked t-test and p.adjust cases checked against R 4.2 (values printed with %.17g by the
// R calls quoted beside each case). The full golden suite is test_ttest_golden.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "feint/error.hpp"
#include "feint/stats/p_adjust.hpp"
#include "feint/stats/ttest.hpp"

namespace fs = feint::stats;

namespace {

const std::vector<double> kX = {0.52, 0.61, 0.47, 0.55, 0.70, 0.58};
const std::vector<double> kY = {0.41, 0.50, 0.44, 0.39, 0.52};

void expect_rel(double got, double want, double tol = 1e-12) {
  EXPECT_NEAR(got, want, tol * std::fabs(want)) << "want " << want;
}

}  // namespace

TEST(OneSampleT, MatchesRTTest) {
  // t.test(x, mu = 0.5)
  const auto r = fs::t_test_one_sample(kX, 0.5);
  ASSERT_TRUE(r.computed) << r.note;
  expect_rel(*r.statistic, 2.2122666826280626);
  expect_rel(*r.df, 5);
  expect_rel(*r.p_value, 0.077882052339840691);
  expect_rel(*r.conf_low, 0.48839233405542576);
  expect_rel(*r.conf_high, 0.65494099927790761);
  EXPECT_EQ(r.method, "One Sample t-test");
  EXPECT_EQ(r.statistic_name, "t");
}

TEST(WelchT, MatchesRTTest) {
  // t.test(x, y)
  const auto r = fs::t_test_welch(kX, kY);
  ASSERT_TRUE(r.computed) << r.note;
  expect_rel(*r.statistic, 2.9165793695350444);
  expect_rel(*r.df, 8.835337755964753);
  expect_rel(*r.p_value, 0.017458148028381647);
  expect_rel(*r.conf_low, 0.026586460263854111);
  expect_rel(*r.conf_high, 0.21274687306947918);
  EXPECT_EQ(r.method, "Welch Two Sample t-test");
}

TEST(StudentT, MatchesRTTest) {
  // t.test(x, y, var.equal = TRUE)
  const auto r = fs::t_test_student(kX, kY);
  ASSERT_TRUE(r.computed) << r.note;
  expect_rel(*r.statistic, 2.8211606049571603);
  expect_rel(*r.df, 9);
  expect_rel(*r.p_value, 0.020009057326681342);
  expect_rel(*r.conf_low, 0.023711545688257892);
  expect_rel(*r.conf_high, 0.21562178764507539);
}

TEST(PairedT, MatchesRTTestOneSidedLess) {
  // t.test(x[1:5], y, paired = TRUE, alternative = "less", conf.level = 0.9)
  const std::vector<double> x5(kX.begin(), kX.begin() + 5);
  const auto r = fs::t_test_paired(x5, kY, {fs::Alternative::less, 0.9});
  ASSERT_TRUE(r.computed) << r.note;
  expect_rel(*r.statistic, 4.5451901730509379);
  expect_rel(*r.df, 4);
  expect_rel(*r.p_value, 0.99477212213715227);
  EXPECT_EQ(*r.conf_low, -std::numeric_limits<double>::infinity());
  expect_rel(*r.conf_high, 0.15780434997233894);
}

TEST(OneSampleT, ConstantDataIsNotComputable) {
  const std::vector<double> c = {0.5, 0.5, 0.5};
  const auto r = fs::t_test_one_sample(c, 0.5);
  EXPECT_FALSE(r.computed);
  EXPECT_EQ(r.note, "data are essentially constant");
  EXPECT_FALSE(r.p_value.has_value());
  const std::vector<double> one = {0.5};
  EXPECT_FALSE(fs::t_test_one_sample(one, 0.5).computed);
}

TEST(PAdjust, HommelAndBYMatchRWithNA) {
  // p.adjust(c(0.01, 0.02, 0.03, 0.04, 0.05, NA), "hommel" / "BY")
  const std::vector<std::optional<double>> p = {0.01, 0.02, 0.03, 0.04, 0.05, std::nullopt};
  const auto h = fs::p_adjust(p, fs::PAdjustMethod::hommel);
  const double want_h[] = {0.049999999999999996, 0.05000000000000001, 0.05000000000000001,
                           0.05000000000000001, 0.05000000000000001};
  for (int i = 0; i < 5; ++i) expect_rel(*h[i], want_h[i], 1e-15);
  EXPECT_FALSE(h[5].has_value());
  const auto by = fs::p_adjust(p, fs::PAdjustMethod::BY);
  const double want_by[] = {0.11416666666666665, 0.11416666666666665, 0.11416666666666665,
                            0.11416666666666667, 0.11416666666666667};
  for (int i = 0; i < 5; ++i) expect_rel(*by[i], want_by[i], 1e-15);
  EXPECT_FALSE(by[5].has_value());
}

TEST(PAdjust, ParsesRNamesAndRejectsOthers) {
  EXPECT_EQ(fs::parse_p_adjust("fdr"), fs::PAdjustMethod::BH);
  EXPECT_EQ(fs::to_string(fs::parse_p_adjust("hommel")), "hommel");
  EXPECT_THROW(fs::parse_p_adjust("sidak"), feint::UsageError);
}

// Mann–Whitney (Wilcoxon rank-sum) test against hand counts and R 4.2's wilcox.test (values in
// comments printed by Rscript with sprintf("%.17g")); the golden suite is in test_rank_golden.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "feint/stats/rank_tests.hpp"

namespace fs = feint::stats;

namespace {

void expect_rel(double actual, double expected, double rel = 1e-10) {
  EXPECT_NEAR(actual, expected, rel * std::fabs(expected)) << "expected " << expected;
}

const std::vector<double> kX{0.8, 0.83, 1.89, 1.04, 1.45, 1.38, 1.91, 1.64, 0.73, 1.46};
const std::vector<double> kY{1.15, 0.88, 0.90, 0.74, 1.21};

}  // namespace

TEST(RankSumDistribution, MatchesHandCounts) {
  // m = 2, n = 2: W takes 0,1,2,2,3,4 over the C(4,2) = 6 arrangements.
  EXPECT_DOUBLE_EQ(fs::detail::pwilcox(0, 2, 2, true), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(fs::detail::pwilcox(2, 2, 2, true), 4.0 / 6.0);
  EXPECT_DOUBLE_EQ(fs::detail::pwilcox(2, 2, 2, false), 2.0 / 6.0);
  EXPECT_DOUBLE_EQ(fs::detail::pwilcox(3, 2, 2, false), 1.0 / 6.0);
  // m = 1: W is uniform on 0..n.
  EXPECT_DOUBLE_EQ(fs::detail::pwilcox(3, 1, 9, true), 0.4);
  // pwilcox(2, 10, 12) = 6.1857646996965881e-06 in R (4 arrangements of C(22,10) = 646646).
  expect_rel(fs::detail::pwilcox(2, 10, 12, true), 6.1857646996965881e-06, 1e-14);
  expect_rel(fs::detail::pwilcox(117, 10, 12, false), 6.1857646996965881e-06, 1e-14);
  EXPECT_DOUBLE_EQ(fs::detail::pwilcox(2, 12, 10, true), fs::detail::pwilcox(2, 10, 12, true));
}

TEST(RankSumDistribution, TailsAddToOne) {
  for (auto [m, n] : {std::pair<std::size_t, std::size_t>{1, 1}, {3, 7}, {12, 5}, {49, 49}}) {
    const double top = static_cast<double>(m * n);
    const double step = m * n > 100 ? 97.0 : 1.0;  // each call builds the whole distribution
    for (double q = -1; q <= top; q += step)
      EXPECT_NEAR(fs::detail::pwilcox(q, m, n, true) + fs::detail::pwilcox(q, m, n, false), 1.0,
                  1e-13);
  }
}

TEST(MannWhitney, ExactMatchesR) {
  // wilcox.test(kX, kY): W = 35, p = 0.2544122544122544
  const auto r = fs::mann_whitney(kX, kY);
  ASSERT_TRUE(r.computed) << r.note;
  EXPECT_EQ(r.method, "Wilcoxon rank sum exact test");
  EXPECT_EQ(r.statistic_name, "W");
  EXPECT_EQ(*r.statistic, 35.0);
  expect_rel(*r.p_value, 0.2544122544122544);
  EXPECT_TRUE(*r.exact);
  EXPECT_EQ(r.n1, 10u);
  EXPECT_EQ(r.n2, 5u);
  EXPECT_DOUBLE_EQ(*r.rank_biserial, 2.0 * 35.0 / 50.0 - 1.0);
  EXPECT_DOUBLE_EQ(*r.median2, 0.90);
  EXPECT_DOUBLE_EQ(*r.mean2, (1.15 + 0.88 + 0.90 + 0.74 + 1.21) / 5.0);
  EXPECT_EQ(*r.mu, 0.0);
}

TEST(MannWhitney, SwappingSamplesFlipsWAndRankBiserial) {
  // wilcox.test(kY, kX, alternative = "less"): W = 15, p = 0.1272061272061272
  const auto a = fs::mann_whitney(kX, kY, {fs::Alternative::greater, 0.95});
  const auto b = fs::mann_whitney(kY, kX, {fs::Alternative::less, 0.95});
  EXPECT_EQ(*b.statistic, 15.0);
  EXPECT_EQ(*a.statistic + *b.statistic, 50.0);
  EXPECT_DOUBLE_EQ(*a.rank_biserial, -*b.rank_biserial);
  expect_rel(*b.p_value, 0.1272061272061272);
  EXPECT_DOUBLE_EQ(*a.p_value, *b.p_value);
}

TEST(MannWhitney, TiesUseCorrectedNormalApproximation) {
  // wilcox.test(c(1,2,2,3,4), c(2,3,3,5,6,7)): W = 6, p = 0.11390314458853068 (warning: ties)
  const std::vector<double> x{1, 2, 2, 3, 4};
  const std::vector<double> y{2, 3, 3, 5, 6, 7};
  const auto r = fs::mann_whitney(x, y);
  EXPECT_EQ(r.method, "Wilcoxon rank sum test with continuity correction");
  EXPECT_FALSE(*r.exact);
  EXPECT_EQ(*r.statistic, 6.0);
  expect_rel(*r.p_value, 0.11390314458853068);
  EXPECT_EQ(r.note, "cannot compute exact p-value with ties");
  EXPECT_LT(*r.rank_biserial, 0.0);  // x tends to be smaller
}

TEST(MannWhitney, CannotComputeEmptyOrAllTied) {
  const std::vector<double> ones{1, 1};
  const auto tied = fs::mann_whitney(ones, ones);  // R: W = 2, p-value NaN
  EXPECT_FALSE(tied.computed);
  EXPECT_FALSE(tied.p_value.has_value());
  EXPECT_NE(tied.note.find("tied"), std::string::npos);

  const std::vector<double> empty;
  EXPECT_FALSE(fs::mann_whitney(empty, ones).computed);
  EXPECT_FALSE(fs::mann_whitney(ones, empty).computed);
  EXPECT_NE(fs::mann_whitney(ones, empty).note.find("'y'"), std::string::npos);
}

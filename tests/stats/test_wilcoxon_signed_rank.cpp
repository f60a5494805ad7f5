// Wilcoxon signed-rank test against hand counts and R 4.2's wilcox.test (values in comments were
// printed by Rscript with sprintf("%.17g")); the full golden suite is in test_rank_golden.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "feint/stats/rank_tests.hpp"

namespace fs = feint::stats;

namespace {

void expect_rel(double actual, double expected, double rel = 1e-10) {
  EXPECT_NEAR(actual, expected, rel * std::fabs(expected)) << "expected " << expected;
}

}  // namespace

TEST(SignRankDistribution, MatchesHandCountedSubsets) {
  // Subsets of {1..10} with sum <= 3: {}, {1}, {2}, {3}, {1,2} -> 5 / 2^10.
  EXPECT_EQ(fs::detail::psignrank(3, 10, true), 5.0 / 1024.0);
  // Upper tail P(V > 51) = P(V >= 52) = P(V <= 3) by symmetry (S = 55).
  EXPECT_EQ(fs::detail::psignrank(51, 10, false), 5.0 / 1024.0);
  EXPECT_EQ(fs::detail::psignrank(-1, 10, true), 0.0);
  EXPECT_EQ(fs::detail::psignrank(55, 10, true), 1.0);
  EXPECT_EQ(fs::detail::psignrank(55, 10, false), 0.0);
}

TEST(SignRankDistribution, TailsAddToOneAndKeepTinyTails) {
  for (std::size_t n : {1u, 2u, 7u, 20u, 49u}) {
    const double s = static_cast<double>(n * (n + 1) / 2);
    const double step = n > 20 ? 13.0 : 1.0;  // each call builds the whole distribution
    for (double q = -1; q <= s; q += step)
      EXPECT_NEAR(fs::detail::psignrank(q, n, true) + fs::detail::psignrank(q, n, false), 1.0, 1e-15);
  }
  // n = 49: P(V = 0) = 2^-49 exactly, and P(V > S - 1) is the same single outcome.
  EXPECT_EQ(fs::detail::psignrank(0, 49, true), std::ldexp(1.0, -49));
  EXPECT_EQ(fs::detail::psignrank(49.0 * 50.0 / 2.0 - 1.0, 49, false), std::ldexp(1.0, -49));
}

TEST(WilcoxonSignedRank, ExactMatchesR) {
  // wilcox.test(c(1.83,0.50,1.62,2.48,1.68,1.88,1.55,3.06,1.30), mu = 1): V = 43, p = 0.01171875
  const std::vector<double> x{1.83, 0.50, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30};
  const auto r = fs::wilcoxon_signed_rank(x, 1.0);
  ASSERT_TRUE(r.computed) << r.note;
  EXPECT_EQ(r.method, "Wilcoxon signed rank exact test");
  EXPECT_EQ(r.statistic_name, "V");
  EXPECT_EQ(*r.statistic, 43.0);
  EXPECT_EQ(*r.p_value, 0.01171875);  // 2 * 6/512
  EXPECT_TRUE(*r.exact);
  EXPECT_EQ(r.n1, 9u);
  EXPECT_DOUBLE_EQ(*r.rank_biserial, (43.0 - 2.0) / 45.0);
  EXPECT_DOUBLE_EQ(*r.median1, 1.68);
  EXPECT_EQ(*r.mu, 1.0);
  EXPECT_FALSE(r.conf_low.has_value());
  EXPECT_TRUE(r.note.empty());
}

TEST(WilcoxonSignedRank, LikertTiesAndZerosUseCorrectedNormalApproximation) {
  // wilcox.test(c(4,5,6,7,3,6,7,5,4,6), mu = 4): V = 34, p = 0.028179654910788273, warnings for
  // ties and zeroes.
  const std::vector<double> x{4, 5, 6, 7, 3, 6, 7, 5, 4, 6};
  const auto r = fs::wilcoxon_signed_rank(x, 4.0);
  ASSERT_TRUE(r.computed);
  EXPECT_EQ(r.method, "Wilcoxon signed rank test with continuity correction");
  EXPECT_FALSE(*r.exact);
  EXPECT_EQ(*r.statistic, 34.0);
  expect_rel(*r.p_value, 0.028179654910788273);
  EXPECT_NE(r.note.find("cannot compute exact p-value with ties"), std::string::npos);
  EXPECT_NE(r.note.find("cannot compute exact p-value with zeroes"), std::string::npos);
  EXPECT_NE(r.note.find("2 of 10"), std::string::npos);
  EXPECT_EQ(r.n1, 10u);
  // 8 non-zero differences: S = 36, r = (34 - 2) / 36.
  EXPECT_DOUBLE_EQ(*r.rank_biserial, 32.0 / 36.0);

  // alternative = "greater", mu = 3.5 (the paper's reference): V = 53, p = 0.0051595949540174544
  const auto g = fs::wilcoxon_signed_rank(x, 3.5, {fs::Alternative::greater, 0.95});
  EXPECT_EQ(*g.statistic, 53.0);
  expect_rel(*g.p_value, 0.0051595949540174544);
  EXPECT_EQ(g.note, "cannot compute exact p-value with ties");
}

TEST(WilcoxonSignedRank, SmallPValueStaysAccurate) {
  // wilcox.test(1:30, mu = -1): V = 465, p = 2 / 2^30 = 1.8626451492309587e-09
  std::vector<double> x;
  for (int i = 1; i <= 30; ++i) x.push_back(i);
  const auto r = fs::wilcoxon_signed_rank(x, -1.0);
  EXPECT_EQ(*r.statistic, 465.0);
  EXPECT_EQ(*r.p_value, std::ldexp(1.0, -29));
  EXPECT_EQ(*r.rank_biserial, 1.0);
  const auto less = fs::wilcoxon_signed_rank(x, -1.0, {fs::Alternative::less, 0.95});
  EXPECT_EQ(*less.p_value, 1.0);
}

TEST(WilcoxonSignedRank, MirroringTheDataFlipsVAndTheSignOfR) {
  const std::vector<double> x{2.1, -0.4, 3.3, 1.7, 0.9, 4.2, -1.1, 2.8};
  std::vector<double> mirrored;
  for (double v : x) mirrored.push_back(-v);
  const auto a = fs::wilcoxon_signed_rank(x, 0.5);
  const auto b = fs::wilcoxon_signed_rank(mirrored, -0.5);
  EXPECT_EQ(*a.statistic + *b.statistic, 36.0);
  EXPECT_DOUBLE_EQ(*a.rank_biserial, -*b.rank_biserial);
  EXPECT_DOUBLE_EQ(*a.p_value, *b.p_value);
  const auto ag = fs::wilcoxon_signed_rank(x, 0.5, {fs::Alternative::greater, 0.95});
  const auto bl = fs::wilcoxon_signed_rank(mirrored, -0.5, {fs::Alternative::less, 0.95});
  EXPECT_DOUBLE_EQ(*ag.p_value, *bl.p_value);
}

TEST(WilcoxonSignedRank, ForcedChoicesOfPath) {
  const std::vector<double> x{1.83, 0.50, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30};
  const auto normal = fs::wilcoxon_signed_rank(x, 1.0, {}, true, false);
  EXPECT_FALSE(*normal.exact);
  EXPECT_EQ(normal.method, "Wilcoxon signed rank test with continuity correction");
  EXPECT_TRUE(normal.note.empty());  // R warns only when exact was wanted
  const auto uncorrected = fs::wilcoxon_signed_rank(x, 1.0, {}, false, false);
  EXPECT_EQ(uncorrected.method, "Wilcoxon signed rank test");
  EXPECT_LT(*uncorrected.p_value, *normal.p_value);
}

TEST(WilcoxonSignedRank, CannotComputeWithoutNonZeroDifferences) {
  const std::vector<double> zeros{4, 4, 4};
  const auto r = fs::wilcoxon_signed_rank(zeros, 4.0);
  EXPECT_FALSE(r.computed);
  EXPECT_FALSE(r.p_value.has_value());
  // R's wilcox.test returns V = 0 (and p-value NaN): feint keeps R's statistic.
  ASSERT_TRUE(r.statistic.has_value());
  EXPECT_EQ(*r.statistic, 0.0);
  EXPECT_NE(r.note.find("zero"), std::string::npos);

  const std::vector<double> empty;
  const auto e = fs::wilcoxon_signed_rank(empty, 0.0);
  EXPECT_FALSE(e.computed);
  EXPECT_NE(e.note.find("not enough"), std::string::npos);

  const std::vector<double> nans{std::nan(""), std::nan("")};
  EXPECT_FALSE(fs::wilcoxon_signed_rank(nans, 0.0).computed);

  const std::vector<double> x{1.0, 2.0, 3.0};
  const auto bad_mu = fs::wilcoxon_signed_rank(x, std::nan(""));
  EXPECT_FALSE(bad_mu.computed);
  EXPECT_NE(bad_mu.note.find("mu"), std::string::npos);
  EXPECT_FALSE(fs::wilcoxon_signed_rank(x, HUGE_VAL).computed);
}

TEST(WilcoxonSignedRank, DropsNaNLikeR) {
  const std::vector<double> with_nan{1.83, 0.50, std::nan(""), 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30};
  const auto r = fs::wilcoxon_signed_rank(with_nan, 1.0);
  EXPECT_EQ(r.n1, 9u);
  EXPECT_EQ(*r.statistic, 43.0);
  EXPECT_EQ(*r.p_value, 0.01171875);
}

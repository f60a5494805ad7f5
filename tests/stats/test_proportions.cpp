// The yes/no answer's statistics against R 4.2 (tests/golden/yesno/, written by
// tests/golden/yesno/make_yesno_golden.R: binom.test, prop.test, fisher.test), hand computations,
// the defining equations of Fisher's odds ratio and interval (solved exactly, where R's uniroot
// stops at 1.2e-4), extremes and every rejection path.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "golden_csv.hpp"
#include "feint/error.hpp"
#include "feint/stats/proportions.hpp"

namespace fs = feint::stats;

namespace {

const std::string kGolden = std::string(FEINT_SOURCE_DIR) + "/tests/golden/yesno/";

fs::Alternative alternative_of(const std::string& s) { return fs::parse_alternative(s); }

/// Fisher's noncentral hypergeometric law by direct products in long double, independently of
/// src/stats/proportions.cpp: P(X = k; psi) for k = 0..n1 (0 outside the support).
std::vector<long double> law(const fs::YesNoTable& t, long double psi) {
  const long yes = static_cast<long>(t.yes1 + t.yes2), n1 = static_cast<long>(t.n1);
  const long no = static_cast<long>(t.n1 + t.n2) - yes;
  auto choose = [](long n, long k) {
    if (k < 0 || k > n) return 0.0L;
    long double c = 1;
    for (long i = 1; i <= k; ++i) c = c * static_cast<long double>(n - k + i) / static_cast<long double>(i);
    return c;
  };
  std::vector<long double> p(static_cast<std::size_t>(n1 + 1));
  long double sum = 0;
  for (long k = 0; k <= n1; ++k) {
    p[static_cast<std::size_t>(k)] = choose(yes, k) * choose(no, n1 - k) * std::pow(psi, static_cast<long double>(k));
    sum += p[static_cast<std::size_t>(k)];
  }
  for (auto& v : p) v /= sum;
  return p;
}

long double mean_of(const std::vector<long double>& p) {
  long double m = 0;
  for (std::size_t k = 0; k < p.size(); ++k) m += static_cast<long double>(k) * p[k];
  return m;
}

long double tail_of(const std::vector<long double>& p, std::size_t x, bool upper) {
  long double s = 0;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (upper ? k >= x : k <= x) s += p[k];
  return s;
}

}  // namespace

TEST(Proportion, ExactAndWilsonIntervalsMatchBinomTestAndPropTest) {
  const feint::test::GoldenCsv golden(kGolden + "proportion.csv");
  ASSERT_GE(golden.rows().size(), 20u);
  for (const auto& row : golden.rows()) {
    const auto x = static_cast<std::size_t>(row.number("x")), n = static_cast<std::size_t>(row.number("n"));
    SCOPED_TRACE(std::to_string(x) + " of " + std::to_string(n));
    const auto p = fs::describe_proportion(x, n, row.number("conf_level"));
    EXPECT_DOUBLE_EQ(p.estimate, static_cast<double>(x) / static_cast<double>(n));
    for (const auto& [got, col] : {std::pair{p.exact_low, "exact_low"}, {p.exact_high, "exact_high"},
                                   {p.wilson_low, "wilson_low"}, {p.wilson_high, "wilson_high"}}) {
      const double want = row.number(col);
      EXPECT_NEAR(got, want, 1e-12 * std::max(want, 1e-3)) << col;
    }
  }
}

TEST(Proportion, WilsonIntervalOfThreeInTenByHand) {
  // z = 1.959964, z^2 = 3.841459: centre (3 + 1.920729) / 13.841459 = 0.355507,
  // half 1.959964 sqrt(2.1 + 0.960365) / 13.841459 = 0.247715.
  const auto p = fs::describe_proportion(3, 10);
  const double z = 1.959963984540054, z2 = z * z;
  EXPECT_NEAR(p.wilson_low, (3 + z2 / 2 - z * std::sqrt(2.1 + z2 / 4)) / (10 + z2), 1e-15);
  EXPECT_NEAR(p.wilson_low, 0.107791, 1e-6);
  EXPECT_NEAR(p.wilson_high, 0.603222, 1e-6);
  // Clopper–Pearson at x = 0: 1 - (alpha/2)^(1/n).
  EXPECT_NEAR(fs::describe_proportion(0, 10).exact_high, 1 - std::pow(0.025, 0.1), 1e-14);
  EXPECT_EQ(fs::describe_proportion(0, 10).exact_low, 0.0);
  EXPECT_EQ(fs::describe_proportion(10, 10).exact_high, 1.0);
}

TEST(YesNoComparison, FisherAndPropTestMatchR) {
  const feint::test::GoldenCsv golden(kGolden + "two_conditions.csv");
  ASSERT_GE(golden.rows().size(), 120u);
  bool tiny_p = false;
  for (const auto& row : golden.rows()) {
    const fs::YesNoTable t{static_cast<std::size_t>(row.number("yes1")), static_cast<std::size_t>(row.number("n1")),
                           static_cast<std::size_t>(row.number("yes2")), static_cast<std::size_t>(row.number("n2"))};
    const fs::TestOptions o{alternative_of(row.str("alternative")), row.number("conf_level")};
    SCOPED_TRACE(std::to_string(t.yes1) + "/" + std::to_string(t.n1) + " vs " + std::to_string(t.yes2) + "/" +
                 std::to_string(t.n2) + " " + row.str("alternative") + " " + row.str("conf_level"));
    const auto f = fs::fisher_exact(t, o);
    ASSERT_TRUE(f.computed) << f.note;
    const double fp = row.number("fisher_p");
    EXPECT_NEAR(*f.p_value, fp, 1e-12 * fp + 1e-300);
    tiny_p = tiny_p || fp < 1e-6;
    // R's odds ratio and interval are uniroot's, to tol = 1.2e-4 on [0, 1] (or on 1 / psi).
    for (const auto& [got, col] : {std::pair{f.estimate, "fisher_or"}, {f.conf_low, "fisher_low"},
                                   {f.conf_high, "fisher_high"}}) {
      const double want = row.number(col);
      ASSERT_TRUE(got.has_value()) << col;
      if (std::isinf(want) || want == 0) EXPECT_EQ(*got, want) << col;
      else EXPECT_NEAR(*got, want, 2e-4 * std::max(1.0, want * want)) << col;
    }
    const auto p = fs::prop_test(t, o, row.str("correct") == "TRUE");
    ASSERT_TRUE(p.computed) << p.note;
    EXPECT_NEAR(*p.statistic, row.number("x2"), 1e-12 * row.number("x2") + 1e-15);
    const double pp = row.number("prop_p");
    EXPECT_NEAR(*p.p_value, pp, 1e-12 * pp + 1e-300);
    EXPECT_NEAR(*p.conf_low, row.number("prop_low"), 1e-13);
    EXPECT_NEAR(*p.conf_high, row.number("prop_high"), 1e-13);
    EXPECT_EQ(*p.df, 1.0);
  }
  EXPECT_TRUE(tiny_p) << "the goldens must include a p-value below 1e-6";
}

TEST(YesNoComparison, FisherOddsRatioAndIntervalSolveTheirEquationsExactly) {
  // The conditional MLE has E[X; psi] = yes1; the bounds have P(X >= yes1; psi_L) = alpha/2 and
  // P(X <= yes1; psi_U) = alpha/2, checked with an independent long-double law.
  for (const fs::YesNoTable t : {fs::YesNoTable{12, 20, 5, 20}, {3, 15, 9, 14}, {18, 30, 17, 29},
                                 {1, 40, 35, 40}, {50, 200, 80, 190}}) {
    SCOPED_TRACE(std::to_string(t.yes1) + "/" + std::to_string(t.n1));
    const auto f = fs::fisher_exact(t);
    EXPECT_NEAR(static_cast<double>(mean_of(law(t, *f.estimate))), static_cast<double>(t.yes1), 1e-9);
    EXPECT_NEAR(static_cast<double>(tail_of(law(t, *f.conf_low), t.yes1, true)), 0.025, 1e-11);
    EXPECT_NEAR(static_cast<double>(tail_of(law(t, *f.conf_high), t.yes1, false)), 0.025, 1e-11);
    // The p-value: every table no more probable than the observed one, at psi = 1.
    const auto p1 = law(t, 1);
    long double p = 0;
    for (const auto v : p1)
      if (v > 0 && v <= p1[t.yes1] * (1 + 1e-7L)) p += v;
    EXPECT_NEAR(*f.p_value, static_cast<double>(p), 1e-13 * static_cast<double>(p));
  }
}

TEST(YesNoComparison, FisherByHandThreeOfThreeAgainstNoneOfThree) {
  // Margins 3 yes / 3 no, 3 per condition: P(X = 3) = P(X = 0) = 1 / C(6, 3) = 1/20.
  const auto f = fs::fisher_exact({3, 3, 0, 3});
  EXPECT_NEAR(*f.p_value, 0.1, 1e-15);
  EXPECT_EQ(*f.estimate, INFINITY);
  EXPECT_EQ(*f.conf_high, INFINITY);
  const auto greater = fs::fisher_exact({3, 3, 0, 3}, {fs::Alternative::greater, 0.95});
  EXPECT_NEAR(*greater.p_value, 0.05, 1e-15);
  EXPECT_NEAR(*f.mean1, 1.0, 0);
  EXPECT_NEAR(*f.mean2, 0.0, 0);
}

TEST(YesNoComparison, LargeStudiesGiveFiniteTinyPValues) {
  // 5,000 of 100,000 against 6,000 of 100,000: chi-square without correction by hand.
  const fs::YesNoTable t{5000, 100000, 6000, 100000};
  const auto p = fs::prop_test(t, {}, false);
  const double pooled = 0.055, e_yes = 100000 * pooled, e_no = 100000 * (1 - pooled);
  const double x2 = 2 * (500.0 * 500 / e_yes + 500.0 * 500 / e_no);
  EXPECT_NEAR(*p.statistic, x2, 1e-10 * x2);
  EXPECT_NEAR(*p.p_value, std::erfc(std::sqrt(x2 / 2)), 1e-10 * *p.p_value);
  const auto f = fs::fisher_exact(t);
  ASSERT_TRUE(f.computed);
  EXPECT_GT(*f.p_value, 0);
  EXPECT_LT(*f.p_value, 1e-20);
  // The odds ratio (conditional MLE) is near the sample odds ratio (5000 * 94000) / (95000 * 6000).
  EXPECT_NEAR(*f.estimate, 5000.0 * 94000 / (95000.0 * 6000), 1e-3);
}

TEST(YesNoComparison, EmptyConditionsAndUniformAnswersAreNotComputable) {
  EXPECT_FALSE(fs::fisher_exact({0, 0, 3, 5}).computed);
  EXPECT_FALSE(fs::prop_test({2, 5, 0, 0}).computed);
  const auto all_no = fs::prop_test({0, 5, 0, 6});
  EXPECT_FALSE(all_no.computed);
  EXPECT_EQ(all_no.note, "every answer is no");
  EXPECT_EQ(fs::prop_test({5, 5, 6, 6}).note, "every answer is yes");
  const auto f = fs::fisher_exact({0, 5, 0, 6});  // one table only: p = 1, no odds ratio (R: 0)
  EXPECT_EQ(*f.p_value, 1.0);
  EXPECT_FALSE(f.estimate.has_value());
  EXPECT_NE(fs::prop_test({1, 4, 3, 4}).note.find("below 5"), std::string::npos);
}

TEST(YesNoComparison, ImpossibleCountsAndLevelsAreRefused) {
  EXPECT_THROW(fs::describe_proportion(6, 5), feint::UsageError);
  EXPECT_THROW(fs::describe_proportion(1, 5, 1.0), feint::UsageError);
  EXPECT_THROW(fs::fisher_exact({6, 5, 0, 5}), feint::UsageError);
  EXPECT_THROW(fs::prop_test({0, 5, 7, 5}), feint::UsageError);
  EXPECT_TRUE(std::isnan(fs::describe_proportion(0, 0).estimate));
}

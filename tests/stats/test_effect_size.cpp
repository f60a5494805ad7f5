// Effect-size intervals against exact roots (tests/golden/effect/make_effect_golden.R).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "feint/error.hpp"
#include "feint/stats/anova.hpp"
#include "feint/stats/effect_size.hpp"
#include "feint/stats/ttest.hpp"
#include "golden_csv.hpp"
#include "accuracy.hpp"

using namespace feint::stats;

namespace {
void expect_bound(double got, std::optional<double> want, const std::string& what) {
  ASSERT_TRUE(want) << what;
  if (std::isinf(*want)) {
    EXPECT_EQ(got, *want) << what;
    return;
  }
  feint::test::record("effect-size CI bounds (exact roots)", got, *want, what);
  // Both sides are exact roots of R's noncentral pt/pf (uniroot at 1e-15, TOMS 748 to the last
  // bit), so they differ by the accuracy of the noncentral distributions (R's pnbeta stops at
  // 1e-9): measured 3.6e-9.
  EXPECT_NEAR(got, *want, 1e-8 * std::max(1.0, std::fabs(*want))) << what;
}
}  // namespace

TEST(EffectSizeGolden, ExactRootsToOneInAMillion) {
  const feint::test::GoldenCsv golden(FEINT_SOURCE_DIR "/tests/golden/effect/effect_golden.csv");
  ASSERT_GE(golden.rows().size(), 100u);
  double worst = 0;
  for (const auto& row : golden.rows()) {
    const std::string kind = row.str("kind");
    const double a = row.number("a"), conf = row.number("conf");
    const Alternative alt = parse_alternative(row.str("alternative"));
    const auto n1 = static_cast<std::size_t>(row.number("n1"));
    const auto n2 = static_cast<std::size_t>(row.number("n2"));
    EffectInterval got{};
    if (kind == "d_one") got = cohen_d_interval_one_sample(a, n1, conf, alt);
    else if (kind == "d_two") got = cohen_d_interval_two_sample(a, n1, n2, conf, alt);
    else if (kind == "rb_two") got = rank_biserial_interval(a, n1, n2, conf, alt);
    else if (kind == "rb_one") got = rank_biserial_interval(a, n1, 0, conf, alt);
    else {
      const EtaSquared e = f_to_eta2(a, row.number("df1"), row.number("df2"), conf, alt);
      got = {e.low, e.high};
    }
    const std::string what = kind + " a=" + row.str("a") + " line " + std::to_string(row.line());
    expect_bound(got.low, row.num("low"), what + " low");
    expect_bound(got.high, row.num("high"), what + " high");
    if (std::isfinite(got.low)) worst = std::max(worst, std::fabs(got.low - *row.num("low")));
    if (std::isfinite(got.high)) worst = std::max(worst, std::fabs(got.high - *row.num("high")));
  }
  std::printf("effect-size intervals: max |feint - exact root| = %.2e\n", worst);
}

TEST(EffectSize, IntervalsFilledOnTestResults) {
  const std::vector<double> x{5.1, 4.8, 6.0, 5.5, 5.9, 6.3, 5.2, 4.9};
  const std::vector<double> y{4.1, 4.5, 4.0, 5.2, 4.4, 3.9, 4.8};
  TestResult one = t_test_one_sample(x, 5.0);
  add_effect_size_intervals(one);
  ASSERT_TRUE(one.cohen_d_low && one.cohen_d_high && one.hedges_g_low);
  EXPECT_LT(*one.cohen_d_low, *one.cohen_d);
  EXPECT_GT(*one.cohen_d_high, *one.cohen_d);
  // the interval of d is the ncp interval of the test's own t over sqrt(n)
  const auto i = noncentral_t_ncp_interval(*one.statistic, 7);
  EXPECT_NEAR(*one.cohen_d_low, i.low / std::sqrt(8.0), 1e-14);
  // Welch's row: the pooled-sd d with the pooled-t interval, the same as Student's
  TestResult w = t_test_welch(x, y), s = t_test_student(x, y);
  add_effect_size_intervals(w);
  add_effect_size_intervals(s);
  EXPECT_NEAR(*w.cohen_d_low, *s.cohen_d_low, 1e-12);
  EXPECT_NEAR(*w.hedges_g_high, *s.hedges_g_high, 1e-12);
  // the d interval excludes 0 exactly when the pooled t test rejects
  EXPECT_EQ(*s.cohen_d_low > 0, *s.p_value < 0.05);
  const std::vector<std::vector<double>> groups{{1, 2, 3, 2.5}, {2, 3, 4, 3.5}, {4, 5, 6, 5.5}};
  TestResult an = one_way_anova(groups);
  add_effect_size_intervals(an);
  ASSERT_TRUE(an.eta_squared_low);
  EXPECT_LE(*an.eta_squared_low, *an.r_squared);
  EXPECT_EQ(*an.eta_squared_high, 1.0);  // one-sided ("greater"), as effectsize
}

TEST(EffectSize, EdgesAndRejections) {
  const auto e = rank_biserial_interval(1.0, 10, 12);
  EXPECT_EQ(e.low, 1.0);
  EXPECT_EQ(e.high, 1.0);
  EXPECT_THROW(rank_biserial_interval(1.5, 10, 12), feint::InvalidData);
  EXPECT_THROW(cohen_d_interval_one_sample(1.0, 1), feint::InvalidData);
  EXPECT_THROW(f_to_eta2(-1, 2, 10), feint::InvalidData);
  EXPECT_THROW(f_to_eta2(2, 2, 10, 0.95, Alternative::less), feint::UsageError);
  // F = 0: eta^2 = 0, lower bound 0
  const EtaSquared z = f_to_eta2(0, 2, 10, 0.95, Alternative::two_sided);
  EXPECT_EQ(z.estimate, 0);
  EXPECT_EQ(z.low, 0);
  EXPECT_EQ(z.high, 0);
  // large t far in the tail still gives finite, ordered bounds
  const auto big = cohen_d_interval_one_sample(40, 30);
  EXPECT_LT(big.low, 40 / std::sqrt(30.0));
  EXPECT_GT(big.high, 40 / std::sqrt(30.0));
}

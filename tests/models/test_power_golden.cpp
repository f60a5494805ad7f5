// t-test power and sample size against R (tests/golden/models/power_golden.R): power.t.test
// (strict = TRUE), pwr.t.test, pwr.t2n.test and the Welch formula, within 1e-10 relative.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "feint/error.hpp"
#include "feint/models/power.hpp"
#include "stats/golden_csv.hpp"
#include "accuracy.hpp"

namespace feint::models {
namespace {

const std::string kFile = std::string(FEINT_SOURCE_DIR) + "/tests/golden/models/power_golden.csv";

TTestPowerSpec spec_of(const test::GoldenRow& row) {
  TTestPowerSpec s;
  s.design = parse_t_test_design(row.str("type"));
  s.alternative = stats::parse_alternative(row.str("alternative"));
  s.tests = static_cast<int>(row.number("tests"));
  s.sd = row.number("sd");
  s.sd2 = row.num("sd2");
  s.ratio = row.number("ratio");
  s.welch = row.str("welch") == "TRUE";
  s.n = row.num("n");
  s.delta = row.num("delta");
  s.power = row.num("power");
  const std::string solve = row.str("solve");
  if (solve == "n") s.n.reset();
  if (solve == "delta") s.delta.reset();
  if (solve == "power") s.power.reset();
  return s;
}

TEST(TTestPowerGolden, AgreesWithRWithin1e10) {
  const test::GoldenCsv golden(kFile);
  ASSERT_GE(golden.rows().size(), 130u);
  double worst = 0;
  for (const auto& row : golden.rows()) {
    const std::string solve = row.str("solve");
    const TTestPowerResult r = solve_t_test_power(spec_of(row));
    const double want = row.number(solve);
    const double got = solve == "n" ? *r.spec.n : solve == "delta" ? *r.spec.delta : *r.spec.power;
    const double rel = std::abs(got - want) / std::abs(want);
    worst = std::max(worst, rel);
    feint::test::record("power (pwr)", got, want, row.str("source") + " " + solve);
    EXPECT_LE(rel, 1e-10) << row.str("source") << " " << solve << " " << row.str("type") << " "
                          << row.str("alternative") << " m=" << row.str("tests") << " got " << got
                          << " want " << want;
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", worst);
  RecordProperty("worst_relative_error", text);
}

TEST(TTestPower, PowerAtTheSolvedWholeSampleSizeIsAtLeastTheTarget) {
  for (auto design : {TTestDesign::one_sample, TTestDesign::two_sample, TTestDesign::paired}) {
    for (double delta : {0.2, 0.5, 1.1}) {
      for (double target : {0.8, 0.9, 0.95}) {
        TTestPowerSpec s;
        s.design = design;
        s.delta = delta;
        s.power = target;
        s.tests = 20;
        if (design == TTestDesign::two_sample) s.ratio = 1.5;
        const TTestPowerResult r = solve_t_test_power(s);
        ASSERT_TRUE(r.power_at_ceiling.has_value());
        EXPECT_GE(*r.power_at_ceiling, target);
        EXPECT_GE(*r.n1_ceiling, *r.spec.n);
        // One participant fewer would not do.
        TTestPowerSpec fewer = r.spec;
        fewer.n = *r.n1_ceiling - 1;
        if (*fewer.n >= 2) {
          EXPECT_LT(t_test_power(fewer), target);
        }
      }
    }
  }
}

TEST(TTestPower, HugeEffectNeedsOnlyTheSmallestSample) {
  TTestPowerSpec s;
  s.design = TTestDesign::one_sample;
  s.delta = 50;
  s.power = 0.8;
  const TTestPowerResult r = solve_t_test_power(s);
  EXPECT_EQ(*r.spec.n, 2.0);  // power.t.test's lower bound for n
  EXPECT_GE(*r.power_at_ceiling, 0.8);
}

TEST(TTestPower, WelchWithEqualSdsAndSizesIsStudent) {
  TTestPowerSpec s;
  s.n = 25;
  s.delta = 0.4;
  const double student = t_test_power(s);
  s.welch = true;
  EXPECT_NEAR(t_test_power(s), student, 1e-14);
}

TEST(TTestPower, BonferroniDividesAlpha) {
  TTestPowerSpec s;
  s.n = 30;
  s.delta = 0.7;
  s.tests = 20;
  const double m20 = t_test_power(s);
  s.tests = 1;
  s.alpha = 0.05 / 20;
  EXPECT_DOUBLE_EQ(t_test_power(s), m20);
}

TEST(TTestPower, ImpossibleRequestsAreUsageErrors) {
  TTestPowerSpec s;  // nothing given
  EXPECT_THROW(solve_t_test_power(s), UsageError);
  s.n = 10;
  s.delta = 0.5;
  s.power = 0.8;  // nothing to solve
  EXPECT_THROW(solve_t_test_power(s), UsageError);
  s.power.reset();
  s.n = 1;
  EXPECT_THROW(solve_t_test_power(s), UsageError);
  s.n = 10;
  s.delta = -0.5;
  EXPECT_THROW(solve_t_test_power(s), UsageError);
  s.delta = 0.5;
  s.design = TTestDesign::paired;
  s.welch = true;
  EXPECT_THROW(solve_t_test_power(s), UsageError);
}

}  // namespace
}  // namespace feint::models

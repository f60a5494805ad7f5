// t-tests, TOST and p.adjust against R 4.2 golden values (tests/golden/stats/ttest_golden.R makes
// ttest_golden.csv and p_adjust_golden.csv): statistic, df, CI, estimate and effect sizes within
// 1e-10 relative, p-values within 1e-10 relative or 1e-300 absolute.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "feint/stats/p_adjust.hpp"
#include "feint/stats/ttest.hpp"
#include "golden_csv.hpp"
#include "accuracy.hpp"

namespace fs = feint::stats;
using feint::test::GoldenCsv;
using feint::test::GoldenRow;

namespace {

constexpr double kRel = 1e-10;

::testing::AssertionResult close(const char* what, std::optional<double> got,
                                 std::optional<double> want, double abs_floor = 0) {
  if (!want) {
    if (!got) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << what << ": R has NA, feint " << *got;
  }
  if (!got) return ::testing::AssertionFailure() << what << ": feint empty, R " << *want;
  if (std::isinf(*want)) {
    if (*got == *want) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << what << ": feint " << *got << ", R " << *want;
  }
  const double err = std::fabs(*got - *want);
  feint::test::record("t tests", *got, *want, what);
  if (err <= std::max(kRel * std::fabs(*want), abs_floor)) return ::testing::AssertionSuccess();
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s: feint %.17g, R %.17g (rel. error %.3g)", what, *got, *want,
                err / std::fabs(*want));
  return ::testing::AssertionFailure() << buf;
}

fs::TestResult run(const GoldenRow& row) {
  const std::string kind = row.str("kind");
  const auto x = row.numbers("x");
  const auto y = row.numbers("y");
  const fs::TestOptions opt{fs::parse_alternative(row.str("alternative")), row.number("conf_level")};
  const double mu = row.number("mu");
  if (kind == "one_sample") return fs::t_test_one_sample(x, mu, opt);
  if (kind == "welch") return fs::t_test_welch(x, y, opt, mu);
  if (kind == "student") return fs::t_test_student(x, y, opt, mu);
  if (kind == "paired") return fs::t_test_paired(x, y, opt, mu);
  const double delta = row.number("delta");
  if (kind == "tost_one_sample") return fs::tost_one_sample(x, mu, delta, opt);
  if (kind == "tost_welch") return fs::tost_two_sample(x, y, delta, false, opt);
  if (kind == "tost_student") return fs::tost_two_sample(x, y, delta, true, opt);
  if (kind == "tost_paired") return fs::tost_paired(x, y, delta, opt);
  ADD_FAILURE() << "unknown kind " << kind;
  return {};
}

}  // namespace

TEST(TTestGolden, AllCasesMatchR) {
  GoldenCsv golden(feint::test::golden_path("ttest_golden.csv"));
  ASSERT_GE(golden.rows().size(), 300u);
  std::size_t tiny = 0, not_computable = 0;
  for (const auto& row : golden.rows()) {
    SCOPED_TRACE("ttest_golden.csv line " + std::to_string(row.line()) + " (" + row.str("kind") +
                 ", " + row.str("alternative") + ", n = " + std::to_string(row.numbers("x").size()) +
                 ")");
    const fs::TestResult r = run(row);
    const bool computed = row.str("computed") == "TRUE";
    ASSERT_EQ(r.computed, computed) << r.note;
    if (!computed) {
      ++not_computable;
      EXPECT_FALSE(r.note.empty());
      EXPECT_FALSE(r.p_value.has_value());
      EXPECT_FALSE(r.statistic.has_value());
      continue;
    }
    EXPECT_TRUE(close("statistic", r.statistic, row.num("statistic")));
    EXPECT_TRUE(close("df", r.df, row.num("df")));
    EXPECT_TRUE(close("p_value", r.p_value, row.num("p_value"), 1e-300));
    EXPECT_TRUE(close("conf_low", r.conf_low, row.num("conf_low")));
    EXPECT_TRUE(close("conf_high", r.conf_high, row.num("conf_high")));
    EXPECT_TRUE(close("estimate", r.estimate, row.num("estimate")));
    EXPECT_TRUE(close("cohen_d", r.cohen_d, row.num("cohen_d")));
    EXPECT_TRUE(close("hedges_g", r.hedges_g, row.num("hedges_g")));
    if (row.number("p_value") < 1e-100) ++tiny;
  }
  std::printf("%zu golden t-test cases, %zu with p < 1e-100, %zu not computable\n",
              golden.rows().size(), tiny, not_computable);
  EXPECT_GE(tiny, 10u);
}

TEST(PAdjustGolden, EveryMethodMatchesR) {
  GoldenCsv golden(feint::test::golden_path("p_adjust_golden.csv"));
  ASSERT_GE(golden.rows().size(), 90u);
  for (const auto& row : golden.rows()) {
    SCOPED_TRACE("p_adjust_golden.csv line " + std::to_string(row.line()) + " (" +
                 row.str("method") + ")");
    std::vector<std::optional<double>> p;
    for (double v : row.numbers("p")) p.push_back(std::isnan(v) ? std::nullopt : std::optional(v));
    const auto want = row.numbers("adjusted");
    const auto got = fs::p_adjust(p, fs::parse_p_adjust(row.str("method")));
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      const auto w = std::isnan(want[i]) ? std::nullopt : std::optional(want[i]);
      EXPECT_TRUE(close(("p[" + std::to_string(i) + "]").c_str(), got[i], w, 1e-300));
    }
  }
}

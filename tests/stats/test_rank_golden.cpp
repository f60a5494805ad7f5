// Wilcoxon signed-rank, Mann–Whitney and their exact distributions against R 4.2 golden values
// (tests/golden/rank/make_rank_golden.R writes wilcoxon.csv and distributions.csv).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "golden_csv.hpp"
#include "feint/stats/rank_tests.hpp"
#include "accuracy.hpp"

namespace fs = feint::stats;
using feint::test::GoldenCsv;
using feint::test::GoldenRow;

namespace {

std::string rank_golden(const std::string& name) {
  return std::string(FEINT_SOURCE_DIR) + "/tests/golden/rank/" + name;
}

// The spec's tolerance: 1e-10 relative, and 1e-300 absolute for p-values.
::testing::AssertionResult close(const std::optional<double>& actual, std::optional<double> expected,
                                 double abs_floor = 0.0) {
  if (!expected) {
    if (!actual) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "expected empty, got " << *actual;
  }
  if (!actual) return ::testing::AssertionFailure() << "empty, expected " << *expected;
  feint::test::record("rank tests", *actual, *expected);
  const double tol = std::max(1e-10 * std::fabs(*expected), abs_floor);
  if (std::fabs(*actual - *expected) <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << ::testing::PrintToString(*actual) << " vs R "
                                       << ::testing::PrintToString(*expected);
}

std::optional<bool> parse_bool(const std::string& s) {
  if (s == "TRUE") return true;
  if (s == "FALSE") return false;
  return std::nullopt;
}

}  // namespace

TEST(RankTestsGolden, WilcoxTestCasesMatchR) {
  const GoldenCsv golden(rank_golden("wilcoxon.csv"));
  ASSERT_GE(golden.rows().size(), 150u);
  std::size_t exact_cases = 0, normal_cases = 0, tiny_p = 0;
  for (const GoldenRow& row : golden.rows()) {
    SCOPED_TRACE(row.str("case") + " (line " + std::to_string(row.line()) + ")");
    const fs::TestOptions options{fs::parse_alternative(row.str("alternative")), 0.95};
    const bool correct = *parse_bool(row.str("correct"));
    const std::optional<bool> exact = parse_bool(row.str("exact_arg"));
    const auto x = row.numbers("x");
    const bool one_sample = row.str("test") == "signrank";
    const fs::TestResult r =
        one_sample ? fs::wilcoxon_signed_rank(x, row.number("mu"), options, correct, exact)
                   : fs::mann_whitney(x, row.numbers("y"), options, correct, exact);
    ASSERT_TRUE(r.computed) << r.note;
    EXPECT_EQ(r.test, one_sample ? "wilcoxon_signed_rank" : "mann_whitney");
    EXPECT_EQ(r.method, row.str("method"));
    EXPECT_EQ(r.alternative, options.alternative);
    EXPECT_EQ(r.statistic_name, one_sample ? "V" : "W");
    EXPECT_TRUE(close(r.statistic, row.num("statistic")));
    EXPECT_TRUE(close(r.p_value, row.num("p_value"), 1e-300));
    ASSERT_TRUE(r.exact.has_value());
    EXPECT_EQ(*r.exact, *parse_bool(row.str("exact")));
    EXPECT_TRUE(close(r.rank_biserial, row.num("rank_biserial")));
    EXPECT_EQ(r.n1, static_cast<std::size_t>(row.number("n1")));
    EXPECT_EQ(r.n2, static_cast<std::size_t>(row.number("n2")));
    EXPECT_TRUE(close(r.mean1, row.num("mean1")));
    EXPECT_TRUE(close(r.sd1, row.num("sd1")));
    EXPECT_TRUE(close(r.median1, row.num("median1")));
    EXPECT_TRUE(close(r.iqr1, row.num("iqr1"), 1e-15));
    EXPECT_TRUE(close(r.mean2, row.num("mean2")));
    EXPECT_TRUE(close(r.sd2, row.num("sd2")));
    EXPECT_TRUE(close(r.median2, row.num("median2")));
    EXPECT_TRUE(close(r.iqr2, row.num("iqr2"), 1e-15));
    EXPECT_FALSE(r.conf_low.has_value());
    EXPECT_FALSE(r.estimate.has_value());
    // The note carries R's warnings, verbatim.
    for (const char* warning : {"cannot compute exact p-value with ties",
                                "cannot compute exact p-value with zeroes"}) {
      const bool r_warned = row.str("warnings").find(warning) != std::string::npos;
      EXPECT_EQ(r.note.find(warning) != std::string::npos, r_warned) << warning;
    }
    (*r.exact ? exact_cases : normal_cases) += 1;
    if (*r.p_value < 1e-20) ++tiny_p;
  }
  // The suite exercises both paths and genuinely small p-values.
  EXPECT_GE(exact_cases, 50u);
  EXPECT_GE(normal_cases, 50u);
  EXPECT_GE(tiny_p, 6u);
}

TEST(RankTestsGolden, ExactDistributionsMatchPsignrankAndPwilcox) {
  const GoldenCsv golden(rank_golden("distributions.csv"));
  ASSERT_GE(golden.rows().size(), 100u);
  for (const GoldenRow& row : golden.rows()) {
    SCOPED_TRACE("line " + std::to_string(row.line()));
    const double q = row.number("q");
    const auto m = static_cast<std::size_t>(row.number("m"));
    const bool lower = *parse_bool(row.str("lower"));
    const double p = row.str("kind") == "psignrank"
                         ? fs::detail::psignrank(q, m, lower)
                         : fs::detail::pwilcox(q, m, static_cast<std::size_t>(row.number("n")), lower);
    EXPECT_TRUE(close(p, row.number("p"), 1e-300));
  }
}

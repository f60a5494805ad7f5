// describe(), Summary and quantiles: R 4.2 golden values (anova_describe_golden.R) and invariants.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "feint/error.hpp"
#include "feint/stats/descriptive.hpp"
#include "feint/stats/exact_decimal.hpp"
#include "golden_csv.hpp"

namespace fs = feint::stats;
using feint::test::GoldenCsv;

namespace {

::testing::AssertionResult close(const char* what, std::optional<double> got,
                                 std::optional<double> want, double rel = 1e-12) {
  if (got.has_value() != want.has_value())
    return ::testing::AssertionFailure() << what << ": feint " << (got ? "has a value" : "empty")
                                         << ", R " << (want ? "has a value" : "NA");
  if (!want) return ::testing::AssertionSuccess();
  if (std::fabs(*got - *want) <= rel * std::fabs(*want) + 1e-300) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << what << ": feint " << *got << ", R " << *want;
}

}  // namespace

TEST(Describe, MatchesRSummaryQuantileTTestAndAcf) {
  GoldenCsv golden(feint::test::golden_path("describe_golden.csv"));
  ASSERT_GE(golden.rows().size(), 20u);
  for (const auto& row : golden.rows()) {
    SCOPED_TRACE("describe_golden.csv line " + std::to_string(row.line()));
    const auto x = row.numbers("x");
    const fs::Description d = fs::describe(x, row.number("conf_level"));
    EXPECT_EQ(d.n, static_cast<std::size_t>(row.number("n")));
    EXPECT_TRUE(close("mean", d.mean, row.num("mean")));
    EXPECT_TRUE(close("sd", d.sd, row.num("sd")));
    EXPECT_TRUE(close("se", d.se, row.num("se")));
    EXPECT_TRUE(close("min", d.min, row.num("min")));
    EXPECT_TRUE(close("q1", d.q1, row.num("q1")));
    EXPECT_TRUE(close("median", d.median, row.num("median")));
    EXPECT_TRUE(close("q3", d.q3, row.num("q3")));
    EXPECT_TRUE(close("max", d.max, row.num("max")));
    EXPECT_TRUE(close("conf_low", d.conf_low, row.num("conf_low"), 1e-10));
    EXPECT_TRUE(close("conf_high", d.conf_high, row.num("conf_high"), 1e-10));
    EXPECT_TRUE(close("autocorr_lag1", d.autocorr_lag1, row.num("autocorr_lag1"), 1e-10));
    if (!d.conf_low) {
      EXPECT_FALSE(d.note.empty());
    }
  }
}

TEST(Describe, DropsNaNAndRejectsBadConfLevel) {
  const std::vector<double> x = {1, std::nan(""), 3};
  const auto d = fs::describe(x);
  EXPECT_EQ(d.n, 2u);
  EXPECT_DOUBLE_EQ(*d.mean, 2.0);
  EXPECT_THROW(fs::describe(x, 1.0), feint::UsageError);
  EXPECT_THROW(fs::describe(x, 0.0), feint::UsageError);
  const auto empty = fs::describe(std::vector<double>{});
  EXPECT_EQ(empty.n, 0u);
  EXPECT_FALSE(empty.mean.has_value());
  EXPECT_FALSE(empty.note.empty());
}

TEST(Quantile, Type7InterpolatesAsR) {
  // quantile(c(1, 2, 4, 8), c(0, 0.1, 1/3, 0.5, 0.9, 1), type = 7) = 1 1.3 2 3 6.8 8
  const std::vector<double> s = {1, 2, 4, 8};
  EXPECT_DOUBLE_EQ(fs::quantile_type7(s, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(fs::quantile_type7(s, 0.1), 1.3);
  EXPECT_DOUBLE_EQ(fs::quantile_type7(s, 1.0 / 3.0), 2.0);
  EXPECT_DOUBLE_EQ(fs::quantile_type7(s, 0.5), 3.0);
  EXPECT_DOUBLE_EQ(fs::quantile_type7(s, 0.9), 6.8);
  EXPECT_DOUBLE_EQ(fs::quantile_type7(s, 1.0), 8.0);
  EXPECT_THROW(fs::quantile_type7(std::vector<double>{}, 0.5), feint::InvalidData);
  EXPECT_THROW(fs::quantile_type7(s, 1.5), feint::UsageError);
}

TEST(Summary, WelfordAddAgreesWithTwoPassAndMergeIsOrderFree) {
  std::mt19937_64 rng(42);
  std::normal_distribution<double> dist(1e6, 0.3);  // many constant leading digits
  std::vector<double> x(5000);
  for (auto& v : x) v = dist(rng);
  const fs::Summary whole = fs::summarize(x);
  fs::Summary added, merged_fwd, merged_rev;
  for (double v : x) added.add(v);
  std::vector<fs::Summary> parts;
  for (std::size_t i = 0; i < x.size(); i += 333)
    parts.push_back(fs::summarize(std::span(x).subspan(i, std::min<std::size_t>(333, x.size() - i))));
  for (const auto& p : parts) merged_fwd.merge(p);
  for (auto it = parts.rbegin(); it != parts.rend(); ++it) merged_rev.merge(*it);
  for (const fs::Summary* s : {&added, &merged_fwd, &merged_rev}) {
    EXPECT_EQ(s->n, whole.n);
    EXPECT_NEAR(s->mean, whole.mean, 1e-15 * whole.mean);
    EXPECT_NEAR(*s->sd(), *whole.sd(), 1e-12 * *whole.sd());
    EXPECT_EQ(s->min, whole.min);
    EXPECT_EQ(s->max, whole.max);
  }
}

TEST(Summary, EmptyAndSingleValue) {
  fs::Summary s;
  EXPECT_FALSE(s.variance().has_value());
  s.add(2.5);
  EXPECT_EQ(s.n, 1u);
  EXPECT_EQ(s.mean, 2.5);
  EXPECT_FALSE(s.sd().has_value());
  fs::Summary t;
  t.merge(s);
  EXPECT_EQ(t.mean, 2.5);
  s.merge(fs::Summary{});
  EXPECT_EQ(s.n, 1u);
}

TEST(ExactDecimal, ReadsTextExactlyAndRejectsGarbage) {
  // 0.1 + 0.2 + 0.3 read exactly: mean 0.2, sd 0.1 to the last bit.
  const std::vector<std::string> t = {"0.1", "0.2", "0.3", "2e-1", "+.2", "20E-2"};
  const fs::Summary s = fs::summarize_decimal(t);
  EXPECT_EQ(s.n, 6u);
  EXPECT_EQ(s.mean, 0.2);
  EXPECT_DOUBLE_EQ(*s.sd(), std::sqrt(0.02 / 5));
  EXPECT_EQ(s.min, 0.1);
  EXPECT_EQ(s.max, 0.3);
  for (const char* bad : {"", "abc", "1.2.3", "1e", "0x10", "nan", "1,5"})
    EXPECT_THROW(fs::summarize_decimal(std::vector<std::string>{bad}), feint::InvalidData) << bad;
}

TEST(ExactDecimal, DescribeDecimalAgreesWithDescribeOnOrdinaryData) {
  GoldenCsv golden(feint::test::golden_path("describe_golden.csv"));
  for (const auto& row : golden.rows()) {
    SCOPED_TRACE("describe_golden.csv line " + std::to_string(row.line()));
    std::vector<std::string> text;
    for (const auto& f : feint::test::split_commas(row.str("x"), ';')) text.push_back(f);
    const fs::Description d = fs::describe_decimal(text, row.number("conf_level"));
    EXPECT_EQ(d.n, text.size());
    EXPECT_TRUE(close("mean", d.mean, row.num("mean")));
    EXPECT_TRUE(close("sd", d.sd, row.num("sd")));
    EXPECT_TRUE(close("q1", d.q1, row.num("q1")));
    EXPECT_TRUE(close("max", d.max, row.num("max")));
    EXPECT_TRUE(close("conf_low", d.conf_low, row.num("conf_low"), 1e-10));
    EXPECT_TRUE(close("autocorr_lag1", d.autocorr_lag1, row.num("autocorr_lag1"), 1e-10));
  }
}

// The mean of values that cancel keeps every digit, from text and from doubles.
TEST(ExactDecimal, TheMeanOfCancellingValuesIsExact) {
  const std::vector<std::string> t = {"1e9", "-1e9", "1"};
  EXPECT_EQ(fs::describe_decimal(t).mean, 1.0 / 3);
  EXPECT_EQ(fs::summarize_decimal(t).mean, 1.0 / 3);
  const std::vector<std::string> u = {"1000000000.1", "-1000000000.1", "0.1", "0.2"};
  EXPECT_EQ(fs::describe_decimal(u).mean, 0.075);
  EXPECT_EQ(fs::describe(std::vector<double>{1e9, -1e9, 1}).mean, 1.0 / 3);
  EXPECT_EQ(fs::describe(std::vector<double>{1e300, 1, -1e300, 2}).mean, 0.75);
  EXPECT_EQ(fs::summarize(std::vector<double>{1e16, 1, -1e16}).mean, 1.0 / 3);
}

// Min, quartiles at data points and max are values of the file, never rebuilt ones.
TEST(ExactDecimal, OrderStatisticsAreTheFilesValues) {
  const std::vector<std::string> t = {"10000000.3", "0.1", "0.3", "0.7", "0.5"};
  const auto d = fs::describe_decimal(t);
  EXPECT_EQ(d.min, 0.1);
  EXPECT_EQ(d.q1, 0.3);
  EXPECT_EQ(d.median, 0.5);
  EXPECT_EQ(d.q3, 0.7);
  EXPECT_EQ(d.max, 10000000.3);
}

// Mantissas longer than 36 digits are read (their tail is below double precision).
TEST(ExactDecimal, LongMantissasAreRead) {
  const std::vector<std::string> t = {"0.12345678901234567890123456789012345678901234567890",
                                      "1.5", "2.25"};
  const auto d = fs::describe_decimal(t);
  EXPECT_EQ(d.min, 0.12345678901234567890123456789012345678901234567890);
  EXPECT_EQ(d.max, 2.25);
  EXPECT_EQ(*d.mean, (0.12345678901234567890123456789012345678901234567890 + 3.75) / 3);
  // Values whose scales are too far apart for one exact scale are an error here; feint describe
  // then falls back to the doubles (tests/tables/test_describe.cpp).
  EXPECT_THROW(fs::describe_decimal(std::vector<std::string>{"1e-300", "1e300"}), feint::InvalidData);
}

// Cronbach's alpha against psych::alpha (tests/golden/rank/alpha.csv, written by
// tests/golden/rank/make_rank_golden.R), hand computations and failure cases.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "golden_csv.hpp"
#include "feint/stats/reliability.hpp"

namespace fs = feint::stats;

namespace {

std::vector<std::vector<double>> parse_items(const std::string& field) {
  std::vector<std::vector<double>> items;
  std::istringstream in(field);
  std::string item;
  while (std::getline(in, item, '|')) {
    std::vector<double> values;
    for (const auto& v : feint::test::split_commas(item, ';'))
      values.push_back(v == "NA" ? std::nan("") : std::strtod(v.c_str(), nullptr));
    items.push_back(std::move(values));
  }
  return items;
}

void expect_rel(double actual, double expected) {
  EXPECT_NEAR(actual, expected, 1e-10 * std::fabs(expected)) << "psych: " << expected;
}

}  // namespace

TEST(CronbachAlpha, MatchesPsychRawAlphaAndAlphaDrop) {
  const feint::test::GoldenCsv golden(std::string(FEINT_SOURCE_DIR) + "/tests/golden/rank/alpha.csv");
  ASSERT_GE(golden.rows().size(), 10u);
  for (const auto& row : golden.rows()) {
    SCOPED_TRACE(row.str("case"));
    const auto items = parse_items(row.str("items"));
    // alpha.csv was made with psych::alpha(na.omit(items)).
    const auto a = fs::cronbach_alpha(items, fs::AlphaMissing::complete_cases);
    ASSERT_TRUE(a.raw_alpha.has_value()) << a.note;
    expect_rel(*a.raw_alpha, row.number("raw_alpha"));
    EXPECT_EQ(a.n, static_cast<std::size_t>(row.number("n")));
    EXPECT_EQ(a.items_used, static_cast<std::size_t>(row.number("items_used")));
    const auto drop = row.numbers("drop");
    ASSERT_EQ(a.if_dropped.size(), drop.size());
    for (std::size_t j = 0; j < drop.size(); ++j) {
      SCOPED_TRACE("item " + std::to_string(j + 1));
      if (std::isnan(drop[j])) {
        EXPECT_FALSE(a.if_dropped[j].has_value());
      } else {
        ASSERT_TRUE(a.if_dropped[j].has_value());
        expect_rel(*a.if_dropped[j], drop[j]);
      }
    }
  }
}

TEST(CronbachAlpha, HandComputedThreeItems) {
  // Items (1,2,3,4), (2,2,3,5), (1,3,3,4): variances 5/3, 2, 19/12 (sum 21/4); totals
  // (4,7,9,13) have variance 57/4. alpha = 3/2 * (1 - 21/57) = 18/19.
  const std::vector<std::vector<double>> items{{1, 2, 3, 4}, {2, 2, 3, 5}, {1, 3, 3, 4}};
  const auto a = fs::cronbach_alpha(items);
  ASSERT_TRUE(a.raw_alpha.has_value()) << a.note;
  EXPECT_NEAR(*a.raw_alpha, 18.0 / 19.0, 1e-14);
  EXPECT_EQ(a.n, 4u);
  EXPECT_EQ(a.items_used, 3u);
  // Without item 3: variances 5/3 + 2 = 11/3, totals (3,4,6,9) variance 7: 2 * (1 - 11/21) = 20/21.
  EXPECT_NEAR(*a.if_dropped[2], 20.0 / 21.0, 1e-14);
}

TEST(CronbachAlpha, IdenticalItemsGiveOne) {
  const std::vector<double> item{1, 4, 2, 5, 3, 3};
  const std::vector<std::vector<double>> items{item, item, item};
  const auto a = fs::cronbach_alpha(items);
  EXPECT_NEAR(*a.raw_alpha, 1.0, 1e-14);
  for (const auto& d : a.if_dropped) EXPECT_NEAR(*d, 1.0, 1e-14);
}

TEST(CronbachAlpha, UsesCompleteCasesOnly) {
  const double na = std::nan("");
  const std::vector<std::vector<double>> with_missing{{1, 2, na, 4, 5}, {2, 1, 3, 5, 4}, {1, 3, 2, 4, na}};
  const std::vector<std::vector<double>> complete{{1, 2, 4}, {2, 1, 5}, {1, 3, 4}};
  const auto a = fs::cronbach_alpha(with_missing, fs::AlphaMissing::complete_cases);
  const auto b = fs::cronbach_alpha(complete, fs::AlphaMissing::complete_cases);
  EXPECT_EQ(a.n, 3u);
  EXPECT_DOUBLE_EQ(*a.raw_alpha, *b.raw_alpha);
}

TEST(CronbachAlpha, NotComputableCasesSayWhy) {
  const std::vector<std::vector<double>> one{{1, 2, 3}};
  auto a = fs::cronbach_alpha(one);
  EXPECT_FALSE(a.raw_alpha.has_value());
  EXPECT_NE(a.note.find("at least 2"), std::string::npos);

  const std::vector<std::vector<double>> ragged{{1, 2, 3}, {1, 2}};
  a = fs::cronbach_alpha(ragged);
  EXPECT_FALSE(a.raw_alpha.has_value());
  EXPECT_NE(a.note.find("different lengths"), std::string::npos);

  const std::vector<std::vector<double>> cancel{{1, 2, 3}, {3, 2, 1}};  // total is constant
  a = fs::cronbach_alpha(cancel);
  EXPECT_FALSE(a.raw_alpha.has_value());
  EXPECT_NE(a.note.find("no variance"), std::string::npos);

  const std::vector<std::vector<double>> constant{{4, 4, 4}, {4, 4, 4}};
  a = fs::cronbach_alpha(constant);
  EXPECT_FALSE(a.raw_alpha.has_value());
  EXPECT_EQ(a.items_used, 0u);

  const std::vector<std::vector<double>> one_row{{1}, {2}};
  a = fs::cronbach_alpha(one_row);
  EXPECT_FALSE(a.raw_alpha.has_value());
  EXPECT_NE(a.note.find("at least 2"), std::string::npos);
}

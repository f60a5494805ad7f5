// Cronbach's alpha with missing answers against psych::alpha: psych's default pairwise
// covariances and complete cases (tests/golden/alpha/alpha_missing.csv, written by
// tests/golden/alpha/make_alpha_missing_golden.R).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/stats/reliability.hpp"
#include "golden_csv.hpp"

namespace st = feint::stats;

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

void expect_alpha(const st::CronbachAlpha& a, double raw, const std::vector<double>& drop) {
  ASSERT_TRUE(a.raw_alpha.has_value()) << a.note;
  EXPECT_NEAR(*a.raw_alpha, raw, 1e-10 * std::fabs(raw)) << "psych: " << raw;
  ASSERT_EQ(a.if_dropped.size(), drop.size());
  for (std::size_t j = 0; j < drop.size(); ++j) {
    ASSERT_TRUE(a.if_dropped[j].has_value()) << "item " << j + 1;
    EXPECT_NEAR(*a.if_dropped[j], drop[j], 1e-10 * std::fabs(drop[j])) << "item " << j + 1;
  }
}

}  // namespace

TEST(CronbachAlphaMissing, PairwiseIsTheDefaultAndMatchesPsychAlpha) {
  const feint::test::GoldenCsv golden(std::string(FEINT_SOURCE_DIR) +
                                      "/tests/golden/alpha/alpha_missing.csv");
  ASSERT_GE(golden.rows().size(), 10u);
  for (const auto& row : golden.rows()) {
    SCOPED_TRACE(row.str("case"));
    const auto items = parse_items(row.str("items"));
    const auto a = st::cronbach_alpha(items);
    EXPECT_EQ(a.missing, st::AlphaMissing::pairwise);
    expect_alpha(a, row.number("pairwise_raw_alpha"), row.numbers("pairwise_drop"));
  }
}

TEST(CronbachAlphaMissing, CompleteCasesMatchPsychAlphaOfNaOmit) {
  const feint::test::GoldenCsv golden(std::string(FEINT_SOURCE_DIR) +
                                      "/tests/golden/alpha/alpha_missing.csv");
  for (const auto& row : golden.rows()) {
    SCOPED_TRACE(row.str("case"));
    const auto items = parse_items(row.str("items"));
    const auto a = st::cronbach_alpha(items, st::AlphaMissing::complete_cases);
    EXPECT_EQ(a.n, static_cast<std::size_t>(row.number("complete_n")));
    expect_alpha(a, row.number("complete_raw_alpha"), row.numbers("complete_drop"));
  }
}

TEST(CronbachAlphaMissing, PairwiseNeedsTwoJointAnswersPerPair) {
  const double na = std::nan("");
  const std::vector<std::vector<double>> items{
      {1, 2, 3, na, na}, {na, na, 2, 4, 5}, {1, 2, 3, 4, 5}};
  const auto a = st::cronbach_alpha(items);
  EXPECT_FALSE(a.raw_alpha.has_value());
  EXPECT_NE(a.note.find("items 1 and 2 were answered together by 1"), std::string::npos) << a.note;
  EXPECT_EQ(st::parse_alpha_missing("complete"), st::AlphaMissing::complete_cases);
  EXPECT_THROW(st::parse_alpha_missing("listwise"), feint::UsageError);
}

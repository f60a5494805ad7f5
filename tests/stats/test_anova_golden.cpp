// One-way ANOVA (anova(lm(y ~ g))) and Welch's ANOVA (oneway.test(y ~ g)) against R 4.2 golden values
// (tests/golden/stats/anova_describe_golden.R), plus the cases that cannot be computed.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/stats/anova.hpp"
#include "golden_csv.hpp"
#include "accuracy.hpp"

namespace fs = feint::stats;
using feint::test::GoldenCsv;

namespace {

std::vector<std::vector<double>> parse_groups(const std::string& text) {
  std::vector<std::vector<double>> groups;
  for (const auto& g : feint::test::split_commas(text, '|')) {
    groups.emplace_back();
    for (const auto& v : feint::test::split_commas(g, ';')) groups.back().push_back(std::stod(v));
  }
  return groups;
}

void expect_rel(std::optional<double> got, double want, const char* what, double abs_floor = 0) {
  ASSERT_TRUE(got.has_value()) << what;
  feint::test::record("one-way ANOVA", *got, want, what);
  EXPECT_LE(std::fabs(*got - want), std::max(1e-10 * std::fabs(want), abs_floor))
      << what << ": feint " << *got << ", R " << want;
}

}  // namespace

TEST(AnovaGolden, TableTestAndWelchMatchR) {
  GoldenCsv golden(feint::test::golden_path("anova_golden.csv"));
  ASSERT_GE(golden.rows().size(), 50u);
  for (const auto& row : golden.rows()) {
    SCOPED_TRACE("anova_golden.csv line " + std::to_string(row.line()));
    const auto groups = parse_groups(row.str("groups"));
    const fs::AnovaTable t = fs::one_way_anova_table(groups);
    expect_rel(t.f_statistic, row.number("f"), "F");
    expect_rel(t.df_between, row.number("df1"), "df1");
    expect_rel(t.df_within, row.number("df2"), "df2");
    expect_rel(t.p_value, row.number("p"), "p", 1e-300);
    expect_rel(t.ss_between, row.number("ss_between"), "ss_between");
    expect_rel(t.ss_within, row.number("ss_within"), "ss_within");
    expect_rel(t.r_squared, row.number("r_squared"), "r_squared");
    const fs::TestResult a = fs::one_way_anova(groups);
    ASSERT_TRUE(a.computed) << a.note;
    expect_rel(a.statistic, row.number("f"), "F (TestResult)");
    expect_rel(a.df2, row.number("df2"), "df2 (TestResult)");
    expect_rel(a.p_value, row.number("p"), "p (TestResult)", 1e-300);
    expect_rel(a.r_squared, row.number("r_squared"), "R^2 (TestResult)");
    EXPECT_EQ(a.statistic_name, "F");
    const fs::TestResult w = fs::welch_anova(groups);
    ASSERT_EQ(w.computed, row.str("welch_computed") == "TRUE") << w.note;
    if (!w.computed) continue;
    expect_rel(w.statistic, row.number("welch_f"), "Welch F");
    expect_rel(w.df, row.number("welch_df1"), "Welch df1");
    expect_rel(w.df2, row.number("welch_df2"), "Welch df2");
    expect_rel(w.p_value, row.number("welch_p"), "Welch p", 1e-300);
  }
}

TEST(Anova, CannotBeComputedSaysWhy) {
  const std::vector<std::vector<double>> one_group = {{1, 2, 3}};
  EXPECT_THROW(fs::one_way_anova_table(one_group), feint::InvalidData);
  EXPECT_FALSE(fs::one_way_anova(one_group).computed);
  const std::vector<std::vector<double>> singletons = {{1}, {2}, {3}};
  EXPECT_THROW(fs::one_way_anova_table(singletons), feint::InvalidData);
  const auto r = fs::one_way_anova(singletons);
  EXPECT_FALSE(r.computed);
  EXPECT_NE(r.note.find("residual"), std::string::npos);
  const std::vector<std::vector<double>> constant = {{2, 2}, {3, 3, 3}};
  const auto c = fs::one_way_anova(constant);
  EXPECT_FALSE(c.computed);
  EXPECT_NE(c.note.find("constant"), std::string::npos);
  // Welch: R's oneway.test stops with "not enough observations" for a group of one value.
  const std::vector<std::vector<double>> small = {{1, 2, 3}, {4}};
  const auto w = fs::welch_anova(small);
  EXPECT_FALSE(w.computed);
  EXPECT_NE(w.note.find("not enough observations"), std::string::npos);
  EXPECT_FALSE(fs::welch_anova(constant).computed);
}

TEST(Anova, EmptyGroupIsLeftOutWithANote) {
  // anova(lm(y ~ g)) with an unused level: the same table as without it.
  const std::vector<std::vector<double>> with_empty = {{1, 2, 3}, {}, {2, 4, 6, 5}};
  const std::vector<std::vector<double>> without = {{1, 2, 3}, {2, 4, 6, 5}};
  const auto a = fs::one_way_anova(with_empty);
  const auto b = fs::one_way_anova(without);
  ASSERT_TRUE(a.computed);
  EXPECT_EQ(*a.statistic, *b.statistic);
  EXPECT_EQ(*a.df, 1.0);
  EXPECT_FALSE(a.note.empty());
}

TEST(Anova, InfiniteValuesAreNotComputableRatherThanThrowing) {
  const std::vector<std::vector<double>> g = {{1, 2, std::numeric_limits<double>::infinity()},
                                              {2, 3, 4}};
  EXPECT_FALSE(fs::one_way_anova(g).computed);
  EXPECT_FALSE(fs::welch_anova(g).computed);
}

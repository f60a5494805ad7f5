// Kruskal–Wallis test against R 4.2's kruskal.test(y ~ g) (tests/golden/rank/kruskal.csv, written
// by tests/golden/rank/make_rank_golden.R), a hand computation, and failure cases.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "golden_csv.hpp"
#include "feint/stats/anova.hpp"

namespace fs = feint::stats;

namespace {

std::vector<std::vector<double>> parse_groups(const std::string& field) {
  std::vector<std::vector<double>> groups;
  std::istringstream in(field);
  std::string group;
  while (std::getline(in, group, '|')) {
    std::vector<double> values;
    for (const auto& v : feint::test::split_commas(group, ';')) values.push_back(std::strtod(v.c_str(), nullptr));
    groups.push_back(std::move(values));
  }
  return groups;
}

}  // namespace

TEST(KruskalWallis, MatchesRGoldenValues) {
  const feint::test::GoldenCsv golden(std::string(FEINT_SOURCE_DIR) + "/tests/golden/rank/kruskal.csv");
  ASSERT_GE(golden.rows().size(), 15u);
  for (const auto& row : golden.rows()) {
    SCOPED_TRACE(row.str("case"));
    const auto groups = parse_groups(row.str("groups"));
    const auto r = fs::kruskal_wallis(groups);
    ASSERT_TRUE(r.computed) << r.note;
    EXPECT_EQ(r.method, "Kruskal-Wallis rank sum test");
    EXPECT_EQ(r.n1, static_cast<std::size_t>(row.number("n")));
    const double stat = row.number("statistic");
    EXPECT_NEAR(*r.statistic, stat, 1e-10 * std::fabs(stat));
    EXPECT_EQ(*r.df, row.number("df"));
    const double p = row.number("p_value");
    EXPECT_NEAR(*r.p_value, p, std::max(1e-10 * p, 1e-300));
  }
}

TEST(KruskalWallis, HandComputedWithoutTies) {
  // Ranks {1,2,3} | {4,5,6}: sum R^2/n = (36 + 225)/3 = 87, H = 12*87/42 - 21 = 27/7.
  const std::vector<std::vector<double>> groups{{0.1, 0.2, 0.3}, {1.1, 1.2, 1.3}};
  const auto r = fs::kruskal_wallis(groups);
  EXPECT_DOUBLE_EQ(*r.statistic, 27.0 / 7.0);
  EXPECT_EQ(*r.df, 1.0);
  EXPECT_NEAR(*r.p_value, std::erfc(std::sqrt(27.0 / 7.0 / 2.0)), 1e-14);  // chi2(1) = z^2
}

TEST(KruskalWallis, GroupOrderDoesNotMatter) {
  const std::vector<std::vector<double>> a{{1, 2, 2, 5}, {3, 3, 7}, {4, 6, 6, 8, 9}};
  const std::vector<std::vector<double>> b{a[2], a[0], a[1]};
  EXPECT_DOUBLE_EQ(*fs::kruskal_wallis(a).statistic, *fs::kruskal_wallis(b).statistic);
}

TEST(KruskalWallis, EqualMeanRanksGiveStatisticZeroAndPOne) {
  const std::vector<std::vector<double>> groups{{1, 4}, {2, 3}};
  const auto r = fs::kruskal_wallis(groups);
  EXPECT_NEAR(*r.statistic, 0.0, 1e-12);
  EXPECT_NEAR(*r.p_value, 1.0, 1e-12);
}

TEST(KruskalWallis, CannotComputeDegenerateInput) {
  const std::vector<std::vector<double>> one_group{{1, 2, 3}};
  EXPECT_FALSE(fs::kruskal_wallis(one_group).computed);
  const std::vector<std::vector<double>> one_value{{1}, {}};
  EXPECT_FALSE(fs::kruskal_wallis(one_value).computed);
  const std::vector<std::vector<double>> all_tied{{2, 2}, {2, 2, 2}};
  const auto tied = fs::kruskal_wallis(all_tied);
  EXPECT_FALSE(tied.computed);
  EXPECT_FALSE(tied.p_value.has_value());
  EXPECT_NE(tied.note.find("tied"), std::string::npos);
}

TEST(KruskalWallis, EmptyGroupsAndNaNAreDroppedLikeR) {
  const std::vector<std::vector<double>> with_empty{{0.1, 0.2, std::nan("")}, {}, {1.1, 1.2}};
  const std::vector<std::vector<double>> clean{{0.1, 0.2}, {1.1, 1.2}};
  const auto r = fs::kruskal_wallis(with_empty);
  EXPECT_DOUBLE_EQ(*r.statistic, *fs::kruskal_wallis(clean).statistic);
  EXPECT_EQ(*r.df, 1.0);
  EXPECT_EQ(r.n1, 4u);
  EXPECT_NE(r.note.find("empty group"), std::string::npos);
}

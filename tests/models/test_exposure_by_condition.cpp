// Condition x exposure per strategy against lmer + lmerTest::contest1D per condition
// (tests/golden/models/exposure_by_condition_golden.R).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "feint/models/exposure.hpp"

#include "golden_csv.hpp"

namespace {
using feint::test::read_csv;
}  // namespace

TEST(ExposureByCondition, SlopesAndTheirDifferenceMatchLmer) {
  const auto data = read_csv(FEINT_SOURCE_DIR "/tests/golden/models/lmm_exposure.csv");
  ASSERT_GT(data.size(), 200u);
  std::vector<std::string> participant, condition, strategy;
  std::vector<double> iteration, y;
  for (std::size_t i = 1; i < data.size(); ++i) {  // iteration,participant,condition,error,strategy
    iteration.push_back(std::stod(data[i][0]));
    participant.push_back(data[i][1]);
    condition.push_back(data[i][2]);
    y.push_back(std::stod(data[i][3]));
    strategy.push_back(data[i][4]);
  }
  const auto exposure = feint::models::exposure_counts(participant, iteration, strategy);
  const auto res = feint::models::exposure_slopes_by_condition(participant, condition, strategy, exposure, y);
  ASSERT_EQ(res.slopes.size(), 6u);
  ASSERT_EQ(res.differences.size(), 3u);
  const auto golden = read_csv(FEINT_SOURCE_DIR "/tests/golden/models/exposure_by_condition_golden.csv");
  ASSERT_EQ(golden.size(), 10u);
  for (std::size_t i = 1; i < golden.size(); ++i) {
    const auto& g = golden[i];
    const bool slope = g[0] == "slope";
    const auto& r = slope ? res.slopes[i - 1] : res.differences[i - 7];
    ASSERT_EQ(r.strategy, g[1]);
    ASSERT_TRUE(r.test.computed) << r.test.note;
    const auto near = [](double a, double b) { return std::fabs(a - b) <= 1e-6 * std::max(1e-3, std::fabs(b)); };
    EXPECT_PRED2(near, *r.test.estimate, std::stod(g[3])) << g[1] << " " << g[2];
    EXPECT_PRED2(near, r.std_error, std::stod(g[4]));
    EXPECT_PRED2(near, *r.test.df, std::stod(g[5]));
    EXPECT_PRED2(near, *r.test.p_value, std::stod(g[7]));
    EXPECT_PRED2(near, *r.test.conf_low, std::stod(g[8]));
    EXPECT_PRED2(near, *r.test.conf_high, std::stod(g[9]));
  }
  EXPECT_EQ(res.differences[0].condition, "adaptive-random");
}

TEST(ExposureByCondition, OneConditionHasNoDifferenceAndABadConditionIsNotComputable) {
  const std::vector<std::string> p{"a", "a", "b", "b"}, c{"x", "x", "x", "x"}, s{"s", "s", "s", "s"};
  const std::vector<double> e{0, 1, 0, 1}, y{1, 1, 1, 1};  // no variance
  const auto res = feint::models::exposure_slopes_by_condition(p, c, s, e, y);
  ASSERT_EQ(res.slopes.size(), 1u);
  EXPECT_FALSE(res.slopes[0].test.computed);
  EXPECT_NE(res.slopes[0].test.note.find("cannot be fitted"), std::string::npos);
  EXPECT_TRUE(res.differences.empty());
}

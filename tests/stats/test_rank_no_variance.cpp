// Rank tests whose statistic has no variance (every difference from mu zero; every value of x and
// y tied): what R's wilcox.test returns, for every alternative, exact or not, with and without the
// continuity correction (R 4.2.2, run by hand, see docs/rank-tests.md):
//   one-sample c(4,4,4,4), mu = 4:     V = 0; p = NaN, except p = 1 for a one-sided test with the
//                                       continuity correction (z = (0 + 0.5)/0 = +Inf for "less",
//                                       (0 - 0.5)/0 = -Inf for "greater");
//   two-sample c(3,3,3) vs c(3,3,3,3): W = 6; the same p-values.
// exact = TRUE changes nothing (R warns that it cannot compute exact p-values with zeroes/ties).
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "feint/stats/rank_tests.hpp"

namespace st = feint::stats;

namespace {

st::TestOptions with(st::Alternative alt) {
  st::TestOptions o;
  o.alternative = alt;
  return o;
}

}  // namespace

TEST(RankTestsWithoutVariance, OneSampleAllZeroDifferencesGiveWhatRGives) {
  const std::vector<double> x{4, 4, 4, 4};
  for (const std::optional<bool> exact :
       {std::optional<bool>{}, std::optional<bool>{true}, std::optional<bool>{false}}) {
    for (const auto alt :
         {st::Alternative::two_sided, st::Alternative::less, st::Alternative::greater}) {
      for (const bool correct : {true, false}) {
        SCOPED_TRACE(::testing::Message() << "alt " << static_cast<int>(alt) << " correct "
                                          << correct << " exact " << exact.value_or(false));
        const auto r = st::wilcoxon_signed_rank(x, 4.0, with(alt), correct, exact);
        const bool r_gives_a_number = correct && alt != st::Alternative::two_sided;
        EXPECT_EQ(r.computed, r_gives_a_number) << r.note;
        if (r_gives_a_number) {
          ASSERT_TRUE(r.p_value.has_value());
          EXPECT_EQ(*r.p_value, 1.0);
          ASSERT_TRUE(r.statistic.has_value());
          EXPECT_EQ(*r.statistic, 0.0);
          EXPECT_NE(r.note.find("R's wilcox.test also returns p = 1"), std::string::npos) << r.note;
        } else {
          EXPECT_FALSE(r.p_value.has_value());
          EXPECT_NE(r.note.find("R's wilcox.test returns V = 0 with p-value NaN"),
                    std::string::npos)
              << r.note;
        }
      }
    }
  }
}

TEST(RankTestsWithoutVariance, TwoSampleAllTiedGiveWhatRGives) {
  const std::vector<double> x{3, 3, 3}, y{3, 3, 3, 3};
  for (const std::optional<bool> exact :
       {std::optional<bool>{}, std::optional<bool>{true}, std::optional<bool>{false}}) {
    for (const auto alt :
         {st::Alternative::two_sided, st::Alternative::less, st::Alternative::greater}) {
      for (const bool correct : {true, false}) {
        SCOPED_TRACE(::testing::Message() << "alt " << static_cast<int>(alt) << " correct "
                                          << correct << " exact " << exact.value_or(false));
        const auto r = st::mann_whitney(x, y, with(alt), correct, exact);
        const bool r_gives_a_number = correct && alt != st::Alternative::two_sided;
        EXPECT_EQ(r.computed, r_gives_a_number) << r.note;
        if (r_gives_a_number) {
          ASSERT_TRUE(r.p_value.has_value());
          EXPECT_EQ(*r.p_value, 1.0);
          ASSERT_TRUE(r.statistic.has_value());
          EXPECT_EQ(*r.statistic, 6.0);
          EXPECT_NE(r.note.find("R's wilcox.test also returns p = 1"), std::string::npos) << r.note;
        } else {
          EXPECT_FALSE(r.p_value.has_value());
          EXPECT_NE(r.note.find("R's wilcox.test returns W = 6 with p-value NaN"),
                    std::string::npos)
              << r.note;
        }
      }
    }
  }
}

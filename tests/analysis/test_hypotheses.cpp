// The study's hypotheses (docs/findings.md "Hypotheses"): the paper's H1 and H2 by default, changed
// and added to by ID:KEY=VALUE settings, every bad setting a usage error that names it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "feint/analysis/hypotheses.hpp"
#include "feint/error.hpp"

using feint::UsageError;
using feint::analysis::parse_hypotheses;

TEST(Hypotheses, ThePapersTwoByDefaultExploratoryWithTheConditionsNamed) {
  const auto hs = parse_hypotheses({}, "adaptive", "random");
  ASSERT_EQ(hs.size(), 2u);
  EXPECT_EQ(hs[0].id, "H1");
  EXPECT_EQ(hs[0].statement,
            "People stay deceived longer under adaptive than under random selection (higher error and confusion).");
  EXPECT_EQ(hs[0].measures, (std::vector<std::string>{"error", "confusion"}));
  EXPECT_EQ(hs[0].direction, "greater");
  EXPECT_FALSE(hs[0].confirmatory);
  EXPECT_EQ(hs[1].id, "H2");
  EXPECT_EQ(hs[1].measures, (std::vector<std::string>{"questionnaire"}));
  EXPECT_EQ(hs[1].direction, "two-sided");
}

TEST(Hypotheses, SettingsChangeADefaultAndAddANewOne) {
  const auto hs = parse_hypotheses({"H1:confirmatory=true", "H1:measures=error",
                                    "H3:statement=Confusion is lower under random.", "H3:measures=confusion",
                                    "H3:direction=less"},
                                   "adaptive", "random");
  ASSERT_EQ(hs.size(), 3u);
  EXPECT_TRUE(hs[0].confirmatory);
  EXPECT_EQ(hs[0].measures, (std::vector<std::string>{"error"}));
  EXPECT_EQ(hs[2].id, "H3");
  EXPECT_EQ(hs[2].statement, "Confusion is lower under random.");
  EXPECT_EQ(hs[2].direction, "less");
  EXPECT_FALSE(hs[2].confirmatory);
}

TEST(Hypotheses, EveryBadSettingIsAUsageErrorThatNamesIt) {
  auto message = [](const std::vector<std::string>& s) {
    try {
      parse_hypotheses(s, "A", "B");
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({"H1confirmatory=true"}).find("expected ID:KEY=VALUE"), std::string::npos);
  EXPECT_NE(message({"H1:confirmatory=yes"}).find("'yes' is not true or false"), std::string::npos);
  EXPECT_NE(message({"H1:direction=up"}).find("greater, less or two-sided"), std::string::npos);
  EXPECT_NE(message({"H1:measures=error,speed"}).find("a list of error, confusion, questionnaire"),
            std::string::npos);
  EXPECT_NE(message({"H1:colour=red"}).find("unknown key 'colour'"), std::string::npos);
  EXPECT_NE(message({"H4:direction=less"}).find("hypothesis H4: give its statement and measures"),
            std::string::npos);
}

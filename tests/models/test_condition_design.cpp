// The condition design (feint/models/condition_design.hpp): read off the data when the data leave
// no doubt, checked against the data when declared, and refused with the participant, the lines
// and what to set when they contradict each other.
#include <gtest/gtest.h>

#include "feint/error.hpp"
#include "feint/models/condition_design.hpp"

namespace {

using feint::models::check_condition_design;
using feint::models::ConditionDesign;
using feint::models::Observation;

// Rows (participant, condition) at two iterations each, lines counted from 2 (after a header).
std::vector<Observation> rows(const std::vector<std::pair<std::string, std::string>>& who) {
  std::vector<Observation> out;
  std::uint64_t line = 2;
  for (const auto& [p, c] : who)
    for (long long it = 1; it <= 2; ++it) out.push_back({p, c, it, 0.5, line++});
  return out;
}

std::string message_of(const std::vector<Observation>& obs, std::optional<ConditionDesign> declared) {
  try {
    check_condition_design(obs, declared, "scores.csv");
  } catch (const feint::InvalidData& e) {
    return e.what();
  }
  return "";
}

TEST(ConditionDesign, OneConditionPerParticipantReadsAsBetween) {
  const auto d = check_condition_design(rows({{"P1", "a"}, {"P2", "b"}, {"P3", "a"}, {"P4", "b"}}), std::nullopt, "s");
  EXPECT_EQ(d.design, ConditionDesign::between);
  EXPECT_FALSE(d.declared);
  EXPECT_NE(d.note.find("read off the data: each of the 4 participants saw one condition"), std::string::npos);
  EXPECT_TRUE(d.warnings.empty());
}

TEST(ConditionDesign, EveryParticipantInEveryConditionReadsAsWithin) {
  const auto d = check_condition_design(rows({{"P1", "a"}, {"P1", "b"}, {"P2", "b"}, {"P2", "a"}}), std::nullopt, "s");
  EXPECT_EQ(d.design, ConditionDesign::within);
  EXPECT_NE(d.note.find("each of the 2 participants saw both conditions"), std::string::npos);
  EXPECT_TRUE(d.incomplete.empty());
}

TEST(ConditionDesign, AMixtureIsRefusedUntilDeclared) {
  const auto obs = rows({{"P1", "a"}, {"P1", "b"}, {"P2", "a"}, {"P3", "b"}});
  const std::string m = message_of(obs, std::nullopt);
  // Where the second condition of P1 starts (line 4), who saw one only (P2, line 6), what to set.
  EXPECT_NE(m.find("scores.csv:4: participant 'P1' has trials in 2 conditions but participant 'P2' (line 6)"),
            std::string::npos) << m;
  EXPECT_NE(m.find("design = \"within\""), std::string::npos);
  EXPECT_NE(m.find("design = \"between\""), std::string::npos);
  // Declared within: the incomplete participants are named, not refused.
  const auto d = check_condition_design(obs, ConditionDesign::within, "scores.csv");
  EXPECT_EQ(d.design, ConditionDesign::within);
  EXPECT_TRUE(d.declared);
  ASSERT_EQ(d.incomplete.size(), 2u);
  EXPECT_EQ(d.incomplete[0], "P2 (a only)");
  EXPECT_EQ(d.incomplete[1], "P3 (b only)");
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("2 participants did not see every condition"), std::string::npos);
  EXPECT_NE(d.note.find("1 of 3 participants saw every condition"), std::string::npos);
}

// Three conditions, everyone in two or more but not everyone in all three: refused with the
// participant who saw fewer (this crashed when nobody saw a single condition).
TEST(ConditionDesign, AMixtureOfThreeConditionsWithNobodyInOneNamesWhoSawFewer) {
  const auto obs = rows({{"P1", "a"}, {"P1", "b"}, {"P1", "c"}, {"P2", "a"}, {"P2", "b"}});
  const std::string m = message_of(obs, std::nullopt);
  EXPECT_NE(m.find("participant 'P1' has trials in 3 conditions but participant 'P2' (line 8) in 2 of the 3 only"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("design = \"within\""), std::string::npos);
}

TEST(ConditionDesign, DeclaredBetweenRefusesAParticipantInTwoConditions) {
  const auto obs = rows({{"P1", "a"}, {"P2", "b"}, {"P2", "a"}});
  const std::string m = message_of(obs, ConditionDesign::between);
  EXPECT_NE(m.find("scores.csv:6: participant 'P2' has trials in condition 'a' (line 6) and in 'b' (line 4)"),
            std::string::npos) << m;
  EXPECT_NE(m.find("set design = \"within\""), std::string::npos);
}

TEST(ConditionDesign, DeclaredWithinRefusesDataWithNobodyInTwoConditions) {
  const std::string m = message_of(rows({{"P1", "a"}, {"P2", "b"}}), ConditionDesign::within);
  EXPECT_NE(m.find("no participant has trials in two conditions (2 participants, each in one of 2 conditions)"),
            std::string::npos) << m;
  EXPECT_NE(m.find("set design = \"between\""), std::string::npos);
}

TEST(ConditionDesign, AConditionWithOneParticipantIsWarnedAbout) {
  const auto d = check_condition_design(rows({{"P1", "a"}, {"P2", "a"}, {"P3", "b"}}), std::nullopt, "s");
  ASSERT_EQ(d.single_participant_conditions, std::vector<std::string>{"b"});
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("condition b has one participant only"), std::string::npos);
}

TEST(ConditionDesign, RowsWithoutConditionsHaveNoDesign) {
  const auto d = check_condition_design(rows({{"P1", ""}, {"P2", ""}}), std::nullopt, "s");
  EXPECT_EQ(d.design, ConditionDesign::between);
  EXPECT_TRUE(d.note.empty());
  EXPECT_TRUE(d.warnings.empty());
}

TEST(ConditionDesign, ParsesTheSettingAndRefusesOtherWords) {
  EXPECT_EQ(feint::models::parse_condition_design(" Within "), ConditionDesign::within);
  EXPECT_EQ(feint::models::parse_condition_design("between"), ConditionDesign::between);
  EXPECT_FALSE(feint::models::parse_condition_design(""));
  try {
    feint::models::parse_condition_design("crossed");
    FAIL();
  } catch (const feint::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--design 'crossed': expected between"), std::string::npos);
  }
}

}  // namespace

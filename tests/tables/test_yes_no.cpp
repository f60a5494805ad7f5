// The yes/no questions of questionnaire_yesno.csv: loaded as `feint collect` writes them, counted
// per condition, compared by Fisher's exact test and the chi-square test, and every rejection path.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "feint/error.hpp"
#include "feint/tables/yes_no.hpp"

namespace ft = feint::tables;
namespace fst = feint::stats;

namespace {

std::string write_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("feint_yes_no_" + name);
  std::ofstream(path) << text;
  return path.string();
}

/// 12 of 20 adaptive and 5 of 20 random answered yes (one random answer empty); "Yes"/"NO" mixed.
std::string collect_file() {
  std::string text = "participant,condition,intentional\n";
  for (int i = 0; i < 20; ++i) text += "A" + std::to_string(i) + ",adaptive," + (i < 12 ? "Yes" : "no") + "\n";
  for (int i = 0; i < 21; ++i)
    text += "R" + std::to_string(i) + ",random," + (i == 20 ? "" : i < 5 ? "yes" : "NO") + "\n";
  return write_file("collect.csv", text);
}

}  // namespace

TEST(YesNoTable, CountsYesPerConditionAndLeavesEmptyAnswersOut) {
  const auto a = ft::analyze_yes_no_file(collect_file(), {});
  ASSERT_EQ(a.questions, std::vector<std::string>{"intentional"});
  ASSERT_EQ(a.summaries.size(), 2u);
  EXPECT_EQ(a.summaries[0].group, "adaptive");
  EXPECT_EQ(a.summaries[0].proportion.x, 12u);
  EXPECT_EQ(a.summaries[0].proportion.n, 20u);
  EXPECT_EQ(a.summaries[1].proportion.x, 5u);
  EXPECT_EQ(a.summaries[1].proportion.n, 20u);
  EXPECT_EQ(a.summaries[1].missing, 1u);
  EXPECT_TRUE(a.rows.empty());  // nothing compared unless asked
}

TEST(YesNoTable, TwoConditionsAreComparedByFisherThenChiSquare) {
  ft::YesNoSettings s;
  s.compare = {"adaptive", "random"};
  const auto a = ft::analyze_yes_no_file(collect_file(), s);
  ASSERT_EQ(a.rows.size(), 2u);
  // R: fisher.test(matrix(c(12, 5, 8, 15), 2))$p.value = 0.053550992594374118 (tests/golden/yesno).
  EXPECT_EQ(a.rows[0].result.test, "fisher_exact");
  EXPECT_NEAR(*a.rows[0].result.p_value, 0.053550992594374118, 1e-14);
  EXPECT_EQ(a.rows[0].label, "n.s.");
  // prop.test(c(12, 5), c(20, 20)): X-squared = 3.6828644501278776, p = 0.054974328721694277.
  EXPECT_EQ(a.rows[1].result.test, "prop_test");
  EXPECT_NEAR(*a.rows[1].result.statistic, 3.6828644501278776, 1e-13);
  s.alpha = 0.06;
  EXPECT_EQ(ft::analyze_yes_no_file(collect_file(), s).rows[0].label, "A>B");
  s.compare = {"random", "adaptive"};
  EXPECT_EQ(ft::analyze_yes_no_file(collect_file(), s).rows[0].label, "A<B");
}

TEST(YesNoTable, RendersEveryFormatWithTheNumbers) {
  ft::YesNoSettings s;
  s.compare = {"adaptive", "random"};
  const auto a = ft::analyze_yes_no_file(collect_file(), s);
  const auto md = ft::render_yes_no(a, ft::OutputFormat::markdown);
  EXPECT_NE(md.find("| intentional | adaptive | 12 | 20 | 60% | [0.36, 0.81] | [0.39, 0.78] |"), std::string::npos) << md;
  EXPECT_NE(md.find("OR = 4.32"), std::string::npos) << md;
  EXPECT_NE(md.find("χ²(1) = 3.68"), std::string::npos) << md;
  const auto csv = ft::render_yes_no(a, ft::OutputFormat::csv);
  EXPECT_NE(csv.find("intentional,random,5,20,1,0.25,"), std::string::npos) << csv;
  const auto json = ft::render_yes_no(a, ft::OutputFormat::json);
  EXPECT_NE(json.find("\"tests\": ["), std::string::npos) << json;
  EXPECT_NE(json.find("\"test\": \"fisher_exact\""), std::string::npos) << json;
}

TEST(YesNoTable, AnAnswerThatIsNotYesOrNoNamesTheFileRowAndColumn) {
  const auto path = write_file("maybe.csv", "participant,condition,intentional\nP1,adaptive,yes\nP2,random,maybe\n");
  try {
    ft::analyze_yes_no_file(path, {});
    FAIL() << "accepted 'maybe'";
  } catch (const feint::InvalidData& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path), std::string::npos) << m;
    EXPECT_NE(m.find(":3"), std::string::npos) << m;
    EXPECT_NE(m.find("intentional"), std::string::npos) << m;
  }
}

TEST(YesNoTable, ComparisonsThatCannotBeMadeAreRefused) {
  ft::YesNoSettings s;
  s.compare = {"adaptive", "fixed"};
  EXPECT_THROW(ft::analyze_yes_no_file(collect_file(), s), feint::UsageError);
  s.compare = {"adaptive", "adaptive"};
  EXPECT_THROW(ft::analyze_yes_no_file(collect_file(), s), feint::UsageError);
  s.compare = {"adaptive", "random"};
  const auto twice = write_file("twice.csv", "participant,condition,intentional\nP1,adaptive,yes\nP1,random,no\n");
  EXPECT_THROW(ft::analyze_yes_no_file(twice, s), feint::InvalidData);
  const auto none = write_file("none.csv", "participant,intentional\nP1,yes\nP2,no\n");
  EXPECT_THROW(ft::analyze_yes_no_file(none, s), feint::UsageError);
  s.compare.reset();
  EXPECT_EQ(ft::analyze_yes_no_file(none, s).summaries.at(0).proportion.x, 1u);
}

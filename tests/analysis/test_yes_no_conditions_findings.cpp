// The yes/no findings across three or more conditions (docs/yes-no.md "The finding"): the finding
// H2-yesno-QUESTION rests on the omnibus test (Fisher's exact test of the C x 2 table between
// participants, Cochran's Q within) and says which way, how much and how sure; each pair's finding
// is Holm-adjusted over the pairs and protected by it. The numbers are checked against the tables
// layer and against hand computations; the protection on answers where Cochran's Q is not
// significant (p = 0.0617) but a pair's Holm-adjusted McNemar p is (0.0469), and where the same
// pair is claimed once alpha lets the omnibus test through.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "feint/analysis/results.hpp"
#include "feint/analysis/study_findings.hpp"
#include "feint/tables/yes_no.hpp"

using namespace feint;
using analysis::Finding;
using analysis::Strength;

namespace {

std::string write_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("feint_yes_no_findings_" + name);
  std::ofstream(path) << text;
  return path.string();
}

// 11 of 12 adaptive, 2 of 12 random and 6 of 12 fixed-block answered yes.
std::string between_file() {
  std::string text = "participant,condition,intentional\n";
  const std::vector<std::pair<std::string, int>> conditions = {{"adaptive", 11}, {"random", 2}, {"fixed-block", 6}};
  int id = 0;
  for (const auto& [c, yes] : conditions)
    for (int i = 0; i < 12; ++i) text += "P" + std::to_string(++id) + "," + c + "," + (i < yes ? "yes" : "no") + "\n";
  return write_file("between.csv", text);
}

// 18 participants after adaptive, random and fixed-block: G = (13, 6, 11), N = 30, sum L^2 = 62,
// Q = 2 (3 * 326 - 900) / (90 - 62) = 5.5714, p = exp(-Q / 2) = 0.0617; adaptive against random
// has b = 7, c = 0: McNemar's exact p = 2 / 2^7 = 0.015625, Holm over the three pairs 0.046875.
std::string within_file() {
  const int answers[18][3] = {{1, 0, 0}, {1, 0, 0}, {1, 1, 1}, {0, 0, 1}, {1, 1, 1}, {1, 1, 0},
                              {1, 1, 0}, {0, 0, 1}, {1, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 0},
                              {0, 0, 1}, {1, 1, 1}, {1, 0, 1}, {0, 0, 1}, {1, 1, 1}, {1, 0, 1}};
  const char* conditions[3] = {"adaptive", "random", "fixed-block"};
  std::string text = "participant,condition,intentional\n";
  for (int i = 0; i < 18; ++i)
    for (int j = 0; j < 3; ++j)
      text += "P" + std::to_string(i + 1) + "," + conditions[j] + "," + (answers[i][j] ? "yes" : "no") + "\n";
  return write_file("within.csv", text);
}

std::vector<Finding> findings_of(const tables::YesNoAnalysis& a, double alpha = 0.05) {
  analysis::StudyResults r;
  r.yes_no = a;
  analysis::WordingRules rules;
  rules.alpha = alpha;
  return analysis::study_findings(r, {}, rules);
}

const Finding* by_id(const std::vector<Finding>& fs, const std::string& id) {
  for (const auto& f : fs)
    if (f.id == id) return &f;
  return nullptr;
}

}  // namespace

TEST(YesNoConditionsFindings, TheQuestionRestsOnFishersTestOfTheWholeTable) {
  const auto a = tables::analyze_yes_no_file(between_file(), {});
  ASSERT_EQ(a.omnibus.size(), 2u);  // Fisher's exact test, then the chi-square test
  const auto fs = findings_of(a);
  const Finding* f = by_id(fs, "H2-yesno-intentional");
  ASSERT_NE(f, nullptr);
  EXPECT_TRUE(f->omnibus);
  EXPECT_EQ(f->test, "Fisher's exact test");
  EXPECT_EQ(*f->p, *a.omnibus[0].result.p_value);
  EXPECT_NEAR(*f->p, 0.0012016111759788324, 1e-15);  // R: fisher.test(matrix(c(11, 2, 6, 1, 10, 6), 3))
  EXPECT_EQ(f->strength, Strength::evidence_for_difference);
  // How much: the chi-square test's bias-corrected Cramér's V. By hand: E = 12 * 19 / 36 = 6.333
  // yes, 5.667 no per condition; X^2 = (4.667^2 + 4.333^2 + 0.333^2)(1/6.333 + 1/5.667) = 13.60.
  ASSERT_TRUE(f->effect_size.has_value());
  EXPECT_EQ(f->effect_size->name, "cramers_v");
  const double x2 = (std::pow(11 - 19.0 / 3, 2) + std::pow(2 - 19.0 / 3, 2) + std::pow(6 - 19.0 / 3, 2)) *
                    (3.0 / 19 + 3.0 / 17);
  EXPECT_NEAR(*a.omnibus[1].result.statistic, x2, 1e-12);
  EXPECT_NEAR(f->effect_size->value, std::sqrt((x2 / 36 - 2.0 / 35) / (34.0 / 35)), 1e-14);
  // Which way, in words; no difference of two sides is claimed for three conditions.
  EXPECT_NE(f->sentence.find("yes 92% of 12 (adaptive), 17% of 12 (random), 50% of 12 (fixed-block): most often in "
                             "adaptive, least in random"),
            std::string::npos)
      << f->sentence;
  EXPECT_NE(f->sentence.find("Cram\u00e9r's V = ."), std::string::npos) << f->sentence;
  // effectsize's interval of V is one-sided (upper bound 1), and the sentence says so.
  EXPECT_EQ(f->effect_size->ci_high, 1.0);
  EXPECT_NE(f->sentence.find(", one-sided 95% CI [."), std::string::npos) << f->sentence;
  EXPECT_NE(f->sentence.find("\u03c7\u00b2(2) = 13.60"), std::string::npos) << f->sentence;
  EXPECT_TRUE(f->direction.empty());
  EXPECT_FALSE(f->estimate.has_value());
  // Each pair: Fisher's 2 x 2 test, Holm-adjusted over the three pairs.
  const Finding* ab = by_id(fs, "H2-yesno-pair-intentional-adaptive-random");
  const Finding* ac = by_id(fs, "H2-yesno-pair-intentional-adaptive-fixed-block");
  ASSERT_NE(ab, nullptr);
  ASSERT_NE(ac, nullptr);
  EXPECT_EQ(ab->strength, Strength::evidence_for_difference);
  EXPECT_EQ(ab->direction, "adaptive > random");
  EXPECT_NEAR(*ab->p_adjusted, 0.0019325808126454259, 1e-15);  // R: 3 x fisher.test's p, the smallest of three
  EXPECT_NE(ab->sentence.find("Holm-adjusted p"), std::string::npos) << ab->sentence;
  EXPECT_EQ(ac->strength, Strength::no_evidence_either_way);  // 11/12 vs 6/12: p = .069
}

TEST(YesNoConditionsFindings, WithinParticipantsCochransQProtectsThePairs) {
  tables::YesNoSettings s;
  s.paired = true;
  const auto a = tables::analyze_yes_no_file(within_file(), s);
  ASSERT_EQ(a.omnibus.size(), 1u);
  const auto& q = a.omnibus[0].result;
  ASSERT_EQ(q.test, "cochran_q");
  EXPECT_NEAR(*q.statistic, 2.0 * 78 / 28, 1e-14);
  EXPECT_NEAR(*q.p_value, std::exp(-78.0 / 28), 1e-15);
  const auto fs = findings_of(a);
  const Finding* f = by_id(fs, "H2-yesno-intentional");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->test, "Cochran's Q test");
  EXPECT_EQ(f->statistics, "Q(2) = 5.57, p = .062");
  EXPECT_EQ(f->strength, Strength::no_evidence_either_way);
  // adaptive against random: McNemar's exact p Holm-adjusted 0.046875 < .05, withheld by Q.
  const Finding* ab = by_id(fs, "H2-yesno-pair-intentional-adaptive-random");
  ASSERT_NE(ab, nullptr);
  EXPECT_EQ(ab->test, "McNemar's exact test");
  EXPECT_NEAR(*ab->p_adjusted, 0.046875, 1e-15);
  EXPECT_EQ(ab->strength, Strength::no_evidence_either_way);
  ASSERT_EQ(ab->warnings.size(), 1u);
  EXPECT_NE(ab->warnings[0].find("omnibus test of condition on intentional did not show a difference"),
            std::string::npos);
  EXPECT_EQ(a.rows[0].label, "n.s.");  // the table withholds it too
  // With alpha = .07 Cochran's Q shows a difference, and the same pair is claimed.
  s.alpha = 0.07;
  const auto loose = tables::analyze_yes_no_file(within_file(), s);
  EXPECT_EQ(loose.rows[0].label, "A>B");
  const Finding* claimed = by_id(findings_of(loose, 0.07), "H2-yesno-pair-intentional-adaptive-random");
  ASSERT_NE(claimed, nullptr);
  EXPECT_EQ(claimed->strength, Strength::evidence_for_difference);
}

TEST(YesNoConditionsFindings, TwoConditionsAreUnchangedAndAParticipantInTwoConditionsIsNoted) {
  // Two conditions named: one finding per question, no omnibus test (as before).
  tables::YesNoSettings s;
  s.compare = std::pair<std::string, std::string>{"adaptive", "random"};
  const auto two = tables::analyze_yes_no_file(between_file(), s);
  EXPECT_TRUE(two.omnibus.empty());
  const auto fs = findings_of(two);
  ASSERT_NE(by_id(fs, "H2-yesno-intentional"), nullptr);
  EXPECT_FALSE(by_id(fs, "H2-yesno-intentional")->omnibus);
  EXPECT_EQ(by_id(fs, "H2-yesno-pair-intentional-adaptive-random"), nullptr);
  // Between participants, the within file has each participant in three conditions: the study's
  // analysis goes on with the answers described, and the note says why they were not compared.
  const auto shared = tables::analyze_yes_no_file(within_file(), {});
  EXPECT_TRUE(shared.omnibus.empty());
  EXPECT_TRUE(shared.rows.empty());
  EXPECT_NE(shared.notes.back().find("not compared: participant P1 answered in both conditions"), std::string::npos)
      << shared.notes.back();
  EXPECT_NE(tables::render_yes_no(shared, tables::OutputFormat::text).find("not compared"), std::string::npos);
}

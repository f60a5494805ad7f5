// The yes/no question of a study folder (questionnaire_yesno.csv, as `feint collect` and
// `feint simulate study` write it) reaches the results, the findings and the tables of
// `feint analyze` with no setting: on the demo, with its numbers recomputed from the file.
#include <gtest/gtest.h>

#include <string>

#include "feint/analysis/analyze.hpp"
#include "feint/analysis/study.hpp"
#include "feint/stats/proportions.hpp"

namespace analysis = feint::analysis;

namespace {

const std::string kDemo = std::string(FEINT_SOURCE_DIR) + "/data/demo";

const analysis::StudyResults& demo() {
  static const analysis::StudyResults r = [] {
    analysis::AnalysisSettings s;  // as data/demo/feint.toml
    s.compare = "adaptive,random";
    s.likert.reference = 3.5;
    return analysis::analyze(analysis::load_study(kDemo, s), "test");
  }();
  return r;
}

}  // namespace

TEST(YesNoFindings, TheDemoComparesItsYesNoQuestionWithFishersTest) {
  const auto& r = demo();
  ASSERT_TRUE(r.yes_no.has_value());
  // data/demo/questionnaire_yesno.csv: 18 of 30 adaptive, 23 of 30 random answered yes.
  ASSERT_EQ(r.yes_no->summaries.size(), 2u);
  EXPECT_EQ(r.yes_no->summaries[0].proportion.x, 18u);
  EXPECT_EQ(r.yes_no->summaries[1].proportion.x, 23u);
  const auto fisher = feint::stats::fisher_exact({18, 30, 23, 30});
  const analysis::Finding* f = nullptr;
  for (const auto& x : r.findings)
    if (x.id == "H2-yesno-intentional") f = &x;
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->test, "Fisher's exact test");
  EXPECT_EQ(*f->p, *fisher.p_value);
  EXPECT_EQ(f->direction, "adaptive < random");
  ASSERT_TRUE(f->effect_size.has_value());
  EXPECT_EQ(f->effect_size->name, "odds_ratio");
  EXPECT_EQ(f->effect_size->value, *fisher.estimate);
  EXPECT_EQ(f->strength, analysis::Strength::no_evidence_either_way);
  EXPECT_NE(f->sentence.find("Intentional (yes/no): adaptive vs random: no evidence either way (yes 60% of 30 vs "
                             "77% of 30; odds ratio 0.46, 95% CI [0.13, 1.59]; Fisher's exact test, p = .267;"),
            std::string::npos)
      << f->sentence;
}

// Every finding of a study carries the numbers a Results paragraph needs (docs/findings.md
// "Fields"): which way, how much, how sure; and the study's hypotheses say which are confirmatory.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "feint/analysis/analyze.hpp"
#include "feint/error.hpp"

using namespace feint;

namespace {

const std::string kDemo = std::string(FEINT_SOURCE_DIR) + "/data/demo";

const analysis::StudyResults& demo_results() {
  static const analysis::StudyResults r = [] {
    analysis::AnalysisSettings s;  // as data/demo/feint.toml, H1 declared confirmatory
    s.compare = "adaptive,random";
    s.likert.reference = 3.5;
    s.hypotheses = {"H1:confirmatory=true"};
    return analysis::analyze(analysis::load_study(kDemo, s), "test");
  }();
  return r;
}

const analysis::Finding* find(const std::string& id) {
  for (const auto& f : demo_results().findings)
    if (f.id == id) return &f;
  return nullptr;
}

}  // namespace

TEST(FindingFields, TheConditionEffectSaysWhichWayHowMuchAndHowSure) {
  for (const std::string metric : {"error", "confusion"}) {
    const analysis::Finding* f = find("H1-model-condition-" + metric);
    ASSERT_NE(f, nullptr) << metric;
    ASSERT_TRUE(f->means && f->estimate && f->ci_low && f->ci_high) << metric;
    // The difference is that of the two marginal means, inside its interval, in the stated direction.
    EXPECT_NEAR(*f->estimate, f->means->first - f->means->second, 1e-9) << metric;
    EXPECT_LT(*f->ci_low, *f->estimate);
    EXPECT_GT(*f->ci_high, *f->estimate);
    EXPECT_EQ(f->contrast, "adaptive - random");
    EXPECT_EQ(f->direction, *f->estimate > 0 ? "adaptive > random" : "adaptive < random");
    ASSERT_TRUE(f->effect_size);
    EXPECT_EQ(f->effect_size->name, "eta2_p");
    EXPECT_GT(f->effect_size->value, 0);
    EXPECT_LT(f->effect_size->value, 1);
    ASSERT_TRUE(f->effect_size->ci_low && f->effect_size->ci_high);
    EXPECT_LE(*f->effect_size->ci_low, f->effect_size->value);
    ASSERT_TRUE(f->bf10) << f->bf_note;
    EXPECT_GT(*f->bf10, 0);
    EXPECT_NE(f->bf_note.find("participants' mean scores"), std::string::npos);
    ASSERT_TRUE(f->p && f->p_adjusted);
    EXPECT_GE(*f->p_adjusted, *f->p);
    EXPECT_NE(f->sentence.find("difference"), std::string::npos) << f->sentence;
    EXPECT_TRUE(f->confirmatory);
  }
}

TEST(FindingFields, TheQuestionnaireRestsOnItsRankTestWithTheTTestSecondary) {
  int compared = 0;
  for (const auto& f : demo_results().findings) {
    if (f.id.rfind("H2-compare-", 0) != 0) continue;
    ++compared;
    EXPECT_EQ(f.test, "Mann-Whitney test") << f.id;
    ASSERT_TRUE(f.effect_size) << f.id;
    EXPECT_EQ(f.effect_size->name, "r_rb");
    EXPECT_TRUE(f.effect_size->ci_low && f.effect_size->ci_high) << f.id;
    ASSERT_TRUE(f.means && f.estimate) << f.id;
    EXPECT_NEAR(*f.estimate, f.means->first - f.means->second, 1e-12);
    EXPECT_NE(f.bf_note.find("secondary"), std::string::npos) << f.bf_note;
    EXPECT_FALSE(f.confirmatory) << "H2 was not declared confirmatory";
    EXPECT_EQ(f.direction.rfind("adaptive ", 0), 0u) << f.direction;
  }
  EXPECT_GT(compared, 0);
}

TEST(FindingFields, EveryComputedFindingHasItsTestPAndAnEffectSizeOrSaysWhy) {
  for (const auto& f : demo_results().findings) {
    if (f.strength == analysis::Strength::not_computable) continue;
    EXPECT_FALSE(f.test.empty()) << f.id;
    EXPECT_TRUE(f.p.has_value()) << f.id;
    EXPECT_TRUE(f.bf10.has_value() || !f.bf_note.empty()) << f.id << ": a missing BF needs its reason";
    if (f.effect_size) {
      EXPECT_TRUE(std::isfinite(f.effect_size->value)) << f.id;
    }
  }
  const analysis::Finding* family = find("H1-iterations-error");
  ASSERT_NE(family, nullptr);
  EXPECT_EQ(family->member.rfind("test ", 0), 0u);
  EXPECT_EQ(family->contrast, "adaptive - random");
  ASSERT_TRUE(family->effect_size);
  EXPECT_EQ(family->effect_size->name, "d");
}

TEST(FindingFields, HypothesesAreTheStudysWithTheDefaultsNamed) {
  const auto& hs = demo_results().hypotheses;
  ASSERT_EQ(hs.size(), 2u);
  EXPECT_TRUE(hs[0].confirmatory);
  EXPECT_FALSE(hs[1].confirmatory);
  EXPECT_NE(hs[0].statement.find("adaptive"), std::string::npos);
}

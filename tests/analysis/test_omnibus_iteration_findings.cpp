// Three or more conditions with no pair named: H1-iterations-<metric> is the family of Table 1's
// per-iteration omnibus tests (Welch's F between, the GG repeated-measures F within), adjusted by
// the table's step-down maxF, or by Holm with a warning when the family has a note
// (docs/findings.md "Three or more conditions: the maxF family").
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "feint/analysis/analyze.hpp"
#include "feint/analysis/calibration.hpp"
#include "feint/analysis/study_findings.hpp"
#include "feint/sim/options.hpp"
#include "feint/sim/study.hpp"
#include "feint/tables/table1.hpp"

using namespace feint;
using analysis::Finding;
using analysis::Strength;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

const Finding* by_id(const std::vector<Finding>& fs, const std::string& id) {
  for (const auto& f : fs)
    if (f.id == id) return &f;
  return nullptr;
}

// 3 + 3 + 3 participants, two iterations. Iteration 1: three tight clusters (a near 1, b near 3,
// c near 5, each with variance 0.01); iteration 2: the values 1..9 dealt so that every condition's
// mean is 5 (F = 0).
analysis::StudyResults clusters() {
  analysis::StudyResults r;
  r.scores.metrics = {"error"};
  r.scores.has_condition = true;
  const std::map<std::string, std::vector<double>> first = {
      {"a", {0.9, 1.0, 1.1}}, {"b", {2.9, 3.0, 3.1}}, {"c", {4.9, 5.0, 5.1}}};
  const std::map<std::string, std::vector<double>> second = {{"a", {1, 5, 9}}, {"b", {2, 6, 7}}, {"c", {3, 4, 8}}};
  for (const auto& [c, v] : first)
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::string who = c + std::to_string(i);
      r.scores.records.push_back({who, c, 1, {v[i]}, 0});
      r.scores.records.push_back({who, c, 2, {second.at(c)[i]}, 0});
    }
  tables::Table1Options o;
  o.metrics = {{"error", 0.5}};
  o.design = models::ConditionDesign::between;
  r.table1 = tables::build_table1(r.scores, o);
  return r;
}

}  // namespace

TEST(OmnibusIterationFindings, ThreeClustersGiveTheExactMaxFFractionAndNameTheHighestAndLowest) {
  const auto r = clusters();
  ASSERT_TRUE(r.table1.conditions);
  const auto fs = analysis::study_findings(r, {{"error", 0.5}});
  const Finding* f = by_id(fs, "H1-iterations-error");
  ASSERT_NE(f, nullptr);
  // 9! / (3! 3! 3!) = 1,680 relabellings, all enumerated. Only the observed partition's 3! = 6
  // namings reach iteration 1's F (any other partition mixes two clusters in a group, and
  // iteration 2's largest F, about 23, is far below it): p = 6 / 1680.
  EXPECT_TRUE(contains(f->sentence, "Westfall\u2013Young maxF-adjusted over 2 iterations, all 1,680 relabellings of "
                                    "the participants between the conditions"))
      << f->sentence;
  ASSERT_TRUE(f->p_adjusted);
  EXPECT_NEAR(*f->p_adjusted, 6.0 / 1680.0, 1e-12);
  EXPECT_EQ(*f->p_adjusted, *r.table1.conditions->primary(0, 0).p_maxf);
  EXPECT_EQ(f->member, "test 1");
  EXPECT_EQ(f->strength, Strength::evidence_for_difference) << f->sentence;
  EXPECT_TRUE(contains(f->sentence, "evidence for a difference in 1 (tests 1)")) << f->sentence;
  EXPECT_TRUE(contains(f->sentence, "Per-iteration Welch F tests of error across a, b and c")) << f->sentence;
  // Which way: c highest, a lowest, at the one iteration with evidence.
  EXPECT_EQ(f->direction, "c > b > a");
  EXPECT_TRUE(contains(f->sentence, "M = 1.00 (a), 3.00 (b), 5.00 (c)")) << f->sentence;
  EXPECT_TRUE(contains(f->sentence, "Over the 1 iteration with evidence, c was highest on average (M = 5.00; highest at 1 of 1) and "
                                    "a lowest (M = 1.00; lowest at 1 of 1)."))
      << f->sentence;
  // How much: the one-way ANOVA's omega squared, F = 12 / 0.01 = 1200 on (2, 6):
  // (F - 1) df1 / (F df1 + df2 + 1) = 2398 / 2407.
  ASSERT_TRUE(f->effect_size);
  EXPECT_EQ(f->effect_size->name, "omega2");
  EXPECT_NEAR(f->effect_size->value, 2398.0 / 2407.0, 1e-12);
  EXPECT_TRUE(contains(f->sentence, "\u03c9\u00b2 = 1.00, one-sided 95% CI [")) << f->sentence;
  EXPECT_TRUE(f->warnings.empty());
}

TEST(OmnibusIterationFindings, AFamilyWithANoteFallsBackToHolmWithAWarning) {
  auto r = clusters();
  r.table1.conditions->families[0].note = "iteration 1's F could not be reproduced from the participants' values";
  const auto fs = analysis::study_findings(r, {{"error", 0.5}});
  const Finding* f = by_id(fs, "H1-iterations-error");
  ASSERT_NE(f, nullptr);
  EXPECT_TRUE(contains(f->sentence, "(Holm-corrected over 2 tests)")) << f->sentence;
  ASSERT_EQ(f->warnings.size(), 1u);
  EXPECT_EQ(f->warnings[0], "The per-iteration omnibus tests of error are Holm-corrected, not maxF-adjusted: "
                            "iteration 1's F could not be reproduced from the participants' values.");
  // Holm over two tests: the smaller p doubled.
  const auto& t = r.table1.conditions->primary(0, 0).row.result;
  ASSERT_TRUE(f->p_adjusted && t.p_value);
  EXPECT_DOUBLE_EQ(*f->p_adjusted, std::min(1.0, 2 * *t.p_value));
}

TEST(OmnibusIterationFindings, DemoThreeHasTheFamilyOfEachMetricAtTheTablesMaxF) {
  analysis::AnalysisSettings s;  // as data/demo-three/feint.toml
  s.design = "between";
  s.scoring.norm = "raw";
  s.metrics = {"error=0.5", "confusion=0.95@raw"};
  const auto r = analysis::analyze(analysis::load_study(std::string(FEINT_SOURCE_DIR) + "/data/demo-three", s), "test");
  ASSERT_TRUE(r.table1.conditions);
  const auto& c = *r.table1.conditions;
  ASSERT_EQ(c.conditions.size(), 3u);
  ASSERT_FALSE(c.within);
  for (std::size_t m = 0; m < c.metrics.size(); ++m) {
    SCOPED_TRACE(c.metrics[m]);
    const Finding* f = by_id(r.findings, "H1-iterations-" + c.metrics[m]);
    ASSERT_NE(f, nullptr);
    EXPECT_EQ(f->hypothesis, "H1");
    EXPECT_EQ(f->measure, c.metrics[m]);
    ASSERT_EQ(f->member.rfind("test ", 0), 0u) << f->member;
    const std::size_t i = std::stoul(f->member.substr(5)) - 1;
    ASSERT_TRUE(f->p_adjusted && c.primary(i, m).p_maxf);
    EXPECT_EQ(*f->p_adjusted, *c.primary(i, m).p_maxf);
    // The member is the family's smallest maxF p, and the strength is the family's.
    bool any = false;
    for (std::size_t j = 0; j < c.iterations.size(); ++j) {
      if (const auto& p = c.primary(j, m).p_maxf) {
        EXPECT_GE(*p, *f->p_adjusted);
        any = any || *p < 0.05;
      }
    }
    EXPECT_EQ(f->strength == Strength::evidence_for_difference, any) << f->sentence;
    EXPECT_TRUE(contains(f->sentence, "across adaptive, random and fixed-block")) << f->sentence;
    EXPECT_TRUE(contains(f->sentence, "maxF-adjusted over 20 iterations")) << f->sentence;
    EXPECT_TRUE(contains(f->sentence, "relabellings of the participants between the conditions")) << f->sentence;
    for (const std::string name : {"(adaptive)", "(random)", "(fixed-block)"})
      EXPECT_TRUE(contains(f->sentence, name)) << f->sentence;
    EXPECT_TRUE(contains(f->sentence, any ? "with evidence, " : "Over all 20 iterations, ")) << f->sentence;
    ASSERT_TRUE(f->effect_size);
    EXPECT_EQ(f->effect_size->name, "omega2");
    EXPECT_EQ(f->effect_size->value, *(&c.primary(i, m))[1].omega_squared);
  }
}

TEST(OmnibusIterationFindings, AWithinStudyOfThreeConditionsPermutesTheConditionsWithinParticipants) {
  sim::StudyOptions o;  // feint simulate study --design within --conditions a=random,b=random,c=random
  o.design = "within";
  o.conditions = "a=random,b=random,c=random";
  o.participants = 6;
  o.iterations = 4;
  o.seed = 7;
  const auto dir = std::filesystem::temp_directory_path() / "feint-test-omnibus-within";
  std::filesystem::remove_all(dir);
  sim::write_study(sim::study_settings(o), dir.string());
  analysis::AnalysisSettings s;
  s.design = "within";
  s.scoring.norm = "raw";
  s.metrics = {"error=0.5", "confusion=0.95@raw"};
  const auto r = analysis::analyze(analysis::load_study(dir.string(), s), "test");
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(r.table1.conditions);
  const auto& c = *r.table1.conditions;
  ASSERT_TRUE(c.within);
  for (std::size_t m = 0; m < c.metrics.size(); ++m) {
    SCOPED_TRACE(c.metrics[m]);
    const Finding* f = by_id(r.findings, "H1-iterations-" + c.metrics[m]);
    ASSERT_NE(f, nullptr);
    // (3!)^6 = 46,656 permutations: 9,999 drawn with the observed one.
    EXPECT_TRUE(contains(f->sentence, "Per-iteration repeated-measures F tests (Greenhouse\u2013Geisser) of "))
        << f->sentence;
    EXPECT_TRUE(contains(f->sentence, "Westfall\u2013Young maxF-adjusted over 4 iterations, 10,000 permutations of "
                                      "the conditions within each participant drawn at random, seed 20261126"))
        << f->sentence;
    const std::size_t i = std::stoul(f->member.substr(5)) - 1;
    ASSERT_TRUE(f->p_adjusted && c.primary(i, m).p_maxf);
    EXPECT_EQ(*f->p_adjusted, *c.primary(i, m).p_maxf);
    ASSERT_TRUE(f->effect_size);
    EXPECT_EQ(f->effect_size->name, "eta2_G");
    EXPECT_EQ(f->effect_size->value, *c.primary(i, m).ges);
    // The interval is the table's (effectsize's, checked against R in test_table1_conditions).
    ASSERT_TRUE(f->effect_size->ci_low && c.primary(i, m).ges_low);
    EXPECT_EQ(*f->effect_size->ci_low, *c.primary(i, m).ges_low);
    EXPECT_EQ(f->effect_size->ci_high, c.primary(i, m).ges_high);
    EXPECT_TRUE(contains(f->sentence, "generalized \u03b7\u00b2 = ")) << f->sentence;
  }
}

TEST(OmnibusIterationFindings, TheCalibrationCountsTheFamilyAsAHeadlineOfThreeConditions) {
  sim::StudyOptions o;  // as bench/findings_calibration ... between a=random,b=random,c=random
  o.conditions = "a=random,b=random,c=random";
  o.participants = 4;
  o.iterations = 4;
  o.lambda = 0;
  auto settings = analysis::calibration_analysis_settings();
  settings.compare.clear();
  const auto out = analysis::calibration_study(o, settings);
  for (const std::string m : {"error", "confusion"}) {
    const auto it = std::find(out.families.begin(), out.families.end(),
                              "H1 per-iteration omnibus F (maxF over iterations): " + m);
    ASSERT_NE(it, out.families.end()) << m;
    EXPECT_NE(out.strengths[static_cast<std::size_t>(it - out.families.begin())], Strength::not_computable) << m;
  }
}

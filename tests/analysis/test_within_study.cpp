// A study whose conditions are within participants (data/demo-within, made by `feint simulate study
// --design within`): the design is read from its feint.toml or off the data, the comparison is
// paired, the ANOVA has the condition within, the per-iteration family is adjusted over sign flips,
// and a design the data contradict is refused with the participant and what to set.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "feint/analysis/analyze.hpp"
#include "feint/error.hpp"
#include "feint/stats/ttest.hpp"

using namespace feint;

namespace {

const std::string kWithin = std::string(FEINT_SOURCE_DIR) + "/data/demo-within";

analysis::AnalysisSettings within_settings(const std::string& design) {
  analysis::AnalysisSettings s;  // as data/demo-within/feint.toml, with the design as given
  s.design = design;
  s.compare = "adaptive,random";
  s.scoring.norm = "raw";
  s.metrics = {"error=0.5", "confusion=0.95@raw"};
  return s;
}

const analysis::StudyResults& within_study() {
  static const analysis::StudyResults r =
      analysis::analyze(analysis::load_study(kWithin, within_settings("within")), "test");
  return r;
}

// Each participant's value of `metric` per (condition, iteration), from the scores themselves.
std::map<std::string, std::map<std::pair<std::string, long long>, double>> values_of(const io::ScoresTable& s,
                                                                                      const std::string& metric) {
  std::map<std::string, std::map<std::pair<std::string, long long>, double>> v;
  const int k = s.metric_index(metric);
  for (const auto& rec : s.records)
    if (rec.values[static_cast<std::size_t>(k)]) v[rec.participant][{rec.condition, rec.iteration}] = *rec.values[static_cast<std::size_t>(k)];
  return v;
}

TEST(WithinStudy, TheDeclaredDesignPairsTheComparison) {
  const auto& r = within_study();
  EXPECT_EQ(r.design.design, models::ConditionDesign::within);
  EXPECT_TRUE(r.design.declared);
  EXPECT_NE(r.design.note.find("24 of 24 participants saw every condition"), std::string::npos) << r.design.note;
  ASSERT_TRUE(r.comparison);
  EXPECT_TRUE(r.comparison->options.paired);
  // Iteration 5 of error: the paired t from the participants' own pairs.
  const auto v = values_of(r.scores, "error");
  std::vector<double> a, b;
  for (const auto& [p, cells] : v) {
    a.push_back(cells.at({"adaptive", 5}));
    b.push_back(cells.at({"random", 5}));
  }
  const auto expected = stats::t_test_paired(a, b, {});
  bool found = false;
  for (const auto& row : r.comparison->rows) {
    if (row.metric != "error" || row.iteration != 5 || row.result.test != "paired_t") continue;
    found = true;
    EXPECT_EQ(row.result.n1, 24u);
    EXPECT_NEAR(*row.result.statistic, *expected.statistic, 1e-12 * std::fabs(*expected.statistic));
    ASSERT_TRUE(row.result.cohen_d);  // d_z
    EXPECT_NEAR(*row.result.cohen_d, *expected.statistic / std::sqrt(24.0), 1e-12);
  }
  EXPECT_TRUE(found);
}

TEST(WithinStudy, TheAnovaHasTheConditionWithinAndItsFIsThePairedTSquared) {
  const auto& r = within_study();
  ASSERT_TRUE(r.anova);
  const auto& a = r.anova->analyses.front();
  ASSERT_EQ(a.metric, "error");
  ASSERT_EQ(a.effects.size(), 3u);
  for (const auto& e : a.effects) EXPECT_TRUE(e.within) << e.effect;
  // Two conditions: the condition F is the squared paired t of the participants' means over the
  // iterations (the one-contrast within effect).
  const auto v = values_of(r.scores, "error");
  std::vector<double> ma, mb;
  for (const auto& [p, cells] : v) {
    double sa = 0, sb = 0;
    for (long long it = 1; it <= 20; ++it) {
      sa += cells.at({"adaptive", it});
      sb += cells.at({"random", it});
    }
    ma.push_back(sa / 20);
    mb.push_back(sb / 20);
  }
  const double t = *stats::t_test_paired(ma, mb, {}).statistic;
  EXPECT_NEAR(a.effects[0].f, t * t, 1e-9 * t * t);
  EXPECT_EQ(a.effects[0].den_df, 23.0);
  // Mauchly's p is a probability even where car's second-order term leaves [0, 1] (19 contrasts,
  // 23 error df).
  for (const auto& e : a.sphericity)
    if (e.p_value) {
      EXPECT_TRUE(*e.p_value >= 0 && *e.p_value <= 1) << e.effect << " " << *e.p_value;
    }
}

TEST(WithinStudy, TheModelsHaveTheConditionWithinAndTheBayesFactorIsPaired) {
  const auto& r = within_study();
  ASSERT_TRUE(r.model);
  EXPECT_TRUE(r.model->options.condition_within);
  bool condition_finding = false;
  for (const auto& f : r.findings) {
    if (f.id.rfind("H1-iterations-", 0) == 0) {
      EXPECT_NE(f.sentence.find("sign flips of the participants' pairs"), std::string::npos) << f.sentence;
    }
    if (f.id == "H1-model-condition-error") {
      condition_finding = true;
      EXPECT_NE(f.bf_note.find("paired t test"), std::string::npos) << f.bf_note;
      EXPECT_NE(f.sentence.find("paired t test on the participants' mean scores"), std::string::npos);
    }
  }
  EXPECT_TRUE(condition_finding);
}

TEST(WithinStudy, TheDesignIsReadOffTheDataWhenNotDeclared) {
  const auto r = analysis::analyze(analysis::load_study(kWithin, within_settings("")), "test");
  EXPECT_EQ(r.design.design, models::ConditionDesign::within);
  EXPECT_FALSE(r.design.declared);
  EXPECT_NE(r.design.note.find("read off the data: each of the 24 participants saw both conditions"),
            std::string::npos);
  EXPECT_TRUE(r.comparison->options.paired);
}

TEST(WithinStudy, DeclaredBetweenIsRefusedWithTheParticipantAndWhatToSet) {
  try {
    analysis::analyze(analysis::load_study(kWithin, within_settings("between")), "test");
    FAIL() << "a between design with every participant in both conditions was analysed";
  } catch (const InvalidData& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("study demo-within: participant 'P01' has trials in condition"), std::string::npos) << m;
    EXPECT_NE(m.find("set design = \"within\""), std::string::npos) << m;
  }
  EXPECT_THROW(analysis::load_study(kWithin, within_settings("crossed")), UsageError);
}

}  // namespace

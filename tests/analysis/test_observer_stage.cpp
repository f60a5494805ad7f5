// `feint analyze` compares the goal-inference observer's log beta and tau between the compared
// conditions (src/analysis/observer_stage.hpp): between participants on data/demo (Welch t), paired
// within participants on data/demo-within, none for pointer logs (data/demo-k3); the numbers are
// those of the library's own fit and comparison of the same logs.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "feint/analysis/analyze.hpp"
#include "feint/io/trace.hpp"
#include "feint/models/observer_fit.hpp"
#include "feint/sim/observer_logs.hpp"

using namespace feint;

namespace {

const analysis::Finding* by_id(const analysis::StudyResults& r, const std::string& id) {
  for (const auto& f : r.findings)
    if (f.id == id) return &f;
  return nullptr;
}

analysis::StudyResults analyze_demo(const std::string& name) {
  analysis::AnalysisSettings s;
  return analysis::analyze(analysis::load_study(std::string(FEINT_SOURCE_DIR) + "/data/" + name, s), "test");
}

}  // namespace

TEST(AnalyzeObserver, TheDemosConditionsAreComparedOnEachParticipantsFit) {
  const auto r = analyze_demo("demo");
  ASSERT_EQ(r.observer.size(), 2u) << r.observer_note;
  // The same fit made directly from the logs (as `feint observer fit data/demo/logs --no-learning`).
  models::ObserverFitSettings s;
  s.learning = false;
  const auto direct = sim::fit_observer_to_logs({std::string(FEINT_SOURCE_DIR) + "/data/demo/logs"}, s, {});
  const auto c = models::compare_conditions(direct.fit.participants, "adaptive", "random", 0.95);
  ASSERT_EQ(c.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_FALSE(r.observer[k].paired);
    EXPECT_EQ(r.observer[k].welch.test, "welch_t");
    EXPECT_EQ(*r.observer[k].welch.statistic, *c[k].welch.statistic);
    EXPECT_EQ(*r.observer[k].welch.p_value, *c[k].welch.p_value);
  }
  const analysis::Finding* beta = by_id(r, "observer-beta");
  const analysis::Finding* tau = by_id(r, "observer-tau");
  ASSERT_NE(beta, nullptr);
  ASSERT_NE(tau, nullptr);
  EXPECT_EQ(beta->hypothesis, "exploratory");
  EXPECT_EQ(*beta->p, *c[0].welch.p_value);
  ASSERT_TRUE(beta->bf10.has_value());
  EXPECT_NEAR(std::log(*beta->bf10), *c[0].welch.log_bf10, 1e-12);
  // Which way and how much on beta's own scale: the ratio of geometric means, exp of the difference.
  EXPECT_NE(beta->sentence.find(fmt::format("ratio {:.2f}", std::exp(*c[0].welch.estimate))), std::string::npos)
      << beta->sentence;
  EXPECT_EQ(*tau->p, *c[1].welch.p_value);
}

TEST(AnalyzeObserver, WithinParticipantsEachParticipantsPairIsCompared) {
  const auto r = analyze_demo("demo-within");
  ASSERT_EQ(r.observer.size(), 2u) << r.observer_note;
  for (const auto& c : r.observer) {
    EXPECT_TRUE(c.paired);
    EXPECT_EQ(c.welch.test, "paired_t");
    EXPECT_EQ(c.rank.test, "wilcoxon_signed_rank");
  }
  const analysis::Finding* beta = by_id(r, "observer-beta");
  ASSERT_NE(beta, nullptr);
  EXPECT_NE(beta->sentence.find("paired within participants"), std::string::npos) << beta->sentence;
}

TEST(AnalyzeObserver, PointerLogsAreLeftToTheirOwnFit) {
  const auto r = analyze_demo("demo-k3");
  EXPECT_TRUE(r.observer.empty());
  EXPECT_TRUE(r.observer_note.empty()) << r.observer_note;
  EXPECT_EQ(by_id(r, "observer-beta"), nullptr);
}

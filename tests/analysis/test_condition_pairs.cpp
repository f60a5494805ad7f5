// Three or more conditions: after the omnibus F of condition, one finding per pair of conditions
// (emmeans' pairwise contrast, Tukey-adjusted over the pairs), which way, how much and how sure,
// and protected by the omnibus finding (docs/findings.md "Three or more conditions").
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "feint/analysis/study_findings.hpp"
#include "feint/models/studentized_range.hpp"
#include "feint/rng.hpp"
#include "feint/stats/bayes_factor.hpp"
#include "feint/stats/ttest.hpp"
#include "feint/tables/model.hpp"

using namespace feint;

namespace {

// 3 conditions x 8 participants x 4 iterations, complete and balanced: participant effects,
// condition c shifted by `shift`.
io::ScoresTable three_conditions(double shift, std::uint64_t seed) {
  io::ScoresTable s;
  s.path = "scores.csv";
  s.metrics = {"error"};
  s.has_condition = true;
  Rng rng(seed);
  const std::vector<std::string> conditions = {"a", "b", "c"};
  int id = 0;
  for (const auto& c : conditions)
    for (int p = 0; p < 8; ++p) {
      const std::string who = "P" + std::to_string(++id);
      const double person = 0.05 * rng.normal();
      for (long long it = 1; it <= 4; ++it) {
        const double y = 0.45 + person + (c == "c" ? shift : 0.0) + 0.02 * static_cast<double>(it) + 0.04 * rng.normal();
        s.records.push_back({who, c, it, {y}, static_cast<std::uint64_t>(s.records.size() + 2)});
      }
    }
  return s;
}

std::vector<analysis::Finding> findings_of(const io::ScoresTable& s) {
  tables::ModelOptions o;
  o.metrics = {"error"};
  const tables::ModelAnalysis m = tables::build_model_analysis(s, o);
  return analysis::mixed_model_findings(&m, nullptr);
}

const analysis::Finding* by_id(const std::vector<analysis::Finding>& fs, const std::string& id) {
  for (const auto& f : fs)
    if (f.id == id) return &f;
  return nullptr;
}

// Each participant's mean, by condition.
std::map<std::string, std::vector<double>> participant_means(const io::ScoresTable& s) {
  std::map<std::string, std::map<std::string, std::pair<double, int>>> sums;
  for (const auto& r : s.records) {
    auto& [sum, n] = sums[r.condition][r.participant];
    sum += *r.values[0];
    ++n;
  }
  std::map<std::string, std::vector<double>> out;
  for (const auto& [c, people] : sums)
    for (const auto& [p, sn] : people) out[c].push_back(sn.first / sn.second);
  return out;
}

TEST(ConditionPairs, EachPairIsTheTukeyContrastOfTheMeansWithItsBayesFactor) {
  const io::ScoresTable s = three_conditions(0.12, 5);
  const auto fs = findings_of(s);
  const auto pm = participant_means(s);
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{{"a", "b"}, {"a", "c"}, {"b", "c"}}) {
    SCOPED_TRACE(a + " - " + b);
    const analysis::Finding* f = by_id(fs, "H1-model-pair-error-" + a + "-" + b);
    ASSERT_NE(f, nullptr);
    // Balanced and complete: the estimated marginal means are the raw means, the contrast their
    // difference.
    double ma = 0, mb = 0;
    for (double v : pm.at(a)) ma += v / 8;
    for (double v : pm.at(b)) mb += v / 8;
    ASSERT_TRUE(f->means && f->estimate);
    EXPECT_NEAR(f->means->first, ma, 1e-10);
    EXPECT_NEAR(f->means->second, mb, 1e-10);
    EXPECT_NEAR(*f->estimate, ma - mb, 1e-10);
    // Tukey over the 3 pairs: p = P(range of 3 means > |t| sqrt 2) on the contrast's df.
    ASSERT_TRUE(f->p && f->p_adjusted);
    // The contrast's SE from the width of its Tukey interval, then t and the Tukey p from it.
    const double df = std::stod(f->statistics.substr(2, f->statistics.find(')') - 2));
    EXPECT_EQ(df, 21.0);  // balanced and complete: the between-participant stratum's 24 - 3
    ASSERT_TRUE(f->ci_low && f->ci_high);
    const double half = models::qtukey(0.95, 3, df) / std::sqrt(2.0);
    const double se = (*f->ci_high - *f->ci_low) / (2 * half);
    EXPECT_NEAR(*f->ci_low + *f->ci_high, 2 * *f->estimate, 1e-12);
    EXPECT_NEAR(*f->p_adjusted, 1 - models::ptukey(std::fabs(*f->estimate / se) * std::sqrt(2.0), 3, df), 1e-8);
    EXPECT_GE(*f->p_adjusted, *f->p);
    // The Bayes factor: Welch t on the participants' means of the two conditions.
    stats::TestResult w = stats::t_test_welch(pm.at(a), pm.at(b), {});
    stats::add_bayes_factor(w, stats::kJzsMediumScale);
    ASSERT_TRUE(f->bf10);
    EXPECT_NEAR(std::log(*f->bf10), *w.log_bf10, 1e-12);
    EXPECT_NE(f->bf_note.find("Welch t test on the participants' mean scores (8 and 8 participants"), std::string::npos);
  }
  // c is shifted by 0.12 (about 2.4 SDs of a participant's mean): the omnibus and both pairs with c
  // are evidence for a difference, and they say which way.
  const analysis::Finding* omnibus = by_id(fs, "H1-model-condition-error");
  ASSERT_NE(omnibus, nullptr);
  EXPECT_EQ(omnibus->strength, analysis::Strength::evidence_for_difference) << omnibus->sentence;
  const analysis::Finding* ac = by_id(fs, "H1-model-pair-error-a-c");
  EXPECT_EQ(ac->strength, analysis::Strength::evidence_for_difference) << ac->sentence;
  EXPECT_EQ(ac->direction, "a < c");
  EXPECT_NE(ac->sentence.find("Tukey-adjusted over the 3 pairs of 3 conditions"), std::string::npos);
  EXPECT_NE(by_id(fs, "H1-model-pair-error-a-b")->strength, analysis::Strength::evidence_for_difference);
}

TEST(ConditionPairs, NoPairIsClaimedWhenTheOmnibusTestIsNot) {
  // Search seeds for a null study whose omnibus is not evidence but some pair reaches Tukey p < .05
  // with BF10 >= 3 on its own; the protected rule must then withhold the claim.
  int checked = 0;
  for (std::uint64_t seed = 1; seed < 400 && checked < 3; ++seed) {
    const auto fs = findings_of(three_conditions(0.04, seed));
    const analysis::Finding* omnibus = by_id(fs, "H1-model-condition-error");
    if (!omnibus || omnibus->strength == analysis::Strength::evidence_for_difference) continue;
    for (const auto& f : fs) {
      if (f.id.rfind("H1-model-pair-", 0) != 0) continue;
      EXPECT_NE(f.strength, analysis::Strength::evidence_for_difference) << f.sentence;
      const bool would = f.p_adjusted && *f.p_adjusted < 0.05 && f.bf10 && *f.bf10 >= 3;
      if (would) {
        ++checked;
        ASSERT_FALSE(f.warnings.empty());
        EXPECT_NE(f.warnings.back().find("did not show a difference"), std::string::npos);
      }
    }
  }
  EXPECT_GT(checked, 0) << "no seed gave a pair that the protected rule had to withhold";
}

TEST(ConditionPairs, TwoConditionsHaveNoPairFindings) {
  io::ScoresTable s = three_conditions(0.0, 3);
  std::erase_if(s.records, [](const io::ScoreRecord& r) { return r.condition == "c"; });
  for (const auto& f : findings_of(s)) EXPECT_EQ(f.id.rfind("H1-model-pair-", 0), std::string::npos) << f.id;
}

}  // namespace

// The calibration mechanism (feint/analysis/calibration.hpp): studies made by `feint simulate
// study`'s simulator, analysed as `feint analyze` does, their headline claims counted. The 200-study
// rates are measured by bench/findings_calibration (docs/findings.md "Calibration against truth");
// here a handful of small studies check the mechanism.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "feint/analysis/calibration.hpp"
#include "feint/error.hpp"

using namespace feint;
using analysis::Strength;
using feint::UsageError;

namespace {

sim::StudyOptions small(int participants, double lambda) {
  sim::StudyOptions o;
  o.participants = participants;
  o.iterations = 8;
  o.lambda = lambda;
  return o;
}

std::size_t family(const analysis::CalibrationOutcome& o, const std::string& label) {
  const auto it = std::find(o.families.begin(), o.families.end(), label);
  EXPECT_NE(it, o.families.end()) << label;
  return static_cast<std::size_t>(it - o.families.begin());
}

}  // namespace

TEST(Calibration, ClopperPearsonMatchesR) {
  // R: binom.test(k, 200)$conf.int
  auto [lo, hi] = analysis::clopper_pearson(3, 200);
  EXPECT_NEAR(lo, 0.00310410762155351, 1e-12);
  EXPECT_NEAR(hi, 0.04320828191771264, 1e-12);
  std::tie(lo, hi) = analysis::clopper_pearson(0, 200);
  EXPECT_EQ(lo, 0.0);
  EXPECT_NEAR(hi, 0.0182753403551362, 1e-12);
  std::tie(lo, hi) = analysis::clopper_pearson(10, 200);
  EXPECT_NEAR(lo, 0.0242341654721085, 1e-12);
  EXPECT_NEAR(hi, 0.0900275377013514, 1e-12);
  EXPECT_THROW(analysis::clopper_pearson(3, 0), UsageError);
  EXPECT_THROW(analysis::clopper_pearson(5, 4), UsageError);
}

TEST(Calibration, SimulatedStudiesGiveEveryHeadlineAndTheSameAnswerOnAnyThreadCount) {
  const auto one = analysis::calibration_run(small(6, 0.0), 42, 3, 1);
  const auto two = analysis::calibration_run(small(6, 0.0), 42, 3, 2);
  ASSERT_EQ(one.size(), 3u);
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].seed, 42 + i);
    EXPECT_EQ(one[i].families, two[i].families);
    EXPECT_EQ(one[i].strengths, two[i].strengths);
    EXPECT_EQ(one[i].bf01, two[i].bf01);
    // Every headline of both metrics is there and computed: the per-iteration contrasts, the
    // mixed models, the exposure slopes, and the questionnaire's four items.
    for (const std::string m : {"error", "confusion"}) {
      for (const std::string f : {"H1 per-iteration contrasts (maxT over iterations): ",
                                  "H1 mixed models (Holm over 3 tests): ",
                                  "H1 exposure slopes by condition (Holm over strategies): "}) {
        EXPECT_NE(one[i].strengths[family(one[i], f + m)], Strength::not_computable) << f << m;
      }
    }
    for (const std::string item : {"entertainment", "deception", "intelligence", "trust"})
      EXPECT_NE(one[i].strengths[family(one[i], "H2 questionnaire between conditions: " + item)],
                Strength::not_computable);
    // BF01 of 8 iterations x 2 metrics and 4 items (two-sample t tests).
    EXPECT_EQ(one[i].bf01.size(), 8u * 2u + 4u);
  }
  // The rates count what the outcomes hold.
  const auto rates = analysis::calibration_rates(one, Strength::evidence_for_difference);
  ASSERT_EQ(rates.size(), one[0].families.size());
  for (const auto& r : rates) {
    EXPECT_EQ(r.studies, 3);
    int k = 0;
    for (const auto& o : one) k += o.strengths[family(o, r.family)] == Strength::evidence_for_difference;
    EXPECT_EQ(r.count, k) << r.family;
    EXPECT_LE(r.low, r.rate);
    EXPECT_GE(r.high, r.rate);
  }
}

TEST(Calibration, APlantedAdaptiveVersusRandomEffectIsReported) {
  // lambda = 1 (the strongest adaptive selection) with 40 participants per condition: the
  // goal-inference participants learn the random condition's strategies faster, so error is higher
  // under adaptive selection, and the mixed models' family reports it. Its rate on 60 other studies,
  // calibration_run(o, 3000, 60, 2) with the same o: 60 of 60 (95 % Clopper-Pearson interval
  // [0.94, 1]; 235 s CPU). Six studies here (about 24 s CPU on two threads),
  // asserted: at least 5 of them. With a rate of 0.99 fewer than 5 of 6 has probability 0.0015
  // (0.046 at the interval's lower end, 0.94); a rate of 0.75 is caught with probability 0.47.
  sim::StudyOptions o = small(40, 1.0);
  o.iterations = 20;
  const int studies = 6;
  const auto out = analysis::calibration_run(o, 7, studies, 2);
  ASSERT_EQ(out.size(), static_cast<std::size_t>(studies));
  int found = 0;
  for (const auto& study : out)
    found += study.strengths[family(study, "H1 mixed models (Holm over 3 tests): error")] ==
             Strength::evidence_for_difference;
  EXPECT_GE(found, studies - 1) << found << " of " << studies << " planted studies";
}

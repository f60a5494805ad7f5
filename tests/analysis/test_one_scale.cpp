// One scale (docs/metrics.md "One scale"): confusion's normalisation and its reference agree, or
// the study is refused before a log is read.
#include <gtest/gtest.h>

#include <string>

#include "feint/analysis/study.hpp"
#include "feint/error.hpp"

using namespace feint;

namespace {

const std::string kDemo = std::string(FEINT_SOURCE_DIR) + "/data/demo";

std::string refusal(const analysis::AnalysisSettings& s) {
  try {
    analysis::load_study(kDemo, s);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(OneScale, TheDefaultsAgreeRawScoresAndThePapersRawReference) {
  analysis::AnalysisSettings s;
  EXPECT_EQ(s.scoring.norm, "raw");
  EXPECT_EQ(refusal(s), "accepted");
}

TEST(OneScale, SpeedScoresWithTheRawReferenceAreRefusedWithTheFix) {
  analysis::AnalysisSettings s;
  s.scoring.norm = "speed";
  const std::string m = refusal(s);
  EXPECT_NE(m.find("confusion is on the speed scale but its reference 0.95 is a value of the raw scale"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("--metric confusion=VALUE@speed"), std::string::npos) << m;
  s.metrics = {"error=0.5", "confusion=0.4@speed"};
  EXPECT_EQ(refusal(s), "accepted");
  s.metrics = {"error=0.5", "confusion=0.4"};  // no scale: the scores' own
  EXPECT_EQ(refusal(s), "accepted");
  s.scoring.norm = "raw";
  s.metrics = {"error=0.5", "confusion=0.4@speed"};
  EXPECT_NE(refusal(s).find("confusion is on the raw scale but its reference 0.4 is a value of the speed scale"),
            std::string::npos);
}

// The per-iteration contrasts' family is adjusted by Westfall–Young maxT over whole participants
// (docs/findings.md, "Per-iteration contrasts: the maxT correction"): worked examples where every
// labelling is enumerated, so the adjusted p is a known fraction, and the fallback to Holm.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "feint/analysis/study_findings.hpp"
#include "feint/tables/table1.hpp"

using namespace feint;
using analysis::Finding;
using analysis::Strength;

namespace {

// participant, condition, iteration, error
struct Row {
  std::string participant, condition;
  long long iteration;
  double error;
};

analysis::StudyResults study(const std::vector<Row>& rows) {
  analysis::StudyResults r;
  r.scores.metrics = {"error"};
  r.scores.has_condition = true;
  for (const auto& row : rows) r.scores.records.push_back({row.participant, row.condition, row.iteration, {row.error}, 0});
  tables::Table1Options o;
  o.metrics = {{"error", 0.5}};
  o.compare = std::make_pair(std::string("a"), std::string("b"));
  r.comparison = tables::build_table1(r.scores, o);
  return r;
}

Finding iterations_finding(const std::vector<Finding>& fs) {
  for (const auto& f : fs)
    if (f.id == "H1-iterations-error") return f;
  throw std::runtime_error("no per-iteration finding");
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Iteration 1 separates the conditions completely; iteration 2 does not.
std::vector<Row> separated(int per_condition) {
  std::vector<Row> rows;
  const double a1[] = {10.1, 11.3, 12.2, 13.4}, b1[] = {1.2, 2.5, 3.1, 4.3};
  const double a2[] = {5.0, 7.5, 6.1, 4.2}, b2[] = {6.3, 4.4, 7.2, 5.5};
  for (int i = 0; i < per_condition; ++i) {
    rows.push_back({"A" + std::to_string(i), "a", 1, a1[i]});
    rows.push_back({"A" + std::to_string(i), "a", 2, a2[i]});
    rows.push_back({"B" + std::to_string(i), "b", 1, b1[i]});
    rows.push_back({"B" + std::to_string(i), "b", 2, b2[i]});
  }
  return rows;
}

}  // namespace

TEST(IterationMaxT, FourAndFourParticipantsGiveTheExactFractionOfSeventyLabellings) {
  const auto r = study(separated(4));
  const Finding f = iterations_finding(analysis::study_findings(r, {{"error", 0.5}}));
  // Only the observed labelling and its mirror image reach iteration 1's |t|: p = 2 / C(8, 4).
  EXPECT_TRUE(contains(f.sentence, "Westfall\u2013Young maxT-adjusted over 2 iterations, all 70 labellings of the "
                                   "participants"))
      << f.sentence;
  EXPECT_TRUE(contains(f.sentence, "smallest adjusted p = .029 (test 1)")) << f.sentence;
  // Welch's p of iteration 1 is far smaller (t = 9.44, p = 8.3e-5): Holm would have said p < .001.
  ASSERT_TRUE(r.comparison->rows[0].result.p_value);
  EXPECT_NEAR(*r.comparison->rows[0].result.statistic, 9.444099, 1e-6);  // R: t.test(a, b)
  EXPECT_LT(*r.comparison->rows[0].result.p_value * 2, 0.001);
  EXPECT_EQ(f.strength, Strength::evidence_for_difference) << f.sentence;
  EXPECT_TRUE(f.warnings.empty());
}

TEST(IterationMaxT, ThreeAndThreeParticipantsCannotReachFivePercentWhateverTheT) {
  // C(6, 3) = 20 labellings: the smallest two-sided p any relabelling test can give is 2/20. The
  // t test's p (normality assumed) is below .001; the finding does not rest on that assumption.
  const auto r = study(separated(3));
  const Finding f = iterations_finding(analysis::study_findings(r, {{"error", 0.5}}));
  EXPECT_TRUE(contains(f.sentence, "all 20 labellings")) << f.sentence;
  EXPECT_TRUE(contains(f.sentence, "smallest adjusted p = .100 (test 1)")) << f.sentence;
  EXPECT_NEAR(*r.comparison->rows[0].result.statistic, 10.79803, 1e-5);
  EXPECT_LT(*r.comparison->rows[0].result.p_value, 0.001);
  EXPECT_EQ(f.strength, Strength::no_evidence_either_way) << f.sentence;
}

TEST(IterationMaxT, AParticipantInBothConditionsFallsBackToHolmAndSaysWhy) {
  auto rows = separated(4);
  rows[2].participant = "A0";  // B0's iteration 1 now belongs to A0, who is also in condition a
  const auto r = study(rows);
  const Finding f = iterations_finding(analysis::study_findings(r, {{"error", 0.5}}));
  EXPECT_TRUE(contains(f.sentence, "(Holm-corrected over 2 tests)")) << f.sentence;
  ASSERT_EQ(f.warnings.size(), 1u);
  EXPECT_EQ(f.warnings[0], "The per-iteration contrasts of error are Holm-corrected, not maxT-adjusted: "
                           "participant A0 is in both conditions.");
}

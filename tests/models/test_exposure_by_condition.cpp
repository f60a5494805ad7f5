// Condition x exposure per strategy by the two-stage method: lm() per participant x strategy, then
// t.test() (tests/golden/models/exposure_by_condition_golden.R), and its rules and invariants.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "feint/models/exposure.hpp"

#include "golden_csv.hpp"
#include "accuracy.hpp"

namespace {
using feint::test::read_csv;

struct Data {
  std::vector<std::string> participant, condition, strategy;
  std::vector<double> exposure, y;
};

Data golden_data() {
  const auto data = read_csv(FEINT_SOURCE_DIR "/tests/golden/models/lmm_exposure.csv");
  Data d;
  std::vector<double> iteration;
  for (std::size_t i = 1; i < data.size(); ++i) {  // iteration,participant,condition,error,strategy
    iteration.push_back(std::stod(data[i][0]));
    d.participant.push_back(data[i][1]);
    d.condition.push_back(data[i][2]);
    d.y.push_back(std::stod(data[i][3]));
    d.strategy.push_back(data[i][4]);
  }
  d.exposure = feint::models::exposure_counts(d.participant, iteration, d.strategy);
  return d;
}

feint::models::ExposureByCondition fit(const Data& d, std::vector<std::string> conditions = {}) {
  return feint::models::exposure_slopes_by_condition(d.participant, d.condition, d.strategy, d.exposure, d.y,
                                                     std::move(conditions));
}

bool near_rel(double a, double b, double tol) { return std::fabs(a - b) <= tol * std::fabs(b); }

}  // namespace

TEST(ExposureByCondition, SlopesAndTheirDifferenceMatchLmAndTTest) {
  const Data d = golden_data();
  ASSERT_GT(d.y.size(), 200u);
  const auto res = fit(d);
  ASSERT_EQ(res.slopes.size(), 6u);
  ASSERT_EQ(res.differences.size(), 3u);
  const auto golden = read_csv(FEINT_SOURCE_DIR "/tests/golden/models/exposure_by_condition_golden.csv");
  ASSERT_EQ(golden.size(), 10u);
  // kind,strategy,condition,n,left_out,estimate,se,df,t,p,lower,upper,log_bf10,ttestbf_log_bf
  for (std::size_t i = 1; i < golden.size(); ++i) {
    const auto& g = golden[i];
    const bool slope = g[0] == "slope";
    const auto& r = slope ? res.slopes[i - 1] : res.differences[i - 7];
    SCOPED_TRACE(g[1] + " " + g[2]);
    ASSERT_EQ(r.strategy, g[1]);
    ASSERT_EQ(r.condition, g[2]);
    ASSERT_TRUE(r.test.computed) << r.test.note;
    EXPECT_EQ(r.participants, std::stoul(g[3]));
    EXPECT_EQ(r.left_out, std::stoul(g[4]));
    EXPECT_EQ(r.test.test, slope ? "one_sample_t" : "welch_t");
    for (const auto& [q, got, col] : {std::tuple{"estimate", *r.test.estimate, 5}, {"SE", r.std_error, 6},
                                      {"df", *r.test.df, 7}, {"t", *r.test.statistic, 8},
                                      {"p", *r.test.p_value, 9}, {"lower", *r.test.conf_low, 10},
                                      {"upper", *r.test.conf_high, 11}})
      feint::test::record(std::string("exposure slopes (lm, t.test) ") + q, got, std::stod(g[col]));
    // Closed forms: 1e-10 relative (measured 1e-14).
    EXPECT_PRED3(near_rel, *r.test.estimate, std::stod(g[5]), 1e-10);
    EXPECT_PRED3(near_rel, r.std_error, std::stod(g[6]), 1e-10);
    EXPECT_PRED3(near_rel, *r.test.df, std::stod(g[7]), 1e-10);
    EXPECT_PRED3(near_rel, *r.test.statistic, std::stod(g[8]), 1e-10);
    EXPECT_PRED3(near_rel, *r.test.p_value, std::stod(g[9]), 1e-10);
    EXPECT_PRED3(near_rel, *r.test.conf_low, std::stod(g[10]), 1e-10);
    EXPECT_PRED3(near_rel, *r.test.conf_high, std::stod(g[11]), 1e-10);
    if (slope) {
      EXPECT_FALSE(r.test.log_bf10.has_value());
    } else {
      // the exact integral (R's integrate at rel.tol 1e-12); measured 4e-16
      ASSERT_TRUE(r.test.log_bf10.has_value());
      feint::test::record("exposure log BF", *r.test.log_bf10, std::stod(g[12]));
      EXPECT_NEAR(*r.test.log_bf10, std::stod(g[12]), 1e-12);
      EXPECT_TRUE(r.test.cohen_d.has_value() && r.test.cohen_d_low.has_value());
    }
    if (r.left_out > 0) {
      EXPECT_NE(r.test.note.find("left out"), std::string::npos) << r.test.note;
    }
    EXPECT_EQ(r.test.method.find("lmer"), std::string::npos);
  }
}

TEST(ExposureByCondition, AParticipantWithOneExposureIsLeftOut) {
  // p1, p2 have two exposures; p3 has two trials both at exposure 0 (no slope), p4 one trial.
  Data d;
  auto add = [&](const std::string& p, double e, double y) {
    d.participant.push_back(p), d.condition.push_back("c"), d.strategy.push_back("s");
    d.exposure.push_back(e), d.y.push_back(y);
  };
  add("p1", 0, 1.0), add("p1", 1, 1.5), add("p1", 2, 2.5);  // slope 0.75
  add("p2", 0, 2.0), add("p2", 1, 1.75);                     // slope -0.25
  add("p3", 0, 9.0), add("p3", 0, -9.0);
  add("p4", 3, 100.0);
  add("p5", 0, 3.0), add("p5", 1, std::nan(""));             // one finite trial: left out
  const auto res = fit(d);
  ASSERT_EQ(res.slopes.size(), 1u);
  const auto& s = res.slopes[0];
  ASSERT_TRUE(s.test.computed) << s.test.note;
  EXPECT_EQ(s.participants, 2u);
  EXPECT_EQ(s.left_out, 3u);
  EXPECT_NEAR(*s.test.estimate, 0.25, 1e-14);
  EXPECT_NEAR(s.std_error, 0.5, 1e-14);  // sd of {0.75, -0.25} = sqrt(0.5), / sqrt(2)
  EXPECT_EQ(*s.test.df, 1.0);
  EXPECT_NE(s.test.note.find("3 participants left out"), std::string::npos) << s.test.note;
  EXPECT_TRUE(res.differences.empty());
}

TEST(ExposureByCondition, FewerThanTwoParticipantsIsNotComputableNeverAThrow) {
  Data d;
  auto add = [&](const std::string& p, const std::string& c, double e, double y) {
    d.participant.push_back(p), d.condition.push_back(c), d.strategy.push_back("s");
    d.exposure.push_back(e), d.y.push_back(y);
  };
  add("a1", "A", 0, 1), add("a1", "A", 1, 2);
  add("a2", "A", 0, 1), add("a2", "A", 1, 4);
  add("b1", "B", 0, 1), add("b1", "B", 1, 3);  // B: one participant with a slope
  add("b2", "B", 0, 5);                        // and one left out
  feint::models::ExposureByCondition res;
  ASSERT_NO_THROW(res = fit(d, {"A", "B"}));
  ASSERT_EQ(res.slopes.size(), 2u);
  EXPECT_TRUE(res.slopes[0].test.computed);
  EXPECT_FALSE(res.slopes[1].test.computed);
  EXPECT_NE(res.slopes[1].test.note.find("fewer than 2 participants"), std::string::npos) << res.slopes[1].test.note;
  EXPECT_NE(res.slopes[1].test.note.find("1 participant left out"), std::string::npos) << res.slopes[1].test.note;
  ASSERT_EQ(res.differences.size(), 1u);
  EXPECT_FALSE(res.differences[0].test.computed);
  EXPECT_NE(res.differences[0].test.note.find("condition 'B'"), std::string::npos) << res.differences[0].test.note;
  EXPECT_EQ(res.differences[0].condition, "A-B");
}

TEST(ExposureByCondition, ShiftingYChangesNothingAndScalingYScalesTheEstimates) {
  const Data d = golden_data();
  const auto base = fit(d);
  Data shifted = d, scaled = d;
  for (auto& v : shifted.y) v += 1000.0;
  for (auto& v : scaled.y) v *= -3.0;
  const auto sh = fit(shifted), sc = fit(scaled);
  auto check = [](const auto& a, const auto& b, const auto& c) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      const auto &t = a[i].test, &u = b[i].test, &v = c[i].test;
      EXPECT_NEAR(*u.estimate, *t.estimate, 1e-9);
      EXPECT_NEAR(*u.statistic, *t.statistic, 1e-7);
      EXPECT_NEAR(*u.p_value, *t.p_value, 1e-8);
      EXPECT_NEAR(*v.estimate, -3.0 * *t.estimate, 1e-12);
      EXPECT_NEAR(c[i].std_error, 3.0 * a[i].std_error, 1e-12);
      EXPECT_NEAR(*v.conf_low, -3.0 * *t.conf_high, 1e-12);
      EXPECT_NEAR(*v.statistic, -*t.statistic, 1e-9);
      EXPECT_NEAR(*v.df, *t.df, 1e-9);
      EXPECT_NEAR(*v.p_value, *t.p_value, 1e-12);
    }
  };
  check(base.slopes, sh.slopes, sc.slopes);
  check(base.differences, sh.differences, sc.differences);
  // the Bayes factor depends on |t| only
  for (std::size_t i = 0; i < base.differences.size(); ++i)
    EXPECT_NEAR(*sc.differences[i].test.log_bf10, *base.differences[i].test.log_bf10, 1e-8);
}

// Within participants: exposure counted within each condition's block, slopes per participant x
// condition x strategy, the difference a paired t test over the participants with a slope in both
// (tests/golden/models/exposure_within_golden.R: lm(), t.test(paired = TRUE), the exact JZS BF).
TEST(ExposureByCondition, WithinParticipantsPairedDifferenceMatchesTTestPaired) {
  const auto data = read_csv(FEINT_SOURCE_DIR "/tests/golden/models/exposure_within.csv");
  Data d;
  std::vector<std::string> block;  // participant x condition: the exposure's own count
  std::vector<double> iteration;
  for (std::size_t i = 1; i < data.size(); ++i) {  // participant,condition,iteration,strategy,error
    d.participant.push_back(data[i][0]);
    d.condition.push_back(data[i][1]);
    block.push_back(data[i][0] + "|" + data[i][1]);
    iteration.push_back(std::stod(data[i][2]));
    d.strategy.push_back(data[i][3]);
    // a missing error is an empty last field (which the line splitter drops)
    d.y.push_back(data[i].size() < 5 || data[i][4].empty() ? std::nan("") : std::stod(data[i][4]));
  }
  d.exposure = feint::models::exposure_counts(block, iteration, d.strategy);
  const auto res = feint::models::exposure_slopes_by_condition(d.participant, d.condition, d.strategy, d.exposure,
                                                               d.y, {"adaptive", "random"}, 0.95,
                                                               feint::stats::kJzsMediumScale, true);
  const auto golden = read_csv(FEINT_SOURCE_DIR "/tests/golden/models/exposure_within_golden.csv");
  ASSERT_EQ(golden.size(), 10u);
  ASSERT_EQ(res.slopes.size(), 6u);
  ASSERT_EQ(res.differences.size(), 3u);
  for (std::size_t i = 1; i < golden.size(); ++i) {
    const auto& g = golden[i];
    const bool slope = g[0] == "slope";
    const auto& r = slope ? res.slopes[i - 1] : res.differences[i - 7];
    SCOPED_TRACE(g[1] + " " + g[2]);
    ASSERT_EQ(r.strategy, g[1]);
    ASSERT_EQ(r.condition, g[2]);
    ASSERT_TRUE(r.test.computed) << r.test.note;
    EXPECT_EQ(r.test.test, slope ? "one_sample_t" : "paired_t");
    EXPECT_EQ(r.participants, std::stoul(g[3]));
    EXPECT_EQ(r.left_out, std::stoul(g[4]));
    for (const auto& [got, col] : {std::pair{*r.test.estimate, 5}, {r.std_error, 6}, {*r.test.df, 7},
                                   {*r.test.statistic, 8}, {*r.test.p_value, 9}, {*r.test.conf_low, 10},
                                   {*r.test.conf_high, 11}}) {
      feint::test::record("exposure slopes within (lm, t.test paired)", got, std::stod(g[col]));
      EXPECT_PRED3(near_rel, got, std::stod(g[col]), 1e-10) << "column " << golden[0][col];
    }
    if (!slope) {
      ASSERT_TRUE(r.test.log_bf10.has_value());
      EXPECT_NEAR(*r.test.log_bf10, std::stod(g[12]), 1e-12);
      EXPECT_TRUE(r.test.cohen_d.has_value() && r.test.cohen_d_low.has_value());  // d_z with its CI
      EXPECT_NE(r.test.note.find("without a slope in both conditions"), std::string::npos) << r.test.note;
    }
  }
}

// Five more data sets within participants (exposure_within_golden.R, exposure_within_sets*.csv):
// balanced; unbalanced blocks with missing errors, absent trials and participants in one condition
// only; three conditions; five participants; a sparse set whose tests are partly not computable (NA
// in R, not computed here). Every number at 1e-10 relative, log BF at 1e-12 absolute, d_z and its
// interval (exact roots of the noncentral t) at 1e-11 * max(1, |x|).
TEST(ExposureByCondition, WithinParticipantsFiveMoreDataSetsMatchR) {
  const auto data = read_csv(FEINT_SOURCE_DIR "/tests/golden/models/exposure_within_sets.csv");
  const auto golden = read_csv(FEINT_SOURCE_DIR "/tests/golden/models/exposure_within_sets_golden.csv");
  std::map<std::string, Data> sets;
  std::map<std::string, std::vector<std::string>> blocks;
  std::map<std::string, std::vector<double>> iterations;
  for (std::size_t i = 1; i < data.size(); ++i) {  // set,participant,condition,iteration,strategy,error
    const auto& f = data[i];
    Data& d = sets[f[0]];
    d.participant.push_back(f[1]);
    d.condition.push_back(f[2]);
    blocks[f[0]].push_back(f[1] + "|" + f[2]);
    iterations[f[0]].push_back(std::stod(f[3]));
    d.strategy.push_back(f[4]);
    d.y.push_back(f.size() < 6 || f[5].empty() ? std::nan("") : std::stod(f[5]));
  }
  ASSERT_EQ(sets.size(), 5u);
  std::map<std::string, std::vector<std::vector<std::string>>> rows;  // set -> golden rows, in order
  std::map<std::string, std::vector<std::string>> conditions;          // set -> conditions, in order
  for (std::size_t i = 1; i < golden.size(); ++i) {
    rows[golden[i][0]].push_back(golden[i]);
    auto& c = conditions[golden[i][0]];
    if (golden[i][1] == "slope" && std::find(c.begin(), c.end(), golden[i][3]) == c.end()) c.push_back(golden[i][3]);
  }
  ASSERT_EQ(rows.size(), 5u);
  std::size_t compared = 0, not_computable = 0;
  for (auto& [name, d] : sets) {
    SCOPED_TRACE(name);
    d.exposure = feint::models::exposure_counts(blocks[name], iterations[name], d.strategy);
    const auto res = feint::models::exposure_slopes_by_condition(d.participant, d.condition, d.strategy, d.exposure,
                                                                 d.y, conditions[name], 0.95,
                                                                 feint::stats::kJzsMediumScale, true);
    const auto& g = rows[name];
    ASSERT_EQ(res.slopes.size() + res.differences.size(), g.size());
    for (std::size_t i = 0; i < g.size(); ++i) {
      const auto& row = g[i];  // set,kind,strategy,condition,n,left_out,estimate,se,df,t,p,lower,upper,
                               // log_bf10,ttestbf_log_bf,d_z,d_z_low,d_z_high
      const bool slope = row[1] == "slope";
      const auto& r = slope ? res.slopes[i] : res.differences[i - res.slopes.size()];
      SCOPED_TRACE(row[1] + " " + row[2] + " " + row[3]);
      ASSERT_EQ(r.strategy, row[2]);
      ASSERT_EQ(r.condition, row[3]);
      EXPECT_EQ(r.participants, std::stoul(row[4]));
      EXPECT_EQ(r.left_out, std::stoul(row[5]));
      if (row[6] == "NA") {
        EXPECT_FALSE(r.test.computed);
        ++not_computable;
        continue;
      }
      ASSERT_TRUE(r.test.computed) << r.test.note;
      EXPECT_EQ(r.test.test, slope ? "one_sample_t" : "paired_t");
      for (const auto& [got, col] : {std::pair{*r.test.estimate, 6}, {r.std_error, 7}, {*r.test.df, 8},
                                     {*r.test.statistic, 9}, {*r.test.p_value, 10}, {*r.test.conf_low, 11},
                                     {*r.test.conf_high, 12}}) {
        feint::test::record("exposure slopes within (lm, t.test paired)", got, std::stod(row[col]), name);
        EXPECT_PRED3(near_rel, got, std::stod(row[col]), 1e-10) << "column " << golden[0][col];
      }
      ++compared;
      if (slope) continue;
      ASSERT_TRUE(r.test.log_bf10 && r.test.cohen_d && r.test.cohen_d_low && r.test.cohen_d_high);
      feint::test::record("exposure slopes within: log BF (exact integral)", *r.test.log_bf10, std::stod(row[13]), name);
      EXPECT_NEAR(*r.test.log_bf10, std::stod(row[13]), 1e-12);
      for (const auto& [got, col] : {std::pair{*r.test.cohen_d, 15}, {*r.test.cohen_d_low, 16},
                                     {*r.test.cohen_d_high, 17}}) {
        const double want = std::stod(row[col]);
        feint::test::record("exposure slopes within: d_z and its CI (exact roots)", got, want, name);
        EXPECT_NEAR(got, want, 1e-11 * std::max(1.0, std::fabs(want))) << "column " << golden[0][col];
      }
    }
  }
  EXPECT_EQ(compared, 44u);
  EXPECT_EQ(not_computable, 4u);
}

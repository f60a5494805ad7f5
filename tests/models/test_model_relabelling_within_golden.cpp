// Relabelling p-values of the models' condition tests with the conditions within participants
// (models::relabel_condition_tests, options.within) against lme4/lmerTest refits of every labelling
// (tests/golden/models/relabel_within_golden.R): two conditions (complete; 12 % of the trials
// missing; AR(1) trials with a shift) and three (complete; trials missing).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "accuracy.hpp"
#include "feint/models/model_relabelling.hpp"
#include "golden_csv.hpp"

namespace {

using feint::models::LongData;

LongData load(const std::string& dataset) {
  static const auto rows = feint::test::read_csv(feint::test::kModelGoldenDir + "relabel_within_data.csv");
  LongData d;
  for (std::size_t r = 1; r < rows.size(); ++r) {  // dataset,participant,condition,iteration,y
    if (rows[r][0] != dataset) continue;
    d.participant.push_back(rows[r][1]);
    d.group.push_back(rows[r][2]);
    d.time.push_back(std::stod(rows[r][3]));
    d.y.push_back(std::stod(rows[r][4]));
  }
  return d;
}

}  // namespace

// The observed F and t at 1e-6 relative (two REML fits, each stopped by its own optimiser); the
// p-values are counts over the same labellings: equal. A labelling that ties the observed statistic
// in exact arithmetic (the mirror swap of every participant for w2_missing's interaction F; one that
// mirrors b against a for w3_complete's slope of b) is computed about 8e-9 (relative) off the
// observed one, so it counts only because the tie margin (relabelling_threshold) is wider than the
// fits' precision: with the old 1e-9 margin p was 47/64 against R's 48/64, and 9/216 against 10/216.
TEST(ModelRelabellingWithinGolden, EveryLabellingRefittedByLmerTest) {
  std::map<std::string, std::map<std::string, double>> g;
  for (const auto& row : feint::test::read_csv(feint::test::kModelGoldenDir + "relabel_within_golden.csv"))
    if (row.size() == 3 && row[0] != "dataset") g[row[0]][row[1]] = std::stod(row[2]);
  ASSERT_EQ(g.size(), 5u);
  for (const auto& [name, want] : g) {
    SCOPED_TRACE(name);
    const std::vector<std::string> levels =
        want.count("slope_t_c") ? std::vector<std::string>{"a", "b", "c"} : std::vector<std::string>{"a", "b"};
    feint::models::RelabellingOptions o;
    o.within = true;
    const auto r = feint::models::relabel_condition_tests(load(name), levels, o);
    EXPECT_TRUE(r.exact);
    EXPECT_EQ(r.labellings, want.at("labellings"));
    EXPECT_EQ(r.not_computable, want.at("not_computable"));
    ASSERT_TRUE(r.interaction_f && r.condition_f);
    ASSERT_EQ(r.slope_differences_t.size(), levels.size() - 1);
    auto close = [&](double got, double w, const std::string& q) {
      feint::test::record("relabelling within (lmerTest refits) statistics", got, w, name + " " + q);
      EXPECT_NEAR(got, w, 1e-6 * std::max(1.0, std::fabs(w))) << q;
    };
    close(*r.interaction_f, want.at("interaction_f"), "interaction F");
    close(*r.condition_f, want.at("condition_f"), "condition F");
    EXPECT_DOUBLE_EQ(*r.p_interaction, want.at("p_interaction"));
    EXPECT_DOUBLE_EQ(*r.p_condition, want.at("p_condition"));
    for (std::size_t k = 1; k < levels.size(); ++k) {
      ASSERT_TRUE(r.slope_differences_t[k - 1] && r.p_slope_differences[k - 1]);
      close(*r.slope_differences_t[k - 1], want.at("slope_t_" + levels[k]), "slope t " + levels[k]);
      EXPECT_DOUBLE_EQ(*r.p_slope_differences[k - 1],
                       want.at("p_slope_" + levels[k]))
          << levels[k];
    }
  }
}

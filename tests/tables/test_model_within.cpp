// `feint model` with the condition within participants (ModelOptions::condition_within) and the
// random slope of the condition (random_condition_slope): the formula actually fitted, the fit
// (REML criterion and variance components against lme4, tests/golden/models/lmm_within_golden.R),
// the missing trials counted per participant x condition seen, the rendered variance components,
// and the options refused.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "feint/error.hpp"
#include "feint/tables/model.hpp"
#include "stats/golden_csv.hpp"

namespace fs = std::filesystem;
using namespace feint;

namespace {

const std::string kDir = std::string(FEINT_SOURCE_DIR) + "/tests/golden/models/";

// One data set of lmm_within_data.csv as a scores table (metric "error").
io::ScoresTable scores_of(const std::string& dataset) {
  const test::GoldenCsv data(kDir + "lmm_within_data.csv");
  const fs::path tmp = fs::temp_directory_path() / ("feint-model-within-" + dataset + ".csv");
  {
    std::ofstream out(tmp);
    out << "participant,condition,iteration,error\n";
    for (const auto& r : data.rows())
      if (r.str("dataset") == dataset)
        out << r.str("participant") << ',' << r.str("condition") << ',' << r.str("iteration") << ','
            << r.str("y") << '\n';
  }
  io::ScoresOptions o;
  o.metrics = {"error"};
  auto scores = io::load_scores(tmp.string(), o);
  fs::remove(tmp);
  return scores;
}

// lme4's value of `quantity` / `name` for the data set and model (f_int, f_slope).
double lme4(const std::string& dataset, const std::string& model, const std::string& quantity,
            const std::string& name = "") {
  static const test::GoldenCsv g(kDir + "lmm_within_golden.csv");
  for (const auto& r : g.rows())
    if (r.str("dataset") == dataset && r.str("model") == model && r.str("quantity") == quantity &&
        r.str("name") == name)
      return r.number("value");
  ADD_FAILURE() << "no golden " << dataset << " " << model << " " << quantity << " " << name;
  return NAN;
}

tables::ModelOptions within_options(bool slope) {
  tables::ModelOptions o;
  o.metrics = {"error"};
  o.condition_within = true;
  o.random_condition_slope = slope;
  return o;
}

TEST(ModelWithin, RandomConditionSlopeFitsLme4sModelAndSaysSo) {
  const auto a = tables::build_model_analysis(scores_of("balanced2x5"), within_options(true));
  const auto& m = a.models.at(0);
  EXPECT_EQ(m.formula, "error ~ condition * iteration + (1 + condition | participant)");
  EXPECT_NEAR(m.fit.reml_criterion, lme4("balanced2x5", "f_slope", "REMLcrit"), 1e-11);
  const auto& v = m.fit.variance;
  ASSERT_EQ(v.group_slopes.size(), 1u);
  EXPECT_NEAR(v.group_slopes[0], lme4("balanced2x5", "f_slope", "variance",
                                      "participant conditionrandom"), 1e-8);
  EXPECT_NEAR(v.group_correlations.at(0), lme4("balanced2x5", "f_slope", "correlation",
                                               "(Intercept) conditionrandom"), 1e-6);
  const auto notes = tables::model_notes(a, m);
  EXPECT_NE(notes.at(0).find("Linear mixed model error ~ condition * iteration + (1 + condition | "
                             "participant) (iteration as a factor; condition within participants"),
            std::string::npos)
      << notes.at(0);
  const std::string text = tables::render_model(a, tables::OutputFormat::text);
  EXPECT_NE(text.find("conditionrandom"), std::string::npos) << text;
  EXPECT_NE(text.find("depends on the condition: no single ICC"), std::string::npos) << text;
  const std::string csv = tables::render_model(a, tables::OutputFormat::csv);
  EXPECT_NE(csv.find("var__conditionrandom"), std::string::npos) << csv;
  EXPECT_NE(csv.find("cor__(Intercept).conditionrandom"), std::string::npos) << csv;
}

TEST(ModelWithin, ConditionWithinWithARandomInterceptOnly) {
  const auto a = tables::build_model_analysis(scores_of("balanced2x5"), within_options(false));
  const auto& m = a.models.at(0);
  EXPECT_EQ(m.formula, "error ~ condition * iteration + (1 | participant)");
  EXPECT_NEAR(m.fit.reml_criterion, lme4("balanced2x5", "f_int", "REMLcrit"), 1e-11);
  EXPECT_NEAR(m.fit.variance.participant,
              lme4("balanced2x5", "f_int", "variance", "participant (Intercept)"), 1e-8);
  // Every participant counts in both conditions.
  ASSERT_EQ(m.participants_per_group.size(), 2u);
  EXPECT_EQ(m.participants_per_group[0].second, 16u);
  EXPECT_EQ(m.participants_per_group[1].second, 16u);
  EXPECT_EQ(m.trials_missing, 0u);
}

TEST(ModelWithin, MissingTrialsArePerParticipantAndConditionSeen) {
  // 14 participants x 2 conditions x 5 iterations, 5 % of the trials dropped, P03 and P11 saw only
  // 'adaptive': 124 trials, 6 of them missing in 5 participant x condition pairs (counted from
  // lmm_within_data.csv); the conditions a participant never saw are not missing trials.
  const auto a =
      tables::build_model_analysis(scores_of("one_condition_participant"), within_options(true));
  const auto& m = a.models.at(0);
  EXPECT_EQ(m.fit.n_obs, 124u);
  EXPECT_EQ(m.trials_missing, 6u);
  EXPECT_EQ(m.participants_with_missing, 5u);
  EXPECT_NEAR(m.fit.reml_criterion, lme4("one_condition_participant", "f_slope", "REMLcrit"), 1e-11);
  const auto notes = tables::model_notes(a, m);
  bool said = false;
  for (const auto& n : notes)
    said = said || n.find("6 participant x condition (seen) x iteration trials") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(ModelWithin, RefusedOptions) {
  tables::ModelOptions o = within_options(true);
  o.condition_within = false;
  try {
    tables::validate(o);
    FAIL() << "expected UsageError";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--random-condition-slope"), std::string::npos);
  }
  EXPECT_THROW(tables::build_model_analysis(scores_of("balanced2x5"), o), UsageError);
  o.condition_within = true;
  o.trend = true;
  o.random_slope = true;
  EXPECT_THROW(tables::validate(o), UsageError);
  // Without condition_within the data's participants in two conditions are refused, as before.
  tables::ModelOptions between;
  between.metrics = {"error"};
  EXPECT_THROW(tables::build_model_analysis(scores_of("balanced2x5"), between), InvalidData);
}

}  // namespace

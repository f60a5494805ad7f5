// build_anova_report(..., condition_within = true): each metric gets the all-within ANOVA
// (models::within_anova, golden-tested against afex in tests/models/test_within_anova_golden.cpp);
// here: the report carries those numbers into the tidy CSV, and the text table renders the
// within rows (condition within, Mauchly per effect, '1 df' for a one-df effect).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/tables/anova.hpp"
#include "stats/golden_csv.hpp"

namespace fs = std::filesystem;
using namespace feint;

namespace {

const std::string kDir = std::string(FEINT_SOURCE_DIR) + "/tests/golden/models/";

// One data set of within_anova_data.csv as a scores table (metric "y").
io::ScoresTable scores_of(const std::string& dataset) {
  const test::GoldenCsv data(kDir + "within_anova_data.csv");
  const fs::path tmp = fs::temp_directory_path() / ("feint-within-" + dataset + ".csv");
  {
    std::ofstream out(tmp);
    out << "participant,condition,iteration,y\n";
    for (const auto& r : data.rows())
      if (r.str("dataset") == dataset)
        out << r.str("participant") << ',' << r.str("condition") << ',' << r.str("iteration") << ','
            << r.str("y") << '\n';
  }
  io::ScoresOptions o;
  o.metrics = {"y"};
  auto scores = io::load_scores(tmp.string(), o);
  fs::remove(tmp);
  return scores;
}

// The tidy CSV's rows keyed by effect.
std::map<std::string, std::map<std::string, std::string>> csv_rows(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  const auto header = test::split_commas(line);
  std::map<std::string, std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const auto cells = test::split_commas(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    rows[row["effect"]] = row;
  }
  return rows;
}

// The text with its notes' line breaks made spaces.
std::string unwrapped(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

// The text table's effect rows keyed by effect (the first word of the row; the rows come before
// the notes).
std::map<std::string, std::string> effect_rows(const std::string& text) {
  std::map<std::string, std::string> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line))
    for (const char* effect : {"condition ", "iteration ", "condition:iteration "})
      if (line.rfind(effect, 0) == 0)
        rows.emplace(std::string(effect, std::strlen(effect) - 1), line);
  return rows;
}

TEST(AnovaWithin, ReportCarriesTheWithinAnalysisIntoTheTidyTable) {
  const auto scores = scores_of("nonspherical");
  const auto report =
      tables::build_anova_report(scores, models::SphericityCorrection::GG, false, {}, true);
  ASSERT_EQ(report.analyses.size(), 1u);
  const auto rows = csv_rows(tables::render_anova(report, tables::OutputFormat::csv));
  const test::GoldenCsv golden(kDir + "within_anova_golden.csv");
  std::size_t checked = 0;
  for (const auto& g : golden.rows()) {
    if (g.str("dataset") != "nonspherical") continue;
    const auto& r = rows.at(g.str("effect"));
    const std::string w = g.str("effect");
    EXPECT_NEAR(std::stod(r.at("F")), g.number("F"), 1e-10 * g.number("F")) << w;
    EXPECT_NEAR(std::stod(r.at("den_df")), g.number("gg_den_df"), 1e-10 * g.number("gg_den_df"))
        << w;
    EXPECT_NEAR(std::stod(r.at("p.value")), g.number("gg_p"), 1e-10 * g.number("gg_p")) << w;
    EXPECT_NEAR(std::stod(r.at("ges")), g.number("ges"), 1e-10 * g.number("ges")) << w;
    EXPECT_NEAR(std::stod(r.at("mauchly_W")), g.number("mauchly_w"), 1e-10 * g.number("mauchly_w"))
        << w;
    EXPECT_EQ(r.at("correction"), "GG") << w;  // the condition row is within, so corrected
    ++checked;
  }
  EXPECT_EQ(checked, 3u);
}

TEST(AnovaWithin, TextTableRendersConditionWithinWithItsOwnSphericity) {
  const auto report = tables::build_anova_report(scores_of("balanced_2x5"),
                                                 models::SphericityCorrection::GG, false, {}, true);
  const std::string text = tables::render_anova(report, tables::OutputFormat::text);
  EXPECT_NE(text.find("condition and iteration within participants"), std::string::npos) << text;
  EXPECT_NE(text.find("condition (2 levels) \u00d7 iteration (5 levels), both within"),
            std::string::npos)
      << text;
  EXPECT_NE(unwrapped(text).find("12 participants with every condition at every iteration"),
            std::string::npos)
      << text;
  // Two conditions: the condition row has one df, so sphericity holds trivially ('1 df'), while
  // iteration and the interaction have their own epsilons (GG .467 and .749 from afex).
  const auto rows = effect_rows(text);
  EXPECT_NE(rows.at("condition").find("1 df"), std::string::npos) << text;
  EXPECT_EQ(rows.at("condition").find("singular"), std::string::npos) << text;
  EXPECT_NE(rows.at("iteration").find(".467"), std::string::npos) << text;
  EXPECT_NE(rows.at("condition:iteration").find(".749"), std::string::npos) << text;
}

TEST(AnovaWithin, ASingularEffectIsMarkedAndTheOthersCorrected) {
  // Three participants, 3 x 3: 2 error df, so the interaction's 4 x 4 error SSP is singular while
  // condition and iteration (2 contrasts each) keep their epsilons (.695 and .571 from afex).
  const auto report = tables::build_anova_report(scores_of("three_participants"),
                                                 models::SphericityCorrection::GG, false, {}, true);
  const std::string text = tables::render_anova(report, tables::OutputFormat::text);
  const auto rows = effect_rows(text);
  EXPECT_NE(rows.at("condition").find(".695"), std::string::npos) << text;
  EXPECT_NE(rows.at("iteration").find(".571"), std::string::npos) << text;
  EXPECT_NE(rows.at("condition:iteration").find("singular"), std::string::npos) << text;
  EXPECT_NE(rows.at("condition:iteration").find("(a)"), std::string::npos) << text;
  EXPECT_NE(
      unwrapped(text).find("sphericity test and corrections of condition:iteration not computable"),
      std::string::npos)
      << text;
}

TEST(AnovaWithin, EmmeansAreRefusedAndTheBetweenDesignIsUnchanged) {
  const auto scores = scores_of("two_by_two");
  tables::AnovaEmmOptions emm;
  emm.emmeans = true;
  EXPECT_THROW(
      tables::build_anova_report(scores, models::SphericityCorrection::GG, false, emm, true),
      UsageError);
  // Without the flag the same table is the split-plot ANOVA, which refuses a participant in two
  // conditions.
  EXPECT_THROW(tables::build_anova_report(scores, models::SphericityCorrection::GG), InvalidData);
}

}  // namespace

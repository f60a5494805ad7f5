// The questionnaire of a within-participants study (data/demo-within: each participant answered
// after each condition, questionnaire.csv and questionnaire_yesno.csv written by `feint simulate
// study --design within`) is compared paired, with no flag: the design is read off the data, the
// Likert items by the paired Wilcoxon signed-rank test and the paired t, the yes/no question by
// McNemar's exact test; checked against the answers read here independently.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "feint/analysis/analyze.hpp"
#include "feint/io/csv.hpp"

using namespace feint;

namespace {

const std::string kWithin = std::string(FEINT_SOURCE_DIR) + "/data/demo-within";

const analysis::StudyResults& study() {
  static const analysis::StudyResults r = [] {
    analysis::AnalysisSettings s;  // no design declared: read off the data
    s.compare = "adaptive,random";
    s.scoring.norm = "raw";
    s.metrics = {"error=0.5", "confusion=0.95@raw"};
    return analysis::analyze(analysis::load_study(kWithin, s), "test");
  }();
  return r;
}

// participant -> condition -> the column's answers, read straight from the file.
std::map<std::string, std::map<std::string, std::string>> answers(const std::string& file, const std::string& column) {
  std::ifstream in(kWithin + "/" + file);
  std::string line;
  std::getline(in, line);
  const auto header = io::split_csv_line(line);
  const auto col = static_cast<std::size_t>(std::find(header.begin(), header.end(), column) - header.begin());
  std::map<std::string, std::map<std::string, std::string>> out;
  while (std::getline(in, line)) {
    const auto f = io::split_csv_line(line);
    out[f.at(0)][f.at(1)] = f.at(col);
  }
  return out;
}

}  // namespace

TEST(WithinQuestionnaire, LikertItemsAreComparedPairedWithNoFlag) {
  const auto& r = study();
  ASSERT_TRUE(r.likert_compare.has_value());
  const auto& a = *r.likert_compare;
  EXPECT_TRUE(a.paired);
  EXPECT_TRUE(a.unpaired.empty());
  ASSERT_EQ(a.rows.size(), 8u);  // four items, signed-rank then paired t
  // deception (item 2): the paired t from the differences computed here.
  const auto file = answers("questionnaire.csv", "deception");
  ASSERT_EQ(file.size(), 24u);
  std::vector<double> d;
  for (const auto& [p, by] : file) d.push_back(std::stod(by.at("adaptive")) - std::stod(by.at("random")));
  double mean = 0, ss = 0;
  for (double v : d) mean += v / static_cast<double>(d.size());
  for (double v : d) ss += (v - mean) * (v - mean);
  const double t = mean / std::sqrt(ss / static_cast<double>(d.size() - 1) / static_cast<double>(d.size()));
  const auto& w = a.rows[2].result;
  const auto& tt = a.rows[3].result;
  EXPECT_EQ(w.test, "wilcoxon_signed_rank");
  EXPECT_EQ(tt.test, "paired_t");
  EXPECT_EQ(tt.n1, 24u);
  EXPECT_NEAR(*tt.statistic, t, 1e-10 * std::max(1.0, std::abs(t)));
  EXPECT_EQ(*tt.df, 23.0);
  // The findings keep their between-design ids and name the paired test.
  const auto f = std::find_if(r.findings.begin(), r.findings.end(),
                              [](const auto& x) { return x.id == "H2-compare-deception"; });
  ASSERT_NE(f, r.findings.end());
  EXPECT_EQ(f->test, "Wilcoxon signed-rank test (paired)");
  EXPECT_EQ(f->contrast, "adaptive - random");
}

TEST(WithinQuestionnaire, YesNoIsComparedByMcNemar) {
  const auto& r = study();
  ASSERT_TRUE(r.yes_no.has_value());
  ASSERT_EQ(r.yes_no->rows.size(), 2u);
  const auto& e = r.yes_no->rows[0].result;
  EXPECT_EQ(e.test, "mcnemar_exact");
  std::size_t b = 0, c = 0;
  for (const auto& [p, by] : answers("questionnaire_yesno.csv", "intentional")) {
    b += by.at("adaptive") == "yes" && by.at("random") == "no";
    c += by.at("adaptive") == "no" && by.at("random") == "yes";
  }
  EXPECT_EQ(*e.statistic, static_cast<double>(b));
  EXPECT_EQ(e.n1, 24u);
  // Two-sided exact binomial p of b among the b + c discordant pairs, summed here.
  double lower = 0, upper = 0;
  for (std::size_t k = 0; k <= b + c; ++k) {
    const double pk = std::exp(std::lgamma(b + c + 1.0) - std::lgamma(k + 1.0) - std::lgamma(b + c - k + 1.0) -
                               static_cast<double>(b + c) * std::log(2.0));
    if (k <= b) lower += pk;
    if (k >= b) upper += pk;
  }
  EXPECT_NEAR(*e.p_value, std::min(1.0, 2 * std::min(lower, upper)), 1e-12);
  EXPECT_EQ(r.yes_no->rows[1].result.test, "mcnemar");
}

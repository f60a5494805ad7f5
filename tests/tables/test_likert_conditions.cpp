// A questionnaire across three or more conditions (feint/tables/likert_conditions.hpp) against R:
// every number of tests/golden/likert/likert_conditions_golden.csv (made by
// likert_conditions_golden.R with kruskal.test, effectsize::rank_epsilon_squared,
// pairwise.wilcox.test(p.adjust.method = "holm") and t.test with p.adjust "holm") on its six data
// sets (tests/data/likert/three_conditions.csv and five generated ones: balanced, unbalanced with
// missing answers, four conditions with ties, five small conditions, a large study), then the
// protection of the pairs by the omnibus test and the rejections.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <tuple>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/questionnaire.hpp"
#include "feint/tables/likert_conditions.hpp"

using namespace feint;

namespace {

using Key = std::tuple<std::string, std::string, std::string, std::string>;  // item, group1, group2, quantity

/// Per data set, its golden values.
std::map<std::string, std::map<Key, double>> read_golden() {
  std::ifstream in(std::string(FEINT_SOURCE_DIR) + "/tests/golden/likert/likert_conditions_golden.csv");
  std::map<std::string, std::map<Key, double>> out;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const auto f = io::split_csv_line(line);
    out[f.at(0)][{f.at(1), f.at(2), f.at(3), f.at(4)}] = std::stod(f.at(5));
  }
  return out;
}

tables::LikertConditions analysis(const std::string& data = "three") {
  const std::string path = data == "three" ? std::string(FEINT_TEST_DATA_DIR) + "/likert/three_conditions.csv"
                                           : std::string(FEINT_SOURCE_DIR) +
                                                 "/tests/golden/likert/data/conditions_" + data + ".csv";
  return tables::analyze_likert_conditions(io::load_questionnaire(path, {}), {});
}

void expect_close(double feint_value, double r_value, const std::string& what) {
  EXPECT_NEAR(feint_value, r_value, 1e-10 * std::max(1.0, std::abs(r_value))) << what;
}

}  // namespace

TEST(LikertConditions, EveryNumberOfEveryDataSetEqualsR) {
  const auto all = read_golden();
  ASSERT_EQ(all.size(), 6u) << "golden file missing or truncated";
  ASSERT_EQ(all.at("three").size(), 88u);
  ASSERT_EQ(analysis().conditions, (std::vector<std::string>{"adaptive", "random", "fixed-block"}));
  for (const auto& [data, golden] : all) {
    const auto a = analysis(data);
    std::size_t checked = 0;
    auto check = [&](const Key& key, std::optional<double> value) {
      const std::string what =
          data + " " + std::get<0>(key) + " " + std::get<1>(key) + " " + std::get<2>(key) + " " + std::get<3>(key);
      const auto it = golden.find(key);
      ASSERT_NE(it, golden.end()) << what;
      ASSERT_TRUE(value.has_value()) << what;
      expect_close(*value, it->second, what);
      ++checked;
    };
    for (const auto& row : a.omnibus) {
      const auto& r = row.result;
      check({row.metric, row.group1, "", "H"}, r.statistic);
      check({row.metric, row.group1, "", "df"}, r.df);
      check({row.metric, row.group1, "", "p"}, r.p_value);
      check({row.metric, row.group1, "", "epsilon2"}, r.rank_epsilon_squared);
    }
    for (const auto& pair : a.pairs)
      for (std::size_t i = 0; i + 1 < pair.rows.size(); i += 2) {
        const auto& mw = pair.rows[i];
        const auto& t = pair.rows[i + 1];
        ASSERT_EQ(mw.result.test, "mann_whitney");
        check({mw.metric, mw.group1, mw.group2, "W"}, mw.result.statistic);
        check({mw.metric, mw.group1, mw.group2, "p_mw"}, mw.result.p_value);
        check({mw.metric, mw.group1, mw.group2, "p_mw_holm"}, mw.result.p_adjusted);
        check({t.metric, t.group1, t.group2, "t"}, t.result.statistic);
        check({t.metric, t.group1, t.group2, "df_t"}, t.result.df);
        check({t.metric, t.group1, t.group2, "p_t_holm"}, t.result.p_adjusted);
      }
    EXPECT_EQ(checked, golden.size()) << data;
  }
}

TEST(LikertConditions, PairsDifferOnlyAfterTheOmnibusTestAndTheirHolmP) {
  const auto a = analysis();
  // trust: fixed-block answers 3 points higher; the omnibus test shows it (p = 3.2e-05).
  std::map<std::pair<std::string, std::string>, std::string> trust_labels;
  for (const auto& pair : a.pairs)
    for (const auto& row : pair.rows)
      if (row.metric == "trust" && row.result.test == "mann_whitney") trust_labels[{row.group1, row.group2}] = row.label;
  EXPECT_EQ(trust_labels.at({"adaptive", "fixed-block"}), "A<B");
  EXPECT_EQ(trust_labels.at({"random", "fixed-block"}), "A<B");
  EXPECT_EQ(trust_labels.at({"adaptive", "random"}), "n.s.");  // Holm p = .072
  // Every other item: the omnibus test shows nothing, so no pair is labelled as differing.
  for (const auto& pair : a.pairs)
    for (const auto& row : pair.rows)
      if (row.metric != "trust") {
        EXPECT_TRUE(row.label == "n.s." || row.label.find("\u2248") != std::string::npos)
            << row.metric << " " << row.group1 << " " << row.group2 << " " << row.label;
      }
  const std::string text = tables::render_likert_conditions(a, tables::OutputFormat::text);
  EXPECT_NE(text.find("Questionnaire across the 3 conditions: Kruskal-Wallis test per item"), std::string::npos);
  EXPECT_NE(text.find("differ"), std::string::npos);
  const std::string csv = tables::render_likert_conditions(a, tables::OutputFormat::csv);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 4 + 3 * 8);  // header, omnibus, 3 pairs x 4 items x 2 tests
}

TEST(LikertConditions, RefusesWithoutConditionsOrWithASharedParticipant) {
  io::Questionnaire q = io::load_questionnaire(std::string(FEINT_TEST_DATA_DIR) + "/likert/three_conditions.csv", {});
  io::Questionnaire no_condition = q;
  no_condition.has_condition = false;
  EXPECT_THROW(tables::analyze_likert_conditions(no_condition, {}), UsageError);
  io::Questionnaire shared = q;
  shared.participants[1] = shared.participants.back();  // one person in adaptive and in fixed-block
  try {
    tables::analyze_likert_conditions(shared, {});
    FAIL() << "a participant in two conditions accepted";
  } catch (const InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("answered in both conditions"), std::string::npos) << e.what();
  }
}

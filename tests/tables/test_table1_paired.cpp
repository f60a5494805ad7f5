// Table 1 with two conditions within participants (--compare adaptive,random --paired --p-adjust
// holm) against R: every number of tests/golden/table1_paired/table1_paired_golden.csv (made by
// table1_paired_golden.R beside it with t.test(paired = TRUE), the exact roots of the noncentral t
// for d_z, the defining integral of the JZS Bayes factor and p.adjust) on its six scores files:
// complete, empty cells and absent trials, participants in one condition only, four participants
// with untestable cells, a strong effect, values with ties and zero differences.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <tuple>

#include "accuracy.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/scores.hpp"
#include "feint/tables/table1.hpp"

using namespace feint;

namespace {

const std::string kDir = std::string(FEINT_SOURCE_DIR) + "/tests/golden/table1_paired/";
const std::vector<std::string> kSets = {"p2_complete.csv", "p2_missing.csv", "p2_unbalanced.csv",
                                        "p2_small.csv",    "p2_strong.csv",  "p2_ties.csv"};

using Key = std::tuple<std::string, std::string, std::string, std::string>;  // dataset, metric, iteration, quantity

std::map<Key, std::string> read_golden() {
  std::ifstream in(kDir + "table1_paired_golden.csv");
  std::map<Key, std::string> out;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const auto f = io::split_csv_line(line);
    out[{f.at(0), f.at(1), f.at(2), f.at(3)}] = f.at(4);
  }
  return out;
}

tables::Table1 paired_table(const std::string& file) {
  io::ScoresOptions so;
  so.metrics = {"error", "confusion"};
  tables::Table1Options o;
  o.compare = std::make_pair(std::string("adaptive"), std::string("random"));
  o.paired = true;
  o.p_adjust = stats::PAdjustMethod::holm;
  return tables::build_table1(io::load_scores(kDir + file, so), o);
}

// Tolerances (relative, absolute below 1): the t test's closed forms and Holm 1e-10; d_z, g_z and
// their bounds 1e-11 (R's roots are of the integral of the noncentral t's definition, rel.tol
// 1e-13); the log Bayes factor 1e-12 (both integrate its definition to rel.tol 1e-12).
struct Quantity {
  const char* name;
  std::optional<double> stats::TestResult::*field;
  double tolerance;
};
const std::vector<Quantity> kQuantities = {
    {"t", &stats::TestResult::statistic, 1e-10},        {"df", &stats::TestResult::df, 1e-10},
    {"p", &stats::TestResult::p_value, 1e-10},          {"conf_low", &stats::TestResult::conf_low, 1e-10},
    {"conf_high", &stats::TestResult::conf_high, 1e-10}, {"estimate", &stats::TestResult::estimate, 1e-10},
    {"d_z", &stats::TestResult::cohen_d, 1e-11},        {"d_z_low", &stats::TestResult::cohen_d_low, 1e-11},
    {"d_z_high", &stats::TestResult::cohen_d_high, 1e-11}, {"g_z", &stats::TestResult::hedges_g, 1e-11},
    {"g_z_low", &stats::TestResult::hedges_g_low, 1e-11}, {"g_z_high", &stats::TestResult::hedges_g_high, 1e-11},
    {"log_bf10", &stats::TestResult::log_bf10, 1e-12},  {"p_holm", &stats::TestResult::p_adjusted, 1e-10}};

}  // namespace

TEST(Table1PairedGolden, EveryNumberOfEveryDataSetEqualsR) {
  const auto golden = read_golden();
  ASSERT_FALSE(golden.empty()) << "golden file missing";
  std::size_t checked = 0, not_computable = 0;
  for (const auto& set : kSets) {
    SCOPED_TRACE(set);
    const auto t = paired_table(set);
    for (const auto& row : t.rows) {
      ASSERT_EQ(row.result.test, "paired_t");
      const std::string it = std::to_string(*row.iteration);
      const std::string where = set + " " + row.metric + " " + it;
      const auto n = golden.find({set, row.metric, it, "n"});
      ASSERT_NE(n, golden.end()) << where;
      EXPECT_EQ(row.result.n1, std::stoul(n->second)) << where;
      ++checked;
      if (golden.at({set, row.metric, it, "t"}) == "NA") {  // R: too few pairs, or constant differences
        EXPECT_FALSE(row.result.computed) << where;
        EXPECT_FALSE(row.result.p_adjusted.has_value()) << where;
        ++not_computable;
        continue;
      }
      ASSERT_TRUE(row.result.computed) << where << ": " << row.result.note;
      for (const auto& q : kQuantities) {
        const auto got = row.result.*q.field;
        ASSERT_TRUE(got.has_value()) << where << " " << q.name;
        const double want = std::stod(golden.at({set, row.metric, it, q.name}));
        feint::test::record(std::string("Table 1 paired (t.test, d_z, BF, Holm): ") + q.name, *got, want, where);
        EXPECT_NEAR(*got, want, q.tolerance * std::max(1.0, std::fabs(want))) << where << " " << q.name;
        ++checked;
      }
    }
  }
  EXPECT_EQ(not_computable, 2u);
  EXPECT_EQ(checked, golden.size() - 2 * 14 - 54);  // less the NA cells' other quantities and the BF cross-checks
}

TEST(Table1PairedGolden, ParticipantsInOneConditionAreLeftOutAndNamed) {
  const auto t = paired_table("p2_unbalanced.csv");
  bool named = false;
  for (const auto& w : t.warnings)
    named = named || (w.find("without a pair") != std::string::npos && w.find("P02") != std::string::npos &&
                      w.find("P05") != std::string::npos && w.find("P07") != std::string::npos &&
                      w.find("P10") != std::string::npos && w.find("P13") != std::string::npos);
  EXPECT_TRUE(named);
}

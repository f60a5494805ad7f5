// End-to-end tests of `feint simulate selection` (runs the feint binary, FEINT_EXE).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_helpers.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;

namespace {

/// A small CSV table: header names -> column of cells.
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::size_t col(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return i;
    }
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
  double num(std::size_t row, const std::string& name) const {
    const auto v = feint::io::parse_double(rows.at(row).at(col(name)));
    EXPECT_TRUE(v.has_value()) << name << " = '" << rows.at(row).at(col(name)) << "'";
    return v.value_or(-1);
  }
};

Table parse(const std::string& text) {
  Table t;
  std::istringstream in(text);
  std::string line;
  bool first = true;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    auto cells = feint::io::split_csv_line(line);
    if (first) {
      t.header = cells;
      first = false;
    } else {
      EXPECT_EQ(cells.size(), t.header.size()) << line;
      t.rows.push_back(cells);
    }
  }
  return t;
}

}  // namespace

TEST(SimulateSelectionCli, DefaultsGiveATextSummaryOfTheAdaptiveAlgorithm) {
  const auto r = run_feint("simulate selection");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("10 runs of 20 iterations"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("adaptive"), std::string::npos);
  EXPECT_NE(r.out.find("0.5"), std::string::npos);
}

TEST(SimulateSelectionCli, CsvSummaryHasTheContractColumns) {
  const auto r = run_feint("simulate selection --algorithm random --runs 2000 --seed 4 --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = parse(r.out);
  ASSERT_EQ(t.rows.size(), 1u);
  for (const char* c : {"algorithm", "lambda", "iterations", "runs", "entropy_mean", "entropy_sd",
                        "entropy_pooled", "repetition_mean", "conditional_entropy_mean",
                        "guess_accuracy_mean", "batch_entropy_mean_q025", "batch_entropy_mean_q975"}) {
    t.col(c);
  }
  EXPECT_EQ(t.rows[0][t.col("algorithm")], "random");
  EXPECT_EQ(t.rows[0][t.col("lambda")], "");  // lambda does not apply to random
  EXPECT_EQ(t.num(0, "runs"), 2000);
  EXPECT_EQ(t.num(0, "iterations"), 20);
  // 2000 runs: the mean entropy is within 5 standard errors of the exact 1.885977
  EXPECT_NEAR(t.num(0, "entropy_mean"), 1.885977, 5 * t.num(0, "entropy_se"));
  EXPECT_LT(t.num(0, "batch_entropy_mean_q025"), t.num(0, "entropy_mean"));
  EXPECT_GT(t.num(0, "batch_entropy_mean_q975"), t.num(0, "entropy_mean"));
}

TEST(SimulateSelectionCli, SameSeedSameOutputDifferentSeedDifferentOutput) {
  const std::string cmd = "simulate selection --runs 500 --format csv --seed ";
  const auto a = run_feint(cmd + "7");
  const auto b = run_feint(cmd + "7 --threads 1");
  const auto c = run_feint(cmd + "8");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(a.out, b.out);  // the thread count does not change the numbers
  EXPECT_NE(a.out, c.out);
  TempDir dir;
  const auto s1 = dir / "s1.csv", s2 = dir / "s2.csv";
  ASSERT_EQ(run_feint("simulate selection --seed 3 --sequences " + shell_quote(s1.string())).exit_code, 0);
  ASSERT_EQ(run_feint("simulate selection --seed 3 --sequences " + shell_quote(s2.string())).exit_code, 0);
  EXPECT_EQ(read_text(s1), read_text(s2));
}

TEST(SimulateSelectionCli, SequencesFileIsTidyAndComplete) {
  TempDir dir;
  const auto seq = dir / "seq.csv";
  const auto r = run_feint("simulate selection --algorithm fixed-block --runs 3 --iterations 8 "
                           "--sequences " + shell_quote(seq.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = parse(read_text(seq));
  EXPECT_EQ(t.header, (std::vector<std::string>{"algorithm", "lambda", "run", "iteration",
                                                "strategy", "variant", "target"}));
  ASSERT_EQ(t.rows.size(), 24u);
  const std::set<std::string> strategies = {"exaggerating", "switching", "ambiguous", "optimal"};
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    EXPECT_EQ(t.num(i, "run"), static_cast<double>(i / 8 + 1));
    EXPECT_EQ(t.num(i, "iteration"), static_cast<double>(i % 8 + 1));
    EXPECT_TRUE(strategies.count(t.rows[i][t.col("strategy")]));
    const auto& v = t.rows[i][t.col("variant")];
    EXPECT_TRUE(v == "main" || v == "v2");
    if (t.rows[i][t.col("strategy")] == "optimal") {
      EXPECT_EQ(v, "main");
    }
    const auto& target = t.rows[i][t.col("target")];
    EXPECT_TRUE(target == "left" || target == "right");
  }
  // fixed-block: each block of four iterations holds every strategy once
  for (std::size_t b = 0; b < 6; ++b) {
    std::set<std::string> block;
    for (std::size_t i = 0; i < 4; ++i) block.insert(t.rows[4 * b + i][t.col("strategy")]);
    EXPECT_EQ(block, strategies);
  }
}

TEST(SimulateSelectionCli, OccurrenceProbabilitiesSumToOnePerIteration) {
  TempDir dir;
  const auto occ = dir / "occ.csv";
  const auto r = run_feint("simulate selection --runs 300 --occurrence " + shell_quote(occ.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = parse(read_text(occ));
  ASSERT_EQ(t.rows.size(), 80u);
  std::map<int, double> sum, cum;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    EXPECT_EQ(t.rows[i][t.col("algorithm")], "adaptive");
    EXPECT_EQ(t.num(i, "lambda"), 0.5);
    sum[static_cast<int>(t.num(i, "iteration"))] += t.num(i, "probability");
    cum[static_cast<int>(t.num(i, "iteration"))] += t.num(i, "cumulative_share");
  }
  ASSERT_EQ(sum.size(), 20u);
  for (const auto& [it, s] : sum) EXPECT_NEAR(s, 1.0, 1e-12) << "iteration " << it;
  for (const auto& [it, s] : cum) EXPECT_NEAR(s, 1.0, 1e-12) << "iteration " << it;
}

TEST(SimulateSelectionCli, CompareAndSweepTabulateEverySetting) {
  const auto cmp = run_feint("simulate selection --compare --runs 400 --format csv");
  ASSERT_EQ(cmp.exit_code, 0) << cmp.err;
  const Table c = parse(cmp.out);
  ASSERT_EQ(c.rows.size(), 4u);
  std::vector<std::string> algs;
  for (const auto& row : c.rows) algs.push_back(row[c.col("algorithm")]);
  EXPECT_EQ(algs, (std::vector<std::string>{"random", "fixed-block", "fixed-balanced", "adaptive"}));
  EXPECT_EQ(c.num(1, "entropy_mean"), 2.0);
  EXPECT_EQ(c.num(1, "entropy_sd"), 0.0);

  const auto sw = run_feint("simulate selection --sweep-lambda 0:1:0.25 --runs 400 --format csv");
  ASSERT_EQ(sw.exit_code, 0) << sw.err;
  const Table s = parse(sw.out);
  ASSERT_EQ(s.rows.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(s.num(i, "lambda"), 0.25 * static_cast<double>(i));
  EXPECT_LT(s.num(0, "entropy_mean"), s.num(2, "entropy_mean"));  // more lambda, more entropy
  EXPECT_EQ(s.num(4, "entropy_mean"), 2.0);                       // lambda = 1: a fixed schedule

  const auto sw2 = run_feint("simulate selection --sweep-lambda 0:1:0.05 --runs 20 --format csv");
  ASSERT_EQ(sw2.exit_code, 0) << sw2.err;
  const Table s2 = parse(sw2.out);
  ASSERT_EQ(s2.rows.size(), 21u);
  EXPECT_EQ(s2.rows[3][s2.col("lambda")], "0.15");
}

TEST(SimulateSelectionCli, JsonAndMarkdownRenderings) {
  TempDir dir;
  const auto json = dir / "s.json";
  auto r = run_feint("simulate selection --runs 50 -o " + shell_quote(json.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string j = read_text(json);
  EXPECT_EQ(j.front(), '[');
  EXPECT_NE(j.find("\"algorithm\": \"adaptive\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"entropy_mean\": 1."), std::string::npos) << j;
  r = run_feint("simulate selection --algorithm random --runs 5 --format json");
  EXPECT_NE(r.out.find("\"lambda\": null"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"batch_entropy_mean_q025\": null"), std::string::npos) << r.out;  // 0 batches
  r = run_feint("simulate selection --runs 50 --format markdown");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("| adaptive"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("-: |"), std::string::npos) << r.out;
  for (const auto& l : {std::string("| adaptive"), std::string("| algorithm")}) {  // one cell per column
    const auto begin = r.out.find(l);
    const auto line = r.out.substr(begin, r.out.find('\n', begin) - begin);
    EXPECT_EQ(std::count(line.begin(), line.end(), '|'), 11) << line;
  }
}

TEST(SimulateSelectionCli, BadOptionsAreUsageErrors) {
  for (const char* args : {"simulate selection --algorithm fixed", "simulate selection --lambda 1.5",
                           "simulate selection --lambda abc", "simulate selection --iterations 0",
                           "simulate selection --runs 0", "simulate selection --sweep-lambda 1:0:0.1",
                           "simulate selection --sweep-lambda 0:1:0", "simulate selection --sweep-lambda 0:1",
                           "simulate selection --format xml", "simulate selection --targets up",
                           "simulate selection --no-such-option", "simulate"}) {
    const auto r = run_feint(args);
    EXPECT_EQ(r.exit_code, 64) << args << "\n" << r.err;
    EXPECT_FALSE(r.err.empty()) << args;
  }
}

TEST(SimulateSelectionCli, UnwritableOutputIsAnIoErrorAndLeavesNothing) {
  TempDir dir;
  const auto out = dir / "no" / "such" / "dir" / "s.csv";
  const auto r = run_feint("simulate selection -o " + shell_quote(out.string()));
  EXPECT_EQ(r.exit_code, 74) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

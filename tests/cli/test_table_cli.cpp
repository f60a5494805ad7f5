// End-to-end tests of `feint table` (runs FEINT_EXE): outputs, messages, exit codes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cli/cli_helpers.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

using feint::test::read_text;
using feint::test::run_feint;
using feint::test::RunResult;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

const std::string kTableDir = std::string(FEINT_TEST_DATA_DIR) + "/table";
const std::string kSmall = kTableDir + "/scores_small.csv";

// Runs feint with the working directory set to tests/data/table, so the note's "Source:" names the
// file as the expected files do.
RunResult run_in_table_dir(const std::string& args) {
  const auto old = std::filesystem::current_path();
  std::filesystem::current_path(kTableDir);
  RunResult r = run_feint(args);
  std::filesystem::current_path(old);
  return r;
}

struct Csv {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
};

Csv read_csv(const std::string& path) {
  feint::io::CsvReader reader(path);
  Csv c;
  c.header = reader.header();
  while (reader.next()) {
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < c.header.size(); ++i) row[c.header[i]] = std::string(reader.field(i));
    c.rows.push_back(std::move(row));
  }
  return c;
}

const char* kHeader =
    "participant,condition,iteration,error,confusion\n";

}  // namespace

TEST(TableCli, PrintsThePaperShapedTableByDefault) {
  const auto r = run_in_table_dir("table scores_small.csv --condition adaptive");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, read_text(kTableDir + "/expected_one_sample.txt"));
  EXPECT_EQ(r.err, "");
}

TEST(TableCli, WritesLatexAtomicallyToAFile) {
  TempDir dir;
  const auto out = (dir / "table1.tex").string();
  const auto r = run_in_table_dir("table scores_small.csv --condition adaptive --format latex -o " +
                                  shell_quote(out));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(read_text(out), read_text(kTableDir + "/expected_one_sample.tex"));
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_EQ(e.path().filename(), "table1.tex");  // no temporary left behind
  }
}

// scores_small.csv has the same participants in both conditions (a within design, read off the
// data: paired, below); scores_small_between.csv has the same values with the random condition's
// participants renamed P09-P16, each participant in one condition: Welch.
TEST(TableCli, TwoSampleWithHolmAndEquivalence) {
  const auto r = run_in_table_dir(
      "table scores_small_between.csv --compare adaptive,random --p-adjust holm --equivalence 0.1");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, read_text(kTableDir + "/expected_welch_holm_tost.txt"));
}

// The same ids in both conditions and no --design: a within design read off the data, compared
// pair by pair; Student's pooled t does not apply to pairs; a declared between design is refused.
TEST(TableCli, ParticipantsInBothConditionsAreComparedPairByPair) {
  const auto r = run_in_table_dir("table scores_small.csv --compare adaptive,random");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("Paired t-tests of error and confusion per iteration", 0), 0u) << r.out;
  const auto v = run_in_table_dir("table scores_small.csv --compare adaptive,random --var-equal");
  EXPECT_EQ(v.exit_code, 64);
  EXPECT_NE(v.err.find("--var-equal: the conditions are within participants"), std::string::npos) << v.err;
  const auto b = run_in_table_dir("table scores_small.csv --compare adaptive,random --design between");
  EXPECT_EQ(b.exit_code, 65);
  EXPECT_NE(b.err.find("participant 'P01' has trials in condition"), std::string::npos) << b.err;
}

TEST(TableCli, TidyCsvHasTheFixedColumnsAndFullPrecision) {
  TempDir dir;
  const auto out = (dir / "t.csv").string();
  const auto r = run_feint("table " + shell_quote(kSmall) + " --format csv -o " + shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto csv = read_csv(out);
  const std::vector<std::string> expected = {
      "metric", "iteration", "test", "method", "alternative", "mu", "group1", "group2", "n1",
      "n2", "mean1", "mean2", "sd1", "sd2", "estimate", "conf_low", "conf_high", "statistic",
      "df", "p_value", "p_adjusted", "cohen_d", "hedges_g", "cohen_d_low", "cohen_d_high",
      "hedges_g_low", "hedges_g_high", "bf10", "bf01", "label", "note"};
  EXPECT_EQ(csv.header, expected);
  ASSERT_EQ(csv.rows.size(), 20u);  // 2 conditions x 2 metrics x 5 iterations
  // R: t.test(error[adaptive, iteration 2], mu = 0.5)$p.value = 1.5223063212763852e-10.
  bool found = false;
  for (const auto& row : csv.rows) {
    if (row.at("metric") == "error" && row.at("iteration") == "2" && row.at("group1") == "adaptive") {
      const double p = *feint::io::parse_double(row.at("p_value"));
      EXPECT_NEAR(p, 1.5223063212763852e-10, 1e-20);
      EXPECT_EQ(row.at("label"), "M>R");
      EXPECT_EQ(row.at("test"), "one_sample_t");
      EXPECT_EQ(row.at("group2"), "");
      EXPECT_EQ(row.at("n2"), "");
      found = true;
    }
    if (row.at("metric") == "confusion" && row.at("iteration") == "3" &&
        row.at("group1") == "adaptive") {
      EXPECT_EQ(row.at("label"), "not computable");
      EXPECT_EQ(row.at("p_value"), "");
      EXPECT_FALSE(row.at("note").empty());
    }
  }
  EXPECT_TRUE(found);
}

TEST(TableCli, ApaColumnAndJson) {
  const auto r = run_feint("table " + shell_quote(kTableDir + "/scores_small_between.csv") +
                           " --compare adaptive,random --var-equal --apa --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("[\n  {\"metric\": \"error\", \"iteration\": 1, \"test\": \"student_t\"", 0), 0u);
  EXPECT_NE(r.out.find("\"apa\": \"t(14) = "), std::string::npos);
  std::size_t objects = 0;
  for (auto p = r.out.find("{\"metric\""); p != std::string::npos; p = r.out.find("{\"metric\"", p + 1)) {
    ++objects;
  }
  EXPECT_EQ(objects, 10u);
}

TEST(TableCli, PairedAndAlternativeOptions) {
  const auto r = run_feint("table " + shell_quote(kSmall) +
                           " --compare adaptive,random --paired --alternative greater --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(",paired_t,Paired t-test,greater,"), std::string::npos);
}

TEST(TableCli, MetricOptionsTakeOneValueEachAndMayPrecedeTheInput) {
  const auto r = run_feint("table --metric confusion=0.9 --metric error " + shell_quote(kSmall) +
                           " --condition random --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\nconfusion,1,one_sample_t,One Sample t-test,two.sided,0.9,random,"),
            std::string::npos);
  EXPECT_NE(r.out.find("\nerror,1,one_sample_t,One Sample t-test,two.sided,0.5,random,"),
            std::string::npos);
  EXPECT_LT(r.out.find("\nconfusion,1,"), r.out.find("\nerror,1,"));  // in the order given
}

TEST(TableCli, AnyNumericColumnCanBeTabulated) {
  TempDir dir;
  const auto in = dir / "s.csv";
  write_text(in, "participant,iteration,reversals\nP1,1,2\nP2,1,3\nP3,1,5\nP1,2,1\nP2,2,1\nP3,2,2\n");
  const auto r = run_feint("table " + shell_quote(in.string()) + " --metric reversals=2 --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\nreversals,1,one_sample_t,One Sample t-test,two.sided,2,,,3,"),
            std::string::npos);
}

TEST(TableCli, NoteReadsTheScoresSidecar) {
  TempDir dir;
  const auto in = dir / "scores.csv";
  write_text(in, read_text(kSmall));
  write_text(dir / "scores.csv.meta.json",
             "{\"tool\": \"feint score\", \"settings\": {\"confusion_norm\": \"speed\"}, "
             "\"units\": {\"confusion\": \"fraction of full-speed movement, [0, 1]\"}}\n");
  // Speed scores: the reference must be on the speed scale (docs/metrics.md "One scale").
  const auto r = run_feint("table " + shell_quote(in.string()) +
                           " --condition random --format markdown --metric error --metric confusion=0.5@speed");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Confusion normalisation: speed (confusion in fraction of full-speed "
                       "movement, [0, 1]) (from "),
            std::string::npos)
      << r.out;
}

TEST(TableCli, ReadsStandardInput) {
  const std::string data = read_text(kSmall);
  const auto r = run_feint("table - --condition random --format csv", data);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 11);
}

TEST(TableCli, InvalidDataExits65WithAPreciseMessage) {
  TempDir dir;
  const auto in = dir / "s.csv";
  const auto out = dir / "out.csv";
  const std::string q = shell_quote(in.string());

  write_text(in, std::string(kHeader) + "P01,adaptive,1,0.5,0.9\nP01,adaptive,1,0.6,0.9\n");
  auto r = run_feint("table " + q + " -o " + shell_quote(out.string()));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_EQ(r.err, "feint: error: " + in.string() +
                       ":3: duplicate participant/condition/iteration P01/adaptive/1: already on "
                       "line 2 (one value per participant and iteration is expected)\n");
  EXPECT_FALSE(std::filesystem::exists(out));  // no half-written table

  write_text(in, std::string(kHeader) + "P01,adaptive,1,0.5,high\n");
  r = run_feint("table " + q);
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find(in.string() + ":2: column 'confusion': 'high' is not a number (P01/adaptive/1;"),
            std::string::npos)
      << r.err;

  write_text(in, "participant,condition,iteration,error\nP01,adaptive,1,0.5\n");
  r = run_feint("table " + q);
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find(":1: metric column 'confusion' is missing"), std::string::npos) << r.err;

  write_text(in, "participant,condition,error,confusion\nP01,adaptive,0.5,0.5\n");
  r = run_feint("table " + q);
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find(":1: column 'iteration' (iteration) is missing"), std::string::npos) << r.err;

  // A condition the data do not have: the command line is wrong, not the data (64, as in likert
  // and analyze).
  r = run_feint("table " + shell_quote(kSmall) + " --compare adaptive,fixed");
  EXPECT_EQ(r.exit_code, 64);
  EXPECT_NE(r.err.find("--compare: condition 'fixed' does not occur in column 'condition' "
                       "(conditions: adaptive, random)"),
            std::string::npos)
      << r.err;
}

TEST(TableCli, BadOptionsExit64) {
  const std::string in = shell_quote(kSmall);
  for (const std::string args :
       {"--format html", "--alternative sideways", "--alpha 0", "--alpha 1", "--conf-level 95",
        "--p-adjust fdrx", "--compare adaptive", "--compare adaptive,adaptive",
        "--metric error=abc", "--metric reversals", "--metric error --metric error",
        "--equivalence -1", "--paired", "--var-equal", "--no-such-option",
        "--condition adaptive --compare adaptive,random"}) {
    const auto r = run_feint("table " + in + " " + args);
    EXPECT_EQ(r.exit_code, 64) << args << ": " << r.err;
    EXPECT_FALSE(r.err.empty()) << args;
  }
  EXPECT_EQ(run_feint("table").exit_code, 64);  // SCORES is required
}

TEST(TableCli, UnreadableInputExits74) {
  const auto r = run_feint("table /nonexistent/scores.csv");
  EXPECT_EQ(r.exit_code, 74) << r.err;
}

// --bf-prior-scale: the JZS Bayes factors at another Cauchy scale r, against the exact
// integral of the definition (tests/golden/bayes/make_bf_prior_golden.R, rel.tol 1e-12) at r =
// sqrt(2)/2, 1, sqrt(2) and 0.5, for every test of the table; the note names the scale.
TEST(TableCli, BayesFactorPriorScaleIsSettableAndMatchesTheExactIntegral) {
  const std::string dir = std::string(FEINT_SOURCE_DIR) + "/tests/golden/bayes/";
  const Csv golden = read_csv(dir + "bf_prior_golden.csv");
  ASSERT_EQ(golden.rows.size(), 9u);
  TempDir tmp;
  const std::map<std::string, std::string> scales = {
      {"medium", "log_bf_medium"}, {"WIDE", "log_bf_wide"}, {"1", "log_bf_wide"},
      {"ultrawide", "log_bf_ultrawide"}, {"0.5", "log_bf_half"}, {"", "log_bf_medium"}};
  for (const auto& [scale, column] : scales) {
    SCOPED_TRACE(scale);
    for (const std::string mode : {"--compare adaptive,random", ""}) {
      const std::string out = (tmp.path() / "t.csv").string();
      const auto r = run_feint("table " + shell_quote(dir + "prior_scale_scores.csv") + " --metric error=0.5 " +
                               mode + (scale.empty() ? "" : " --bf-prior-scale " + scale) +
                               " --format csv -o " + shell_quote(out));
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const Csv c = read_csv(out);
      int matched = 0;
      for (const auto& g : golden.rows) {
        const bool two = g.at("test") == "two_sample";
        if (two != !mode.empty()) continue;
        for (const auto& row : c.rows) {
          if (row.at("iteration") != g.at("iteration") || row.at("group1") != g.at("group1")) continue;
          if (row.at("test") != (two ? "welch_t" : "one_sample_t")) continue;
          const double exact = std::stod(g.at(column));
          EXPECT_NEAR(std::log(std::stod(row.at("bf10"))), exact, 1e-6 * std::max(1.0, std::abs(exact)))
              << g.at("test") << " " << g.at("group1") << " " << g.at("iteration");
          ++matched;
        }
      }
      EXPECT_EQ(matched, mode.empty() ? 6 : 3);
    }
  }
  // The note says which prior was used.
  const auto wide = run_feint("table " + shell_quote(dir + "prior_scale_scores.csv") +
                              " --metric error=0.5 --compare adaptive,random --bf-prior-scale wide");
  EXPECT_NE(wide.out.find("scale r = 1 (wide)"), std::string::npos) << wide.out;
  const auto medium = run_feint("table " + shell_quote(dir + "prior_scale_scores.csv") + " --metric error=0.5");
  EXPECT_NE(medium.out.find("scale r = 0.7071 (medium)"), std::string::npos) << medium.out;
  // Rejected: zero, negative, text, infinite, NaN; each named.
  for (const std::string bad : {"0", "-1", "abc", "inf", "nan", "1e400", "''"}) {
    const auto r = run_feint("table " + shell_quote(kSmall) + " --bf-prior-scale " + bad);
    EXPECT_EQ(r.exit_code, 64) << bad << ": " << r.err;
    EXPECT_NE(r.err.find("--bf-prior-scale"), std::string::npos) << bad << ": " << r.err;
    EXPECT_NE(r.err.find("medium"), std::string::npos) << r.err;
  }
}

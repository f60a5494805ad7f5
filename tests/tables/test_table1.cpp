// Table 1 (statistics.md): every test against R (tests/data/table/golden_table1.csv, made by
// make_golden.R beside it), labels, p-adjust families, TOST, and the paper-shaped renderings
// compared to committed expected files.
#include "feint/tables/table1.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>

#include "feint/error.hpp"
#include "feint/io/scores.hpp"

using namespace feint;
using namespace feint::tables;

namespace {

const std::string kDir = std::string(FEINT_TEST_DATA_DIR) + "/table/";

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Golden {
  double statistic, df, p, low, high, estimate;
  std::optional<double> p_holm;
};

// (mode, metric, iteration, group1) -> R's values.
using GoldenMap = std::map<std::tuple<std::string, std::string, int, std::string>, Golden>;

GoldenMap load_golden() {
  std::ifstream in(kDir + "golden_table1.csv");
  std::string line;
  std::getline(in, line);  // header
  GoldenMap g;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    if (line.back() == ',') f.emplace_back();
    if (f.size() != 12) continue;
    Golden v{std::stod(f[5]), std::stod(f[6]), std::stod(f[7]), std::stod(f[8]), std::stod(f[9]),
             std::stod(f[10]), std::nullopt};
    if (!f[11].empty()) v.p_holm = std::stod(f[11]);
    g[{f[0], f[1], std::stoi(f[2]), f[3]}] = v;
  }
  return g;
}

io::ScoresTable small_scores() {
  auto s = io::load_scores(kDir + "scores_small.csv");
  s.path = "scores_small.csv";  // as a user would type it: the note names the source
  return s;
}

void expect_close(double actual, double expected, const std::string& what) {
  EXPECT_NEAR(actual, expected, 1e-10 * std::max(1.0, std::fabs(expected))) << what;
}

// Compares every difference-test row of `t` with R's values for `mode`; returns rows compared.
int compare_with_r(const Table1& t, const std::string& mode, bool holm = false) {
  const auto golden = load_golden();
  int compared = 0;
  for (const auto& row : t.rows) {
    if (row.result.test == "tost") continue;
    const auto key = std::make_tuple(mode, row.metric, *row.iteration, row.group1);
    const auto it = golden.find(key);
    const std::string what = mode + "/" + row.metric + "/" + std::to_string(*row.iteration) + "/" +
                             row.group1;
    if (it == golden.end()) {
      EXPECT_FALSE(row.result.computed) << what << ": R could not compute it either";
      continue;
    }
    const Golden& g = it->second;
    EXPECT_TRUE(row.result.computed) << what;
    if (!row.result.computed) continue;
    expect_close(*row.result.statistic, g.statistic, what + " statistic");
    expect_close(*row.result.df, g.df, what + " df");
    expect_close(*row.result.p_value, g.p, what + " p");
    expect_close(*row.result.conf_low, g.low, what + " conf_low");
    expect_close(*row.result.conf_high, g.high, what + " conf_high");
    if (mode != "welch" && mode != "student") {
      expect_close(*row.result.estimate, g.estimate, what + " estimate");
    }
    if (holm) {
      EXPECT_TRUE(g.p_holm.has_value() && row.result.p_adjusted.has_value()) << what;
      if (g.p_holm && row.result.p_adjusted) {
        expect_close(*row.result.p_adjusted, *g.p_holm, what + " holm");
      }
    }
    ++compared;
  }
  return compared;
}

void expect_matches_file(const std::string& actual, const std::string& name) {
  const std::string path = kDir + name;
  if (std::getenv("FEINT_UPDATE_EXPECTED") != nullptr) {
    std::ofstream(path, std::ios::binary) << actual;
  }
  EXPECT_EQ(actual, slurp(path)) << "regenerate with FEINT_UPDATE_EXPECTED=1 after checking: " << path;
}

}  // namespace

TEST(Table1OneSample, EveryTestMatchesR) {
  const auto t = build_table1(small_scores(), {});
  ASSERT_EQ(t.blocks.size(), 2u);  // adaptive, random
  EXPECT_EQ(t.rows.size(), 2u * 2u * 5u);
  EXPECT_EQ(compare_with_r(t, "one_sample"), 19);  // adaptive confusion at iteration 3 is constant
}

TEST(Table1OneSample, ConstantDataIsNotComputableAndSaysWhy) {
  Table1Options o;
  o.condition = "adaptive";
  const auto t = build_table1(small_scores(), o);
  const auto& cell = t.blocks.at(0).cells.at(2).at(1);  // iteration 3, confusion
  const auto& row = t.rows.at(cell.difference_row);
  EXPECT_FALSE(row.result.computed);
  EXPECT_FALSE(row.result.note.empty());
  EXPECT_EQ(row.label, "not computable");
  const auto note = table1_note(t);
  bool found = false;
  for (const auto& n : note) found = found || n.find("Not computable: confusion, iteration 3") == 0;
  EXPECT_TRUE(found);
}

TEST(Table1OneSample, LabelsFollowPAndTheSignOfMMinusR) {
  const auto t = build_table1(small_scores(), {});
  for (const auto& row : t.rows) {
    if (!row.result.computed) continue;
    const double p = *row.result.p_value;
    const double diff = *row.result.estimate - *row.result.mu;
    const std::string expected = p < 0.05 ? (diff > 0 ? "M>R" : "M<R") : "M\u2248R";
    EXPECT_EQ(row.label, expected) << row.metric << " " << *row.iteration << " " << row.group1;
  }
  // Adaptive error at iteration 2 is far above 0.5 (R: p = 1.5e-10).
  EXPECT_EQ(t.rows.at(t.blocks[0].cells[1][0].difference_row).label, "M>R");
}

TEST(Table1OneSample, ReferenceMeansAreSettable) {
  Table1Options o;
  o.condition = "random";
  o.metrics = {{"error", 0.7}};
  const auto t = build_table1(small_scores(), o);
  ASSERT_EQ(t.rows.size(), 5u);
  for (const auto& r : t.rows) EXPECT_EQ(*r.result.mu, 0.7);
}

TEST(Table1TwoSample, WelchStudentAndPairedMatchR) {
  Table1Options o;
  o.compare = std::make_pair(std::string("adaptive"), std::string("random"));
  EXPECT_EQ(compare_with_r(build_table1(small_scores(), o), "welch"), 10);
  o.var_equal = true;
  EXPECT_EQ(compare_with_r(build_table1(small_scores(), o), "student"), 10);
  o.var_equal = false;
  o.paired = true;
  const auto paired = build_table1(small_scores(), o);
  EXPECT_EQ(compare_with_r(paired, "paired"), 10);
  // P03 has no error value in random at iteration 4: unpaired there, and said so.
  bool warned = false;
  for (const auto& w : paired.warnings) warned = warned || w.find("iteration 4: P03") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(Table1TwoSample, HolmWithinEachMetricColumnMatchesPAdjust) {
  Table1Options o;
  o.compare = std::make_pair(std::string("adaptive"), std::string("random"));
  o.p_adjust = stats::PAdjustMethod::holm;
  const auto t = build_table1(small_scores(), o);
  EXPECT_EQ(compare_with_r(t, "welch", true), 10);
  for (const auto& row : t.rows) {
    const double p = *row.result.p_adjusted;  // labels use the adjusted p
    const std::string expected =
        p < 0.05 ? (*row.result.estimate > 0 ? "A>B" : "A<B") : "A\u2248B";
    EXPECT_EQ(row.label, expected);
  }
}

TEST(Table1TwoSample, MissingValuesAreExcludedAndCounted) {
  Table1Options o;
  o.compare = std::make_pair(std::string("adaptive"), std::string("random"));
  const auto t = build_table1(small_scores(), o);
  const auto& row = t.rows.at(t.blocks[0].cells[3][0].difference_row);  // error, iteration 4
  EXPECT_EQ(row.result.n1, 8u);
  EXPECT_EQ(row.result.n2, 7u);
  ASSERT_EQ(t.warnings.size(), 1u);
  EXPECT_EQ(t.warnings[0], "error (adaptive, random): 1 empty cell excluded as missing.");
}

TEST(Table1Equivalence, TostEarnsApproxOtherwiseInconclusive) {
  Table1Options o;
  o.condition = "adaptive";
  o.metrics = {{"error", 0.5}};
  o.equivalence = 0.2;  // wide: every non-different iteration is shown equivalent
  auto t = build_table1(small_scores(), o);
  ASSERT_EQ(t.rows.size(), 10u);  // a difference row and a TOST row per iteration
  int approx = 0;
  for (const auto& cell : t.blocks[0].cells) {
    const auto& d = t.rows[cell[0].difference_row];
    const auto& e = t.rows[*cell[0].tost_row];
    EXPECT_EQ(e.result.test, "tost");
    EXPECT_EQ(d.label, e.label);
    if (*d.result.p_value >= 0.05) {
      EXPECT_LT(*e.result.p_value, 0.05);
      EXPECT_EQ(d.label, "M\u2248R");
      ++approx;
    }
  }
  EXPECT_EQ(approx, 4);
  o.equivalence = 0.001;  // narrow: nothing can be shown equivalent with n = 8
  t = build_table1(small_scores(), o);
  for (const auto& cell : t.blocks[0].cells) {
    const auto& d = t.rows[cell[0].difference_row];
    EXPECT_EQ(d.label, *d.result.p_value < 0.05 ? "M>R" : "inconclusive");
  }
}

TEST(Table1Errors, UnknownConditionAndImpossibleOptions) {
  const auto s = small_scores();
  Table1Options o;
  o.compare = std::make_pair(std::string("adaptive"), std::string("fixed"));
  try {
    build_table1(s, o);
    ADD_FAILURE() << "expected UsageError";
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(),
                 "scores_small.csv: --compare: condition 'fixed' does not occur in column "
                 "'condition' (conditions: adaptive, random)");
  }
  o.compare = std::make_pair(std::string("random"), std::string("random"));
  EXPECT_THROW(build_table1(s, o), UsageError);
  o = {};
  o.condition = "nope";
  EXPECT_THROW(build_table1(s, o), UsageError);
  o = {};
  o.alpha = 1.5;
  EXPECT_THROW(build_table1(s, o), UsageError);
  o = {};
  o.paired = true;  // without --compare
  EXPECT_THROW(build_table1(s, o), UsageError);
  o = {};
  o.equivalence = -0.1;
  EXPECT_THROW(build_table1(s, o), UsageError);
}

TEST(Table1Metric, ParsesNameEqualsReference) {
  EXPECT_EQ(parse_metric_spec("error=0.5").reference, 0.5);
  EXPECT_EQ(parse_metric_spec("reversal_time=1.25").column, "reversal_time");
  EXPECT_EQ(parse_metric_spec("confusion").reference, 0.95);
  EXPECT_THROW(parse_metric_spec("reversals"), UsageError);
  EXPECT_THROW(parse_metric_spec("error=abc"), UsageError);
  EXPECT_THROW(parse_metric_spec("=1"), UsageError);
}

TEST(Table1Render, TidyCsvHasOneRowPerTestAndTheFixedColumns) {
  Table1Options o;
  o.condition = "adaptive";
  const auto t = build_table1(small_scores(), o);
  const std::string csv = render_table1(t, OutputFormat::csv);
  std::size_t lines = 0, commas_first = 0;
  for (std::size_t i = 0; i < csv.size(); ++i) {
    if (csv[i] == '\n') ++lines;
    if (lines == 0 && csv[i] == ',') ++commas_first;
  }
  EXPECT_EQ(lines, 1u + 10u);
  EXPECT_EQ(commas_first, 30u);
  EXPECT_NE(csv.find("confusion,3,one_sample_t,One Sample t-test,two.sided,0.95,adaptive,,8,"),
            std::string::npos);
  const std::string json = render_table1(t, OutputFormat::json);
  EXPECT_EQ(json.front(), '[');
  EXPECT_NE(json.find("\"label\": \"not computable\""), std::string::npos);
}

TEST(Table1Render, PaperShapedTextAndLatexMatchTheExpectedFiles) {
  Table1Options o;
  o.condition = "adaptive";
  const auto t = build_table1(small_scores(), o);
  expect_matches_file(render_table1(t, OutputFormat::text), "expected_one_sample.txt");
  expect_matches_file(render_table1(t, OutputFormat::latex), "expected_one_sample.tex");
  expect_matches_file(render_table1(t, OutputFormat::markdown), "expected_one_sample.md");
}

TEST(Table1Render, TwoSampleWithHolmAndTostMatchesTheExpectedFiles) {
  Table1Options o;
  o.compare = std::make_pair(std::string("adaptive"), std::string("random"));
  o.p_adjust = stats::PAdjustMethod::holm;
  o.equivalence = 0.1;
  const auto t = build_table1(small_scores(), o);
  expect_matches_file(render_table1(t, OutputFormat::text), "expected_welch_holm_tost.txt");
  expect_matches_file(render_table1(t, OutputFormat::latex), "expected_welch_holm_tost.tex");
}

TEST(Table1Render, LatexIsBooktabsAndBalanced) {
  const auto t = build_table1(small_scores(), {});  // two condition blocks
  const std::string s = render_table1(t, OutputFormat::latex);
  EXPECT_NE(s.find("\\begin{tabular}{rrrlrrl}"), std::string::npos);
  EXPECT_NE(s.find("\\multicolumn{7}{l}{\\textit{Condition: random}}"), std::string::npos);
  EXPECT_NE(s.find("\\addlinespace"), std::string::npos);
  EXPECT_NE(s.find("$1.5 \\times 10^{-10}$"), std::string::npos);  // adaptive error, iteration 2
  int braces = 0;
  for (char c : s) braces += c == '{' ? 1 : c == '}' ? -1 : 0;
  EXPECT_EQ(braces, 0);
  std::size_t begins = 0, ends = 0;
  for (auto p = s.find("\\begin{"); p != std::string::npos; p = s.find("\\begin{", p + 1)) ++begins;
  for (auto p = s.find("\\end{"); p != std::string::npos; p = s.find("\\end{", p + 1)) ++ends;
  EXPECT_EQ(begins, ends);
  EXPECT_EQ(s.find("\\hline"), std::string::npos);
}

TEST(Table1Render, ApaStringsAreListedUnderTheTableForPeople) {
  Table1Options o;
  o.compare = std::make_pair(std::string("adaptive"), std::string("random"));
  o.apa = true;
  const auto t = build_table1(small_scores(), o);
  for (const auto& r : t.rows) EXPECT_EQ(r.apa, apa_string(r.result));
  const std::string text = render_table1(t, OutputFormat::text);
  EXPECT_NE(text.find("\nAPA-style results:\n"), std::string::npos);
  EXPECT_NE(text.find("\nerror, iteration 2 (adaptive vs random): t("), std::string::npos) << text;
  EXPECT_NE(render_table1(t, OutputFormat::csv).find(",apa\n"), std::string::npos);
}

// The paper's own Table 1 numbers (M and p per iteration, one-sample, 30 participants) rendered
// through the writers: the cells read as the paper prints them (4-decimal means and p, 1.5e-04 for
// 1.5*10^-4). Labels follow statistics.md; the paper's iteration 1 and 3 confusion labels ("M>R"
// for M < R) disagree with its own numbers, and feint does not copy that.
TEST(Table1Render, ThePapersNumbersReadAsInThePaper) {
  const double error_m[] = {0.5703, 0.5403, 0.5112, 0.5295};
  const double error_p[] = {0.0066, 0.0992, 0.7479, 0.4494};
  const double conf_m[] = {0.8504, 0.8726, 0.7239, 0.5426};
  const double conf_p[] = {0.2109, 0.5241, 0.0201, 1.5e-4};
  Table1 t;
  t.source = "paper";
  t.options.condition = "adaptive";
  Table1Block blk;
  blk.group1 = "adaptive";
  for (int i = 0; i < 4; ++i) {
    blk.iterations.push_back(i + 1);
    std::vector<Table1Cell> cells;
    for (int m = 0; m < 2; ++m) {
      TidyRow row;
      row.metric = m == 0 ? "error" : "confusion";
      row.iteration = i + 1;
      row.group1 = "adaptive";
      row.result.test = "one_sample_t";
      row.result.mu = m == 0 ? 0.5 : 0.95;
      row.result.n1 = 30;
      row.result.mean1 = row.result.estimate = m == 0 ? error_m[i] : conf_m[i];
      row.result.p_value = m == 0 ? error_p[i] : conf_p[i];
      row.label = one_sample_label(row.result, 0.05);
      cells.push_back({t.rows.size(), std::nullopt});
      t.rows.push_back(row);
    }
    blk.cells.push_back(cells);
  }
  t.blocks.push_back(blk);
  const std::string text = render_table1(t, OutputFormat::text);
  EXPECT_NE(text.find("        1    0.5703  0.0066  M>R          0.8504   0.2109  M\u2248R\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("        3    0.5112  0.7479  M\u2248R          0.7239   0.0201  M<R\n"),
            std::string::npos);
  EXPECT_NE(text.find("        4    0.5295  0.4494  M\u2248R          0.5426  1.5e-04  M<R\n"),
            std::string::npos);
  EXPECT_NE(render_table1(t, OutputFormat::latex).find("$1.5 \\times 10^{-4}$ & $M < R$"),
            std::string::npos);
}

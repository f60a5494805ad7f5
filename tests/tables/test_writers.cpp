// Writers shared by every report: number/p formatting, APA strings, labels, tidy CSV/JSON, tables.
#include "feint/tables/writers.hpp"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <limits>

#include "feint/error.hpp"

using namespace feint;
using namespace feint::tables;
using feint::stats::TestResult;

namespace {

// t.test(x, mu = 0.5) for x = c(0.61, 0.55, ...) style result, built by hand (values from R:
// t = 2.93, df = 29, p = 0.006574, d = 0.535).
TestResult one_sample(double p = 0.006574) {
  TestResult r;
  r.test = "one_sample_t";
  r.method = "One Sample t-test";
  r.mu = 0.5;
  r.n1 = 30;
  r.mean1 = 0.5703;
  r.sd1 = 0.1314;
  r.estimate = 0.5703;
  r.statistic = 2.9306;
  r.statistic_name = "t";
  r.df = 29;
  r.p_value = p;
  r.conf_low = 0.5212;
  r.conf_high = 0.6194;
  r.cohen_d = 0.5349;
  r.hedges_g = 0.521;
  return r;
}

TestResult welch(double estimate, double p) {
  TestResult r;
  r.test = "welch_t";
  r.method = "Welch Two Sample t-test";
  r.mu = 0;
  r.n1 = 30;
  r.n2 = 30;
  r.mean1 = 0.55;
  r.mean2 = 0.55 - estimate;
  r.estimate = estimate;
  r.statistic = estimate > 0 ? 2.5 : -2.5;
  r.statistic_name = "t";
  r.df = 57.4321;
  r.p_value = p;
  r.cohen_d = estimate > 0 ? 0.64 : -0.64;
  return r;
}

}  // namespace

TEST(OutputFormat, ParsesEveryNameCaseInsensitively) {
  EXPECT_EQ(parse_output_format("text"), OutputFormat::text);
  EXPECT_EQ(parse_output_format("Markdown"), OutputFormat::markdown);
  EXPECT_EQ(parse_output_format("md"), OutputFormat::markdown);
  EXPECT_EQ(parse_output_format("LATEX"), OutputFormat::latex);
  EXPECT_EQ(parse_output_format("csv"), OutputFormat::csv);
  EXPECT_EQ(parse_output_format("json"), OutputFormat::json);
  EXPECT_THROW(parse_output_format("html"), UsageError);
  EXPECT_EQ(to_string(OutputFormat::latex), "latex");
}

TEST(FormatMean, FourDecimalsAsThePaper) {
  EXPECT_EQ(format_mean(0.57034), "0.5703");
  EXPECT_EQ(format_mean(0.85044), "0.8504");
  EXPECT_EQ(format_mean(0.5), "0.5000");
  EXPECT_EQ(format_mean(-0.00001), "0.0000");  // no "-0.0000"
  EXPECT_EQ(format_mean(-0.12345), "-0.1235");
  EXPECT_EQ(format_mean(std::nullopt), "");
}

TEST(FormatP, FourDecimalsThenScientificBelowOneThousandth) {
  EXPECT_EQ(format_p(0.0066), "0.0066");
  EXPECT_EQ(format_p(0.2109), "0.2109");
  EXPECT_EQ(format_p(1.0), "1.0000");
  EXPECT_EQ(format_p(0.001), "0.0010");
  EXPECT_EQ(format_p(1.5e-4), "1.5e-04");     // the paper's 1.5*10^-4
  EXPECT_EQ(format_p(0.000999), "1.0e-03");
  EXPECT_EQ(format_p(4.3e-30), "4.3e-30");
  EXPECT_EQ(format_p(std::nullopt), "");
}

TEST(FormatP, BelowTheSmallestDoubleIsNeverZero) {
  EXPECT_EQ(format_p(0.0), "< 2.2e-308");
  EXPECT_EQ(format_p(std::numeric_limits<double>::denorm_min()), "< 2.2e-308");
  EXPECT_EQ(format_p(DBL_MIN / 4), "< 2.2e-308");
  EXPECT_EQ(format_p(1e-300), "1.0e-300");
  EXPECT_EQ(format_p(0.0, PStyle::latex), "$< 2.2 \\times 10^{-308}$");
}

TEST(FormatP, LatexUsesTimesTenToThe) {
  EXPECT_EQ(format_p(1.5e-4, PStyle::latex), "$1.5 \\times 10^{-4}$");
  EXPECT_EQ(format_p(6.44e-22, PStyle::latex), "$6.4 \\times 10^{-22}$");
  EXPECT_EQ(format_p(0.0201, PStyle::latex), "0.0201");
}

TEST(FormatFull, RoundTripsAndSpellsInfinityAsR) {
  EXPECT_EQ(format_full(0.1), "0.1");
  EXPECT_EQ(format_full(1e-300), "1e-300");
  EXPECT_EQ(format_full(std::numeric_limits<double>::infinity()), "Inf");
  EXPECT_EQ(format_full(-std::numeric_limits<double>::infinity()), "-Inf");
  EXPECT_EQ(format_full(std::nullopt), "");
}

TEST(ApaP, NoLeadingZeroThreeDecimals) {
  EXPECT_EQ(apa_p(0.006574), "p = .007");
  EXPECT_EQ(apa_p(0.0412), "p = .041");
  EXPECT_EQ(apa_p(0.00099), "p < .001");
  EXPECT_EQ(apa_p(0.0), "p < .001");
  EXPECT_EQ(apa_p(0.9996), "p > .999");
  EXPECT_EQ(apa_p(0.5), "p = .500");
}

TEST(ApaString, OneSampleAndStudentTUseWholeDf) {
  EXPECT_EQ(apa_string(one_sample()), "t(29) = 2.93, p = .007, d = 0.53");
  auto tiny = one_sample(1e-5);
  EXPECT_EQ(apa_string(tiny), "t(29) = 2.93, p < .001, d = 0.53");
  auto student = welch(0.1, 0.02);
  student.test = "student_t";
  student.df = 58;
  EXPECT_EQ(apa_string(student), "t(58) = 2.50, p = .020, d = 0.64");
}

// A paired t test's standardised difference is d_z (mean difference / sd of the differences), and
// the APA string names it so, as the findings and the Results text do.
TEST(ApaString, APairedTestNamesItsEffectSizeDz) {
  auto paired = one_sample();
  paired.test = "paired_t";
  EXPECT_EQ(apa_string(paired), "t(29) = 2.93, p = .007, d_z = 0.53");
  EXPECT_EQ(apa_string(one_sample()), "t(29) = 2.93, p = .007, d = 0.53");
}

TEST(ApaString, WelchDfHasTwoDecimals) {
  EXPECT_EQ(apa_string(welch(-0.1, 0.0151)), "t(57.43) = -2.50, p = .015, d = -0.64");
}

TEST(ApaString, AddsTheAdjustedP) {
  auto r = one_sample();
  r.p_adjusted = 0.0521;
  EXPECT_EQ(apa_string(r), "t(29) = 2.93, p = .007, adjusted p = .052, d = 0.53");
}

TEST(ApaString, RankTestsUseVOrWAndRankBiserial) {
  TestResult v;
  v.test = "wilcoxon_signed_rank";
  v.statistic = 120;
  v.statistic_name = "V";
  v.p_value = 0.003;
  v.rank_biserial = 0.62;
  EXPECT_EQ(apa_string(v), "V = 120, p = .003, r = .62");
  TestResult w;
  w.test = "mann_whitney";
  w.statistic = 310.5;
  w.statistic_name = "W";
  w.p_value = 0.0412;
  w.rank_biserial = -0.271;
  EXPECT_EQ(apa_string(w), "W = 310.5, p = .041, r = -.27");
}

TEST(ApaString, FTestsAndKruskalWallis) {
  TestResult f;
  f.test = "anova";
  f.statistic_name = "F";
  f.statistic = 3.4127;
  f.df = 2;
  f.df2 = 57;
  f.p_value = 0.0398;
  EXPECT_EQ(apa_string(f), "F(2, 57) = 3.41, p = .040");
  f.r_squared = 0.107;
  EXPECT_EQ(apa_string(f), "F(2, 57) = 3.41, p = .040, \u03b7\u00b2 = .11");
  f.r_squared.reset();
  f.test = "welch_anova";
  f.df2 = 35.123;
  EXPECT_EQ(apa_string(f), "F(2, 35.12) = 3.41, p = .040");
  TestResult k;
  k.test = "kruskal_wallis";
  k.statistic_name = "Kruskal-Wallis chi-squared";
  k.statistic = 5.2104;
  k.df = 2;
  k.p_value = 0.0739;
  EXPECT_EQ(apa_string(k), "\u03c7\u00b2(2) = 5.21, p = .074");
}

TEST(ApaString, TostAndNotComputable) {
  auto t = one_sample(0.0221);
  t.test = "tost";
  t.statistic = 2.1;
  EXPECT_EQ(apa_string(t), "TOST: t(29) = 2.10, p = .022");
  const auto nc = TestResult::not_computable("one_sample_t", "One Sample t-test",
                                             "fewer than 2 observations");
  EXPECT_EQ(apa_string(nc), "not computable: fewer than 2 observations");
}

TEST(Labels, OneSampleBySignWhenSignificant) {
  EXPECT_EQ(one_sample_label(one_sample(0.0066), 0.05), "M>R");
  auto below = one_sample(0.00015);
  below.estimate = 0.5426;
  below.mu = 0.95;
  EXPECT_EQ(one_sample_label(below, 0.05), "M<R");
  EXPECT_EQ(one_sample_label(one_sample(0.0992), 0.05), "n.s.");
  EXPECT_EQ(one_sample_label(one_sample(0.0499), 0.01), "n.s.");  // alpha matters
}

TEST(Labels, UseTheAdjustedPWhenPresent) {
  auto r = one_sample(0.0066);
  r.p_adjusted = 0.132;
  EXPECT_EQ(one_sample_label(r, 0.05), "n.s.");
}

TEST(Labels, TwoSampleAandB) {
  EXPECT_EQ(two_sample_label(welch(0.1, 0.01), 0.05), "A>B");
  EXPECT_EQ(two_sample_label(welch(-0.1, 0.01), 0.05), "A<B");
  EXPECT_EQ(two_sample_label(welch(0.01, 0.6), 0.05), "n.s.");
}

TEST(Labels, EquivalenceIsEarnedByTost) {
  auto tost = one_sample(0.01);
  tost.test = "tost";
  EXPECT_EQ(one_sample_label(one_sample(0.4), 0.05, &tost), "M\u2248R");
  tost.p_value = 0.2;
  EXPECT_EQ(one_sample_label(one_sample(0.4), 0.05, &tost), "n.s.");
  // A significant difference wins regardless of TOST.
  EXPECT_EQ(one_sample_label(one_sample(0.001), 0.05, &tost), "M>R");
  const auto nc = TestResult::not_computable("tost", "TOST", "n < 2");
  EXPECT_EQ(one_sample_label(one_sample(0.4), 0.05, &nc), "not computable");
}

TEST(Labels, ApproxOnlyFromBf01AtLeast3) {
  auto r = one_sample(0.4);
  r.log_bf10 = -std::log(4.0);  // BF01 = 4: moderate evidence for no difference
  EXPECT_EQ(one_sample_label(r, 0.05), "M\u2248R");
  r.log_bf10 = -std::log(2.9);  // BF01 = 2.9: not enough
  EXPECT_EQ(one_sample_label(r, 0.05), "n.s.");
  r.log_bf10 = std::log(5.0);   // BF10 = 5 but p >= alpha: still not a difference
  EXPECT_EQ(two_sample_label(r, 0.05), "n.s.");
  auto sig = one_sample(0.001);
  sig.log_bf10 = -std::log(4.0);  // significant wins: the label is the test's
  EXPECT_EQ(one_sample_label(sig, 0.05), "M>R");
}

TEST(Labels, NotComputable) {
  const auto nc = TestResult::not_computable("one_sample_t", "One Sample t-test", "n < 2");
  EXPECT_EQ(one_sample_label(nc, 0.05), "not computable");
}

TEST(TidyCsv, HeaderIsExactlyTheTableColumns) {
  const auto cols = table_columns();
  const std::string csv = tidy_csv({}, cols);
  EXPECT_EQ(csv,
            "metric,iteration,test,method,alternative,mu,group1,group2,n1,n2,mean1,mean2,sd1,sd2,"
            "estimate,conf_low,conf_high,statistic,df,p_value,p_adjusted,cohen_d,hedges_g,"
            "cohen_d_low,cohen_d_high,hedges_g_low,hedges_g_high,bf10,bf01,label,note\n");
  EXPECT_EQ(table_columns(true).back(), "apa");
  EXPECT_EQ(likert_columns().size(), kTableColumns.size() + kLikertExtraColumns.size());
}

TEST(TidyCsv, OneRowPerTestFullPrecisionEmptyWhereNotApplicable) {
  std::vector<TidyRow> rows(2);
  rows[0].metric = "error";
  rows[0].iteration = 1;
  rows[0].group1 = "adaptive";
  rows[0].result = one_sample(1.2345678901234567e-200);
  rows[0].label = "M>R";
  rows[1].metric = "confusion";
  rows[1].iteration = 2;
  rows[1].group1 = "adaptive";
  rows[1].result = TestResult::not_computable("one_sample_t", "One Sample t-test",
                                              "fewer than 2 observations, \"n = 1\"");
  rows[1].result.n1 = 1;
  rows[1].label = "not computable";
  const std::string csv = tidy_csv(rows, table_columns());
  const auto l1 = csv.substr(csv.find('\n') + 1);
  EXPECT_EQ(l1.substr(0, l1.find('\n')),
            "error,1,one_sample_t,One Sample t-test,two.sided,0.5,adaptive,,30,,0.5703,,0.1314,,"
            "0.5703,0.5212,0.6194,2.9306,29,1.2345678901234567e-200,,0.5349,0.521,,,,,,,M>R,");
  const auto l2 = l1.substr(l1.find('\n') + 1);
  EXPECT_EQ(l2,
            "confusion,2,one_sample_t,One Sample t-test,two.sided,,adaptive,,1,,,,,,,,,,,,,,,,,,,,,"
            "not computable,\"fewer than 2 observations, \"\"n = 1\"\"\"\n");
}

TEST(TidyJson, NullsNumbersAndEscapes) {
  std::vector<TidyRow> rows(1);
  rows[0].metric = "err\"or";
  rows[0].iteration = 3;
  rows[0].group1 = "a";
  rows[0].group2 = "b";
  rows[0].result = welch(0.1, 0.0);
  rows[0].result.conf_high = std::numeric_limits<double>::infinity();
  rows[0].label = "A>B";
  const std::vector<std::string_view> cols = {"metric", "iteration", "n2",    "p_value",
                                              "p_adjusted", "conf_high", "label"};
  EXPECT_EQ(tidy_json(rows, cols),
            "[\n  {\"metric\": \"err\\\"or\", \"iteration\": 3, \"n2\": 30, \"p_value\": 0, "
            "\"p_adjusted\": null, \"conf_high\": \"Inf\", \"label\": \"A>B\"}\n]\n");
  EXPECT_EQ(tidy_json({}, cols), "[]\n");
}

TEST(TidyCell, LikertColumnsAndUnknownColumn) {
  TidyRow row;
  row.result.exact = true;
  row.result.rank_biserial = 0.25;
  row.cronbach_alpha = 0.81;
  EXPECT_EQ(tidy_cell(row, "exact").text, "true");
  EXPECT_EQ(tidy_cell(row, "rank_biserial").text, "0.25");
  EXPECT_EQ(tidy_cell(row, "cronbach_alpha").text, "0.81");
  EXPECT_EQ(tidy_cell(row, "median1").kind, Cell::Kind::empty);
  EXPECT_THROW(tidy_cell(row, "no_such_column"), std::invalid_argument);
}

TEST(LatexEscape, SpecialCharactersAndApprox) {
  EXPECT_EQ(latex_escape("a_b & 50% #1 {x} $"), "a\\_b \\& 50\\% \\#1 \\{x\\} \\$");
  EXPECT_EQ(latex_escape("M\u2248R"), "M\\ensuremath{\\approx}R");
  EXPECT_EQ(latex_escape("BF\u2081\u2080 = 3.20, BF\u2080\u2081 = 4.00"), "BF\\textsubscript{10} = 3.20, BF\\textsubscript{01} = 4.00");
  EXPECT_EQ(latex_escape("a<b"), "a\\textless{}b");
  EXPECT_EQ(latex_escape("method = \"holm\", \"p adj.\""), "method = ``holm'', ``p adj.''");
  EXPECT_EQ(latex_escape("\u03b7\u00b2"), "\\ensuremath{\\eta}\\textsuperscript{2}");
  EXPECT_EQ(latex_escape("~^\\"), "\\textasciitilde{}\\textasciicircum{}\\textbackslash{}");
}

TEST(DisplayWidth, CountsCodePoints) {
  EXPECT_EQ(display_width("M\u2248R"), 3u);
  EXPECT_EQ(display_width("abc"), 3u);
}

namespace {
TextTable small_table() {
  TextTable t;
  t.caption = "Caption";
  t.groups = {{"Error (R = 0.5)", 1, 2}};
  t.header = {"Iteration", "M", "Inference"};
  t.right_align = {true, true, false};
  t.rows = {{{"1", "0.5703", "M>R"}, false}, {{"10", "0.4991", "M\u2248R"}, false}};
  t.notes = {"A note with 50% & more."};
  return t;
}
}  // namespace

TEST(RenderTable, TextAlignsColumnsAndGroups) {
  const std::string s = render_table(small_table(), OutputFormat::text);
  EXPECT_EQ(s,
            "Caption\n\n"
            "           Error (R = 0.5)\n"
            "           -----------------\n"
            "Iteration       M  Inference\n"
            "----------------------------\n"
            "        1  0.5703  M>R\n"
            "       10  0.4991  M\u2248R\n"
            "----------------------------\n"
            "\nA note with 50% & more.\n");
}

TEST(RenderTable, MarkdownHasGroupRowThenBoldHeader) {
  const std::string s = render_table(small_table(), OutputFormat::markdown);
  EXPECT_EQ(s,
            "**Caption**\n\n"
            "|  | **Error (R = 0.5)** |  |\n"
            "|---:|---:|---|\n"
            "| **Iteration** | **M** | **Inference** |\n"
            "| 1 | 0.5703 | M>R |\n"
            "| 10 | 0.4991 | M\u2248R |\n"
            "\n*Note.* A note with 50% & more.\n");
}

TEST(RenderTable, LatexIsABooktabsFragment) {
  auto t = small_table();
  t.latex_cells = {{"", "", "$M > R$"}, {}};
  const std::string s = render_table(t, OutputFormat::latex);
  EXPECT_NE(s.find("\\begin{tabular}{rrl}"), std::string::npos);
  EXPECT_NE(s.find("\\toprule"), std::string::npos);
  EXPECT_NE(s.find("& \\multicolumn{2}{c}{Error (R = 0.5)}"), std::string::npos);
  EXPECT_NE(s.find("\\cmidrule(lr){2-3}"), std::string::npos);
  EXPECT_NE(s.find("1 & 0.5703 & $M > R$ \\\\"), std::string::npos);
  EXPECT_NE(s.find("10 & 0.4991 & M\\ensuremath{\\approx}R \\\\"), std::string::npos);
  EXPECT_NE(s.find("50\\% \\& more"), std::string::npos);
  EXPECT_LT(s.find("\\midrule"), s.find("\\bottomrule"));
  EXPECT_EQ(s.find("\\hline"), std::string::npos);  // booktabs rules only
  EXPECT_THROW(render_table(t, OutputFormat::csv), std::invalid_argument);
}

TEST(Apa, EffectSizeIntervalAndBayesFactorWhenPresent) {
  auto r = one_sample();
  r.cohen_d_low = 0.147;
  r.cohen_d_high = 0.914;
  r.log_bf10 = std::log(6.4321);
  EXPECT_EQ(apa_string(r), "t(29) = 2.93, p = .007, d = 0.53 [0.15, 0.91], BF\u2081\u2080 = 6.43");
  r.log_bf10 = std::log(0.25);
  EXPECT_EQ(apa_string(r), "t(29) = 2.93, p = .007, d = 0.53 [0.15, 0.91], BF\u2080\u2081 = 4.00");
  // one-sided interval: an infinite bound is not printed
  r.cohen_d_high = HUGE_VAL;
  r.log_bf10.reset();
  EXPECT_EQ(apa_string(r), "t(29) = 2.93, p = .007, d = 0.53");
  EXPECT_EQ(apa_bayes_factor(std::log(123456.0)), "BF\u2081\u2080 = 1.2e+05");
}

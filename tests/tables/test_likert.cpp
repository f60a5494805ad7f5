// Likert analysis assembly and rendering: options, rows, labels, tables, tidy output.
#include "feint/tables/likert.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "feint/error.hpp"

using feint::InvalidData;
using feint::UsageError;
using feint::tables::analyze_likert_file;
using feint::tables::LikertSettings;
using feint::tables::OutputFormat;
using feint::tables::parse_composite;
using feint::tables::render_likert;

namespace {

std::string data(const std::string& name) {
  return std::string(FEINT_TEST_DATA_DIR) + "/likert/" + name;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

}  // namespace

TEST(LikertComposite, ParsesNameAndItems) {
  const auto c = parse_composite(" enjoyment = entertainment, boring ,fun");
  EXPECT_EQ(c.name, "enjoyment");
  EXPECT_EQ(c.items, (std::vector<std::string>{"entertainment", "boring", "fun"}));
  EXPECT_THROW(parse_composite("enjoyment"), UsageError);
  EXPECT_THROW(parse_composite("=a,b"), UsageError);
  EXPECT_THROW(parse_composite("x=a"), UsageError);  // one item is not a multi-item scale
  EXPECT_THROW(parse_composite("x=a,A"), UsageError);
}

TEST(LikertAnalysis, CompositesMustNameKnownItemsAndNewNames) {
  LikertSettings s;
  s.composites = {parse_composite("fun=entertainment,honesty")};
  EXPECT_THROW(analyze_likert_file(data("wide.csv"), s), UsageError);
  s.composites = {parse_composite("trust=entertainment,deception")};
  EXPECT_THROW(analyze_likert_file(data("wide.csv"), s), UsageError);
}

TEST(LikertAnalysis, OneSampleRowsPerConditionWithThePrimaryRankTestFirst) {
  LikertSettings s;
  const auto a = analyze_likert_file(data("wide.csv"), s);
  EXPECT_EQ(a.groups, (std::vector<std::string>{"adaptive", "random"}));
  ASSERT_EQ(a.rows.size(), 2u * 4u * 2u);
  for (std::size_t i = 0; i < a.rows.size(); i += 2) {
    EXPECT_EQ(a.rows[i].result.test, "wilcoxon_signed_rank");
    EXPECT_EQ(a.rows[i + 1].result.test, "one_sample_t");
    EXPECT_EQ(a.rows[i].metric, a.rows[i + 1].metric);
    EXPECT_FALSE(a.rows[i].iteration.has_value());
  }
  EXPECT_EQ(a.rows[0].group1, "adaptive");
  EXPECT_EQ(a.rows[8].group1, "random");
  // entertainment in adaptive: 7 6 6 5 7 against 4, all above: V = 15 (every rank positive).
  EXPECT_EQ(a.rows[0].result.statistic, 15.0);
  EXPECT_EQ(a.rows[0].result.rank_biserial, 1.0);
  // Not significant with n = 5 and ties (normal approximation), and a rank test has no Bayes
  // factor: "n.s.", never "≈".
  EXPECT_EQ(a.rows[0].label, "n.s.");
  EXPECT_EQ(a.rows[1].label, "M>R");  // t-test: t(4) = 5.88, p = .004
}

TEST(LikertAnalysis, ConditionRestrictsAndUnknownConditionIsAUsageError) {
  LikertSettings s;
  s.condition = "random";
  const auto a = analyze_likert_file(data("wide.csv"), s);
  EXPECT_EQ(a.groups, (std::vector<std::string>{"random"}));
  EXPECT_EQ(a.rows.size(), 8u);
  s.condition = "placebo";
  EXPECT_THROW(analyze_likert_file(data("wide.csv"), s), UsageError);
  s.condition.clear();
  s.compare = std::make_pair(std::string("adaptive"), std::string("adaptive"));
  EXPECT_THROW(analyze_likert_file(data("wide.csv"), s), UsageError);
}

TEST(LikertAnalysis, CompareNeedsIndependentGroups) {
  const auto path = (std::filesystem::temp_directory_path() /
                     ("feint-likert-" + std::to_string(::getpid()) + ".csv"))
                        .string();
  std::ofstream(path) << "participant,condition,trust\nP1,a,3\nP2,a,4\nP1,b,5\nP3,b,6\n";
  LikertSettings s;
  s.compare = std::make_pair(std::string("a"), std::string("b"));
  try {
    analyze_likert_file(path, s);
    ADD_FAILURE() << "expected InvalidData";
  } catch (const InvalidData& e) {
    EXPECT_EQ(std::string(e.what()),
              path +
                  ": participant P1 answered in both conditions a and b; Mann-Whitney and "
                  "Welch compare independent groups");
  }
  std::remove(path.c_str());
}

TEST(LikertAnalysis, CompareGivesMannWhitneyAndWelchWithBothGroupsDescribed) {
  LikertSettings s;
  s.compare = std::make_pair(std::string("adaptive"), std::string("random"));
  const auto a = analyze_likert_file(data("wide.csv"), s);
  EXPECT_TRUE(a.two_sample);
  ASSERT_EQ(a.rows.size(), 8u);
  EXPECT_EQ(a.rows[0].result.test, "mann_whitney");
  EXPECT_EQ(a.rows[1].result.test, "welch_t");
  EXPECT_EQ(a.rows[0].group1, "adaptive");
  EXPECT_EQ(a.rows[0].group2, "random");
  EXPECT_EQ(a.summaries.size(), 8u);  // 4 items x 2 groups
  // trust: adaptive 2 3 2 1 2 against random 4 3 5 4 3 -> A lower.
  EXPECT_EQ(a.rows[6].metric, "trust");
  EXPECT_LT(*a.rows[6].result.rank_biserial, 0.0);
  EXPECT_EQ(a.rows[7].label, "A<B");
}

TEST(LikertAnalysis, PaperModeUsesTheFourItemsAndReference35) {
  LikertSettings s;
  s.paper = true;
  s.condition = "adaptive";
  const auto a = analyze_likert_file(data("wide.csv"), s);
  EXPECT_EQ(a.reference, 3.5);
  EXPECT_EQ(a.names, feint::tables::paper_items());
  EXPECT_EQ(a.rows[1].result.mu, 3.5);
  bool noted = false;
  for (const auto& n : a.notes) noted = noted || n.find("--paper") != std::string::npos;
  EXPECT_TRUE(noted);
  // An explicit reference wins over --paper's 3.5.
  s.reference = 4.0;
  EXPECT_EQ(analyze_likert_file(data("wide.csv"), s).reference, 4.0);
}

TEST(LikertAnalysis, PAdjustFamiliesAreOneTestKindAcrossItems) {
  LikertSettings s;
  s.condition = "adaptive";
  s.p_adjust = feint::stats::PAdjustMethod::bonferroni;
  const auto a = analyze_likert_file(data("wide.csv"), s);
  for (const auto& r : a.rows) {
    ASSERT_TRUE(r.result.p_value && r.result.p_adjusted) << r.metric;
    EXPECT_DOUBLE_EQ(*r.result.p_adjusted, std::min(1.0, 4.0 * *r.result.p_value));
  }
}

TEST(LikertRender, TextTableShowsWilcoxonAsPrimaryAndTheTTestAsThePapers) {
  LikertSettings s;
  s.load.reverse = {"trust"};
  s.apa = true;
  const auto a = analyze_likert_file(data("wide.csv"), s);
  std::string text = render_likert(a, OutputFormat::text);
  std::replace(text.begin(), text.end(), '\n', ' ');  // the note is wrapped
  EXPECT_NE(text.find("Wilcoxon signed-rank (primary)"), std::string::npos) << text;
  // "(the paper's analysis)" only with --paper: the user's paper is another one.
  EXPECT_NE(text.find("One-sample t-test"), std::string::npos);
  EXPECT_EQ(text.find("the paper's analysis"), std::string::npos);
  EXPECT_NE(text.find("Condition: adaptive"), std::string::npos);
  EXPECT_NE(text.find("trust (reversed)"), std::string::npos);  // reverse-coded items are marked
  EXPECT_NE(text.find("Responses per scale point"), std::string::npos);
  EXPECT_NE(text.find("Reverse-coded before analysis (x -> 8 - x): trust."), std::string::npos);
  EXPECT_NE(text.find("the Wilcoxon signed-rank test (R's wilcox.test(x, mu = R)) is the primary"),
            std::string::npos);
  EXPECT_NE(text.find("APA, entertainment (adaptive): V = 15, p = .057, r = 1.00 [1.00, 1.00]; "
                      "t(4) = 5.88, p = .004, d = 2.63 [0.66, 4.57], BF\u2081\u2080 = 13.26"),
            std::string::npos)
      << text;
  const auto md = render_likert(a, OutputFormat::markdown);
  EXPECT_NE(md.find("| entertainment"), std::string::npos) << md;
  const auto tex = render_likert(a, OutputFormat::latex);
  EXPECT_NE(tex.find("\\toprule"), std::string::npos) << tex;
}

TEST(LikertRender, TidyCsvHasTheTableColumnsPlusTheLikertColumns) {
  LikertSettings s;
  s.composites = {parse_composite("ability=entertainment,deception")};
  const auto a = analyze_likert_file(data("wide.csv"), s);
  const auto csv = render_likert(a, OutputFormat::csv);
  std::string expected;
  for (const auto c : feint::tables::kTableColumns) expected += std::string(c) + ",";
  for (const auto c : feint::tables::kLikertExtraColumns) expected += std::string(c) + ",";
  expected.pop_back();
  EXPECT_EQ(csv.substr(0, csv.find('\n')), expected);
  EXPECT_EQ(count(csv, "\n"), 1u + 2u * 5u * 2u);  // header + 2 tests x 5 names x 2 conditions
  // The composite's rows carry its alpha in the last column; item rows leave it empty.
  std::istringstream lines(csv);
  std::string line;
  std::size_t with_alpha = 0;
  while (std::getline(lines, line)) {
    if (line.rfind("ability,", 0) == 0) {
      EXPECT_NE(line.back(), ',') << line;
      ++with_alpha;
    } else if (line.rfind("trust,", 0) == 0) {
      EXPECT_EQ(line.back(), ',') << line;
    }
  }
  EXPECT_EQ(with_alpha, 4u);
  const auto json = render_likert(a, OutputFormat::json);
  EXPECT_EQ(json.front(), '[');
  EXPECT_EQ(count(json, "\"cronbach_alpha\""), 20u);
}

TEST(LikertRender, SummaryCsvHasCountsPerScalePoint) {
  LikertSettings s;
  s.condition = "adaptive";
  const auto a = analyze_likert_file(data("wide.csv"), s);
  const auto csv = feint::tables::likert_summary_csv(a);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "group,name,kind,n,missing,mean,sd,median,q1,q3,iqr,pct_below,pct_at,pct_above,n_1,n_2,"
            "n_3,n_4,n_5,n_6,n_7,pct_1,pct_2,pct_3,pct_4,pct_5,pct_6,pct_7");
  // deception in adaptive: 5 4 (missing) 5 6 -> n 4, missing 1, counts 4:1 5:2 6:1.
  EXPECT_NE(csv.find("adaptive,deception,item,4,1,5,0.816496580927726"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",0,0,0,1,2,1,0,0,0,0,25,50,25,0\n"), std::string::npos) << csv;
}

TEST(LikertRender, ReportToFileWritesAtomically) {
  const auto out = (std::filesystem::temp_directory_path() /
                    ("feint-likert-out-" + std::to_string(::getpid()) + ".md"))
                       .string();
  LikertSettings s;
  feint::tables::likert_report_to_file(data("long.csv"), s, out, OutputFormat::markdown);
  std::ifstream in(out);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("| intelligence"), std::string::npos);
  std::remove(out.c_str());
}

TEST(LikertRender, LongScalesShowOnlyBelowAtAbove) {
  const auto path = (std::filesystem::temp_directory_path() /
                     ("feint-likert-vas-" + std::to_string(::getpid()) + ".csv"))
                        .string();
  std::ofstream(path) << "participant,vas\nP1,73\nP2,100\nP3,20\nP4,50\n";
  LikertSettings s;
  s.load.scale_min = 0;
  s.load.scale_max = 100;
  const auto a = analyze_likert_file(path, s);
  EXPECT_EQ(a.reference, 50.0);
  const auto text = render_likert(a, OutputFormat::text);
  EXPECT_NE(text.find("Responses: % of n below / at / above the neutral point 50"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find(" 99 "), std::string::npos);
  EXPECT_NE(text.find("vas    25%   25%   50%"), std::string::npos) << text;
  std::remove(path.c_str());
}

// The JZS prior scale (settable): every t-test row carries the Bayes factor at the
// settings' r. Against the exact integral of the definition: entertainment in adaptive, t(4) =
// 5.8797 against 4 (7 6 6 5 7), log BF10 by integrate(rel.tol = 1e-12) in R with
// tests/golden/bayes/make_bf_golden.R's log_bf_point(t, 5, 4, r).
constexpr double kLogBfMedium = 2.5846784571506802;  // r = sqrt(2)/2
constexpr double kLogBfWide = 2.7753595797574162;    // r = 1

TEST(LikertAnalysis, BayesFactorPriorScaleIsTheSettingsAndMatchesTheExactIntegral) {
  LikertSettings s;
  const auto medium = analyze_likert_file(data("wide.csv"), s);
  s.bf_prior_r = 1.0;
  const auto wide = analyze_likert_file(data("wide.csv"), s);
  ASSERT_EQ(medium.rows.size(), wide.rows.size());
  const auto& m = medium.rows[1].result;
  const auto& w = wide.rows[1].result;
  ASSERT_EQ(m.test, "one_sample_t");
  ASSERT_TRUE(m.log_bf10 && w.log_bf10);
  EXPECT_EQ(*m.bf_prior_r, 0.70710678118654752440);
  EXPECT_EQ(*w.bf_prior_r, 1.0);
  EXPECT_NEAR(*m.log_bf10, kLogBfMedium, 1e-6 * std::abs(kLogBfMedium));
  EXPECT_NEAR(*w.log_bf10, kLogBfWide, 1e-6 * std::abs(kLogBfWide));
  // The note states the scale.
  const std::string text = render_likert(wide, OutputFormat::text);
  EXPECT_EQ(count(text, "scale r = 1 (wide)"), 1u) << text;
}

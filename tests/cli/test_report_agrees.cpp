// The study report agrees with itself (docs/report.md), and a confirmatory hypothesis with a
// direction is tested one-sided (docs/findings.md "Hypotheses"), against R (one_sided_golden.R).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>

#include "cli/cli_helpers.hpp"

namespace fs = std::filesystem;
using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_output;
using feint::test::shell_quote;
using feint::test::TempDir;

namespace {

const std::string kDemo = std::string(FEINT_SOURCE_DIR) + "/data/demo";

// A small study without feint.toml: P1, P2 (adaptive) and P3, P4 (random), two iterations of a
// 0.5 s trial with strategies L and R; P4's second trial has no strategy (`unlabelled`). With
// `questionnaire`, 10 + 10 respondents rate trust and warmth (the values of one_sided_golden.R).
fs::path small_study(const fs::path& dir, bool unlabelled, bool questionnaire) {
  const fs::path study = dir / "study";
  fs::create_directories(study / "logs");
  std::string log = "participant,condition,iteration,strategy,target,t,pad,pad_speed\n";
  const char* ids[] = {"P1", "P2", "P3", "P4"};
  for (int p = 0; p < 4; ++p) {
    for (int it = 1; it <= 2; ++it) {
      const std::string strategy = unlabelled && p == 3 && it == 2 ? "" : (it == 1 ? "L" : "R");
      for (int k = 0; k <= 5; ++k) {
        log += std::string(ids[p]) + ',' + (p < 2 ? "adaptive," : "random,") + std::to_string(it) + ',' +
               strategy + ",right," + std::to_string(k * 0.1) + ',' +
               std::to_string(0.5 + 0.05 * k * (p + 1) / 4.0 + 0.01 * it) + ",0.5\n";
      }
    }
  }
  feint::test::write_text(study / "logs" / "lab.csv", log);
  if (questionnaire) {
    const int trust_a[] = {5, 6, 4, 7, 5, 6, 5, 4, 6, 7}, trust_b[] = {4, 3, 5, 4, 2, 5, 4, 3, 4, 5};
    const int warmth_a[] = {3, 4, 4, 5, 3, 4, 5, 4, 3, 4}, warmth_b[] = {4, 4, 3, 5, 4, 4, 3, 5, 4, 4};
    std::string q = "participant,condition,trust,warmth\n";
    for (int i = 0; i < 10; ++i)
      q += "A" + std::to_string(i) + ",adaptive," + std::to_string(trust_a[i]) + "," + std::to_string(warmth_a[i]) + "\n";
    for (int i = 0; i < 10; ++i)
      q += "B" + std::to_string(i) + ",random," + std::to_string(trust_b[i]) + "," + std::to_string(warmth_b[i]) + "\n";
    feint::test::write_text(study / "questionnaire.csv", q);
  }
  return study;
}

// The finding object of `id` in findings.json (one object per line's worth of text).
std::string finding_json(const std::string& json, const std::string& id) {
  const auto at = json.find("{\"id\": \"" + id + "\"");
  if (at == std::string::npos) return {};
  return json.substr(at, json.find("\n", at) - at);
}

// A number field of a finding object ("p", "ci_low", "bf10"); NaN when absent or null.
double field(const std::string& object, const std::string& name) {
  const std::regex re("\"" + name + "\": (-?[0-9.eE+-]+)");
  std::smatch m;
  if (!std::regex_search(object, m, re)) return std::nan("");
  return std::stod(m[1].str());
}

}  // namespace

// R 4.2.2 (one_sided_golden.R): t.test / wilcox.test(alternative = "greater") and BayesFactor's
// ttestBF(nullInterval = c(0, Inf)) on the questionnaire; two-sided when H2 is exploratory.
TEST(OneSided, ConfirmatoryDirectionalHypothesisIsTestedOneSidedAsR) {
  TempDir dir;
  const auto study = small_study(dir.path(), false, true);
  auto r = run_feint("analyze " + shell_quote(study.string()) + " -o " + shell_quote((dir / "one").string()) +
                     " --no-figures --hypothesis H2:confirmatory=true --hypothesis H2:direction=greater");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string json = read_text(dir / "one" / "findings.json");
  std::string trust = finding_json(json, "H2-compare-trust");
  ASSERT_FALSE(trust.empty()) << json.substr(0, 2000);
  EXPECT_NE(trust.find("\"alternative\": \"greater\""), std::string::npos) << trust;
  EXPECT_NE(trust.find("one-sided (adaptive > random)"), std::string::npos) << trust;
  EXPECT_NEAR(field(trust, "p"), 0.00321754561578, 1e-10);       // wilcox.test, greater
  EXPECT_NEAR(field(trust, "ci_low"), 0.79461284514, 1e-9);      // t.test, greater: [0.79, Inf)
  EXPECT_NE(trust.find("\"ci_high\": null"), std::string::npos) << trust;
  EXPECT_NEAR(field(trust, "bf10"), 26.1526651721, 26.15 * 1e-6);  // ttestBF nullInterval c(0, Inf)
  // Against the direction: the rank test's continuity correction makes p other than 1 - p2/2.
  const std::string warmth = finding_json(json, "H2-compare-warmth");
  EXPECT_NEAR(field(warmth, "p"), 0.647095892393, 1e-10);
  EXPECT_NEAR(field(warmth, "ci_low"), -0.645606368864, 1e-9);
  EXPECT_NEAR(field(warmth, "bf10"), 0.326987790867, 0.327 * 1e-6);
  const std::string text = read_text(dir / "one" / "results-text.md");
  EXPECT_NE(text.find("one-sided Mann-Whitney test"), std::string::npos) << text;
  EXPECT_NE(text.find("95% CI [0.79, \u221e)"), std::string::npos) << text;

  // Exploratory (the default): two-sided, as before.
  r = run_feint("analyze " + shell_quote(study.string()) + " -o " + shell_quote((dir / "two").string()) +
                " --no-figures");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  json = read_text(dir / "two" / "findings.json");
  trust = finding_json(json, "H2-compare-trust");
  EXPECT_NE(trust.find("\"alternative\": \"two.sided\""), std::string::npos) << trust;
  EXPECT_NEAR(field(trust, "p"), 0.00643509123156, 1e-10);
  EXPECT_NEAR(field(trust, "ci_low"), 0.624108941463, 1e-9);
  EXPECT_NEAR(field(trust, "ci_high"), 2.57589105854, 1e-9);
  EXPECT_NEAR(field(trust, "bf10"), 13.1403131944, 13.14 * 1e-6);
  EXPECT_EQ(read_text(dir / "two" / "results-text.md").find("one-sided"), std::string::npos);
}

// H1 confirmatory (direction greater, the paper's): the per-iteration Welch tests are one-sided,
// so the family's member has p = p(two-sided) / 2 when its t is in the direction (R's t.test).
TEST(OneSided, ConfirmatoryH1PerIterationContrastsAreOneSided) {
  TempDir dir;
  const auto study = small_study(dir.path(), false, false);
  const auto r = run_feint("analyze " + shell_quote(study.string()) + " -o " + shell_quote((dir / "out").string()) +
                           " --no-figures --hypothesis H1:confirmatory=true");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string f = finding_json(read_text(dir / "out" / "findings.json"), "H1-iterations-error");
  ASSERT_FALSE(f.empty());
  EXPECT_NE(f.find("\"alternative\": \"greater\""), std::string::npos) << f;
  EXPECT_NE(f.find("\"test\": \"one-sided Welch t test\""), std::string::npos) << f;
  // The comparison table stays two-sided: its p of the member's iteration is twice the finding's.
  const std::string csv = read_text(dir / "out" / "table1_compare.csv");
  const std::string member = f.substr(f.find("\"member\": \"test ") + 16, 1);
  const std::regex row("\\nerror," + member + ",welch_t,[^\\n]*?,two\\.sided,(?:[^,]*,){14}([0-9.eE+-]+),");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(csv, m, row)) << csv;
  const double two_sided = std::stod(m[1].str());
  const double estimate = field(f, "estimate");
  EXPECT_NEAR(field(f, "p"), estimate > 0 ? two_sided / 2 : 1 - two_sided / 2, 1e-12) << f;
}

// On a study folder without feint.toml: the title names the folder given as ".", the trials left
// out of an analysis are accounted for (never "nothing was excluded" beside them), the captions do
// not claim the paper's design (two iterations are not the paper's 20), and the reference check is
// stated with its scale.
TEST(ReportAgrees, StudyFolderWithoutSettings) {
  TempDir dir;
  const auto study = small_study(dir.path(), true, false);
  const std::string out = shell_output("cd " + shell_quote(study.string()) + " && " + shell_quote(FEINT_EXE) +
                                       " analyze . -o ../out 2>&1");
  const std::string md = read_text(dir / "out" / "report.md");
  ASSERT_FALSE(md.empty()) << out;
  EXPECT_EQ(md.rfind("# Study report: study\n", 0), 0u) << md.substr(0, 200);
  EXPECT_NE(read_text(dir / "out" / "report.html").find("<title>Study report: study"), std::string::npos);
  const auto acc = md.find("## Accounting");
  const std::string accounting = md.substr(acc, md.find("\n## ", acc + 5) - acc);
  EXPECT_EQ(accounting.find("Nothing was excluded and there was no warning"), std::string::npos) << accounting;
  EXPECT_NE(accounting.find("1 scored trial of error without a strategy in the logs' labels is left out of "
                            "the exposure analysis."),
            std::string::npos)
      << accounting;
  EXPECT_NE(accounting.find("Reference check: error against 0.5 (error has one scale); confusion against 0.95 "
                            "on the raw scale; the scores' confusion is on the raw scale"),
            std::string::npos)
      << accounting;
  // (The table notes' "the paper's eq. 4" cites a formula, not the design.)
  for (const std::string claim : {"paper's Fig", "paper's claim"}) {
    const auto at = md.find(claim);
    EXPECT_EQ(at, std::string::npos) << "a caption claims the paper's design: "
                                     << md.substr(at == std::string::npos ? 0 : at - 200, 300);
  }
  EXPECT_NE(md.find("This is what the study's participants actually saw, not what a selection algorithm"),
            std::string::npos);
  EXPECT_NE(md.find("- Metrics and references: error against 0.5; confusion against 0.95 on the raw scale"),
            std::string::npos);
}

// On the shipped demo: the paper's design is cited; the model tables' boundary notes name their
// model; the HTML's Table 1, comparison and questionnaire show every test's t, df, p, d [CI], BF
// (r_rb [CI] for the rank test); F's df are printed one way everywhere.
TEST(ReportAgrees, Demo) {
  TempDir dir;
  const auto r = run_feint("analyze " + shell_quote(kDemo) + " -o " + shell_quote((dir / "out").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string md = read_text(dir / "out" / "report.md");
  const std::string html = read_text(dir / "out" / "report.html");
  EXPECT_NE(md.find("The paper's Fig. 5/7 show the selection algorithms' expectation"), std::string::npos);
  EXPECT_NE(md.find("(the paper's Fig. 11)"), std::string::npos);
  EXPECT_NE(md.find("- Metrics and references: error against 0.5; confusion against 0.95 on the raw scale"),
            std::string::npos);
  EXPECT_EQ(md.find("\nSingular fit: "), std::string::npos) << "a boundary note without its model";
  EXPECT_NE(md.find("Singular fit of the confusion model: "), std::string::npos);
  // Table 1 (error, iteration 1, adaptive: t(29) = -1.08 in table1.csv) and the comparison.
  const auto table1 = html.find("<section id=\"table1\"");
  const auto comparison = html.find("<section id=\"comparison\"");
  ASSERT_NE(table1, std::string::npos);
  ASSERT_NE(comparison, std::string::npos);
  const std::string t1 = html.substr(table1, comparison - table1);
  EXPECT_NE(t1.find("t(29) = -1.08, p = .287, d = -0.20 [-0.56, 0.17], BF"), std::string::npos)
      << t1.substr(0, 3000);
  const std::string cmp = html.substr(comparison, html.find("<section", comparison + 10) - comparison);
  EXPECT_NE(cmp.find("t(57.07) = 1.49, p = .143, d = 0.38 [-0.13, 0.89], BF"), std::string::npos)
      << cmp.substr(0, 3000);
  const auto likert = html.find("<section id=\"questionnaire-compare\"");
  ASSERT_NE(likert, std::string::npos);
  EXPECT_NE(html.find("W = 463.5, p = .831, r = .03 [-.26, .31]", likert), std::string::npos);
  // One df format: whole df without decimals, in the findings, the Results text and the page.
  for (const std::string file : {"findings.json", "results-text.md", "report.md"}) {
    const std::string text = read_text(dir / "out" / file);
    EXPECT_EQ(text.find("F(1, 58.0)"), std::string::npos) << file;
    EXPECT_NE(text.find("(1, 58) = 8.48"), std::string::npos) << file;
  }
}

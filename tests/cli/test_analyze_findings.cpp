// feint analyze prints the findings, writes findings.json and puts them first in the report.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_helpers.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

namespace fs = std::filesystem;
using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;

TEST(AnalyzeFindings, PrintedWrittenAndFirstInTheReport) {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  const auto r = run_feint("analyze " + shell_quote(std::string(FEINT_SOURCE_DIR) + "/data/demo") +
                           " -o " + shell_quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("Findings\n* [H1] ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("Per-iteration contrasts of error, adaptive vs random (Westfall\u2013Young maxT-adjusted over 20 iterations"),
            std::string::npos) << r.out;
  // H1 from the mixed models and condition x exposure per strategy, before H2 (docs/findings.md).
  // The condition effect now has a Bayes factor (participants' mean scores), so it is graded.
  const auto model = r.out.find("* [H1] Moderate evidence for a difference: Main effect of condition on error in the mixed model");
  const auto exposure = r.out.find("Exposure slope (error) of strategy 'exaggerating'");
  const auto h2 = r.out.find("* [H2] ");
  EXPECT_NE(model, std::string::npos) << r.out;
  EXPECT_NE(exposure, std::string::npos) << r.out;
  EXPECT_LT(model, h2);
  EXPECT_LT(exposure, h2);
  // The demo lives on the paper's scale: its references lie inside the data, so no warning.
  EXPECT_EQ(r.out.find("lies above every participant's score"), std::string::npos);
  const std::string json = read_text(out / "findings.json");
  for (const char* id : {"H1-model-interaction-error", "H1-model-trend-confusion", "H1-exposure-error-optimal"})
    EXPECT_NE(json.find(std::string("{\"id\": \"") + id + "\""), std::string::npos) << id;
  EXPECT_EQ(json.rfind("[\n  {\"id\": \"H1-iterations-error\"", 0), 0u) << json.substr(0, 200);
  const std::string md = read_text(out / "report.md");
  const auto findings = md.find("## Findings"), design = md.find("## Design");
  ASSERT_NE(findings, std::string::npos);
  EXPECT_LT(findings, design);
  EXPECT_NE(md.find("- **No evidence either way** (H1). Per-iteration contrasts of error"), std::string::npos);
  const std::string html = read_text(out / "report.html");
  EXPECT_NE(html.find("<li class=\"finding inconclusive\" id=\"finding-H1-iterations-error\">"), std::string::npos);
  // Table 1 in the report: "≈" only with BF01 >= 3 (no --equivalence here), else "n.s.".
  for (const char* stem : {"table1.csv", "table1_compare.csv"}) {
    feint::io::CsvReader csv((out / stem).string());
    const int label = csv.column("label"), bf01 = csv.column("bf01"), p = csv.column("p_value");
    int approx = 0, inconclusive = 0;
    while (csv.next()) {
      const std::string l(csv.field(static_cast<std::size_t>(label)));
      const auto bf = feint::io::parse_double(csv.field(static_cast<std::size_t>(bf01)));
      const auto pv = feint::io::parse_double(csv.field(static_cast<std::size_t>(p)));
      ASSERT_TRUE(bf && pv) << stem;
      if (l.find("\u2248") != std::string::npos) {
        ++approx;
        EXPECT_GE(*bf, 3.0) << stem << " " << l;
      } else if (*pv >= 0.05) {
        ++inconclusive;
        EXPECT_EQ(l, "n.s.") << stem;
        EXPECT_LT(*bf, 3.0) << stem;
      }
    }
    EXPECT_GT(approx + inconclusive, 0) << stem;
  }
}

// data/example is a within-participants design (each participant in both conditions, no feint.toml):
// the design is read off the data, the per-iteration contrasts are paired and adjusted by maxT over
// the 2^3 sign flips of the pairs, and the exposure slopes (counted within each condition) are
// compared paired: a paired t on the 3 participants' slopes, t(2).
TEST(AnalyzeFindings, AWithinParticipantsStudyIsAnalysedPairedIncludingTheExposureSlopes) {
  TempDir dir;
  fs::create_directories(dir.path() / "study" / "logs");
  for (const char* f : {"p01.csv", "p02.csv", "p03.csv"})
    fs::copy_file(fs::path(FEINT_SOURCE_DIR) / "data" / "example" / f, dir.path() / "study" / "logs" / f);
  const auto r = run_feint("analyze " + shell_quote((dir.path() / "study").string()) +
                           " --compare adaptive,random -o " + shell_quote((dir.path() / "out").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Per-iteration contrasts of error, adaptive vs random (Westfall\u2013Young maxT-adjusted "
                       "over 20 iterations, all 8 sign flips of the participants' pairs)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(read_text(dir.path() / "out" / "table1_compare.txt").find("Paired t-tests"), std::string::npos);
  EXPECT_NE(read_text(dir.path() / "out" / "report.md").find("conditions within participants (read off the data: "
                                                             "each of the 3 participants saw both conditions)"),
            std::string::npos);
  EXPECT_EQ(r.out.find("Exposure slopes of error by condition: not computable"), std::string::npos) << r.out;
  const std::string findings = read_text(dir.path() / "out" / "findings.json");
  const auto at = findings.find("\"id\": \"H1-exposure-error-exaggerating\"");
  ASSERT_NE(at, std::string::npos);
  EXPECT_NE(findings.find("\"effect_size\": {\"name\": \"d_z\"", at), std::string::npos);
  EXPECT_NE(findings.find("\"test\": \"paired t test\"", at), std::string::npos);
  EXPECT_NE(read_text(dir.path() / "out" / "exposure_by_condition.md").find("a paired t test on the slopes"),
            std::string::npos);
}

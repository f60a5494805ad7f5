// feint analyze prints the findings, writes findings.json and puts them first in the report.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_helpers.hpp"

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
  EXPECT_NE(r.out.find("Per-iteration contrasts of error, adaptive vs random (Holm-corrected over 20 tests)"),
            std::string::npos) << r.out;
  EXPECT_NE(r.out.find("The reference confusion = 0.95 lies above every participant's score"), std::string::npos);
  const std::string json = read_text(out / "findings.json");
  EXPECT_EQ(json.rfind("[\n  {\"id\": \"H1-iterations-error\"", 0), 0u) << json.substr(0, 200);
  const std::string md = read_text(out / "report.md");
  const auto findings = md.find("## Findings"), design = md.find("## Design");
  ASSERT_NE(findings, std::string::npos);
  EXPECT_LT(findings, design);
  EXPECT_NE(md.find("- **No evidence either way** (H1). Per-iteration contrasts of error"), std::string::npos);
  const std::string html = read_text(out / "report.html");
  EXPECT_NE(html.find("<li class=\"finding inconclusive\" id=\"finding-H1-iterations-error\">"), std::string::npos);
}

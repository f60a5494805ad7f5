// The study pipeline end to end (issue 19): the settings block that the report prints is a
// feint.toml that feint accepts and that reproduces the run byte for byte; `analyze` without -o
// says where it wrote; `plot` states its true defaults and refuses --apa.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "cli/cli_helpers.hpp"

namespace fs = std::filesystem;
using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;

namespace {

const std::string kDemo = std::string(FEINT_SOURCE_DIR) + "/data/demo";

std::string shell_output(const std::string& command) {
  std::string out;
  FILE* p = popen(command.c_str(), "r");
  if (p == nullptr) return out;
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  pclose(p);
  return out;
}

}  // namespace

TEST(AnalyzePipeline, PrintedSettingsReproduceTheRunByteForByte) {
  TempDir dir;
  const auto first = dir / "first", second = dir / "second";
  auto r = run_feint("analyze " + shell_quote(kDemo) + " -o " + shell_quote(first.string()) +
                     " --no-figures --p-adjust holm --alpha 0.01");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The block in report.html is the settings.toml written beside it.
  const std::string toml = read_text(first / "settings.toml");
  ASSERT_NE(toml.find("p-adjust = \"holm\""), std::string::npos) << toml;
  ASSERT_NE(toml.find("alpha = 0.01"), std::string::npos) << toml;
  ASSERT_NE(toml.find("compare = \"adaptive,random\""), std::string::npos) << toml;
  const std::string html = read_text(first / "report.html");
  EXPECT_NE(html.find("p-adjust = &quot;holm&quot;"), std::string::npos);
  const std::string md = read_text(first / "report.md");
  EXPECT_NE(md.find("```toml\n" + toml), std::string::npos) << "report.md's block is settings.toml";

  // Take the printed settings (no other option), analyze again, compare every result.
  feint::test::write_text(dir / "printed.toml", toml);
  r = run_feint("analyze " + shell_quote(kDemo) + " --config " +
                shell_quote((dir / "printed.toml").string()) + " -o " +
                shell_quote(second.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::size_t compared = 0;
  for (const auto& e : fs::recursive_directory_iterator(first)) {
    if (!e.is_regular_file()) continue;
    const auto rel = fs::relative(e.path(), first);
    const std::string name = rel.string();
    // The report pages name the command line and the settings file, which differ by design.
    if (name == "report.html" || name == "report.md") continue;
    ASSERT_TRUE(fs::exists(second / rel)) << name;
    EXPECT_EQ(read_text(e.path()), read_text(second / rel)) << name << " differs";
    ++compared;
  }
  EXPECT_GE(compared, 30u);
  EXPECT_EQ(read_text(second / "settings.toml"), toml);
}

TEST(AnalyzePipeline, WithoutOutputSaysWhereItWrote) {
  TempDir dir;
  const std::string out = shell_output("cd " + shell_quote(dir.path().string()) + " && " +
                                       shell_quote(FEINT_EXE) + " analyze " + shell_quote(kDemo) +
                                       " --no-figures 2>&1");
  EXPECT_NE(out.find("written to feint-analysis (the default; choose another with -o)"),
            std::string::npos)
      << out;
  EXPECT_TRUE(fs::exists(dir / "feint-analysis" / "report.html"));
}

TEST(AnalyzePipeline, ReportListsExclusionsAndTheMixedModel) {
  TempDir dir;
  const auto r = run_feint("analyze " + shell_quote(kDemo) + " -o " +
                           shell_quote((dir / "out").string()) + " --no-figures --time-unit ms");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Seconds read as milliseconds: the warning goes to standard error and into the report.
  EXPECT_NE(r.err.find("feint: warning:"), std::string::npos) << r.err;
  const std::string md = read_text(dir / "out" / "report.md");
  EXPECT_NE(md.find("## Accounting: data read, excluded and warned about"), std::string::npos);
  EXPECT_NE(md.find("Read 60 log files (219587 rows); 1200 trials scored, 0 trials rejected."),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("scoring: "), std::string::npos) << "the scoring warning is listed";
  EXPECT_NE(md.find("## Mixed model (condition x iteration)"), std::string::npos);
  EXPECT_NE(md.find("[Download as CSV](model.csv)"), std::string::npos);
  const std::string json = read_text(dir / "out" / "results.json");
  EXPECT_NE(json.find("\"trials_scored\": 1200"), std::string::npos);
  EXPECT_NE(json.find("\"model\": "), std::string::npos);
}

TEST(PlotCli, HelpStatesTrueDefaultsAndApaIsRefused) {
  const auto help = run_feint("plot --help");
  ASSERT_EQ(help.exit_code, 0);
  const auto o = help.out.find("-o,--output");
  ASSERT_NE(o, std::string::npos) << help.out;
  const std::string line = help.out.substr(o, help.out.find('\n', o) - o);
  EXPECT_EQ(line.find("[-]"), std::string::npos) << line;
  EXPECT_NE(help.out.find("(required)"), std::string::npos);
  const auto missing = run_feint("plot x.csv --figure error");
  EXPECT_EQ(missing.exit_code, 64) << missing.err;
  const auto apa = run_feint("plot " + shell_quote(kDemo + "/questionnaire.csv") +
                             " --figure likert --apa -o /tmp/never-written.svg");
  EXPECT_EQ(apa.exit_code, 64) << apa.err;
  EXPECT_NE(apa.err.find("--apa: a figure has no APA strings"), std::string::npos) << apa.err;
  EXPECT_FALSE(fs::exists("/tmp/never-written.svg"));
}

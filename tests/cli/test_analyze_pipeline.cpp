// The study pipeline end to end: the settings block that the report prints is a
// feint.toml that feint accepts and that reproduces the run byte for byte; `analyze` without -o
// says where it wrote; `plot` states its true defaults and refuses --apa.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/cli_helpers.hpp"

namespace fs = std::filesystem;
using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_output;
using feint::test::shell_quote;
using feint::test::TempDir;

namespace {

const std::string kDemo = std::string(FEINT_SOURCE_DIR) + "/data/demo";

// A small study in `dir`: P1, P2 (adaptive) and P3, P4 (random), two iterations of a 0.5 s trial
// (times multiplied by `scale`: 1000 = milliseconds), with or without the condition column, and a
// questionnaire naming `respondents` (none when empty).
fs::path small_study(const fs::path& dir, double scale, bool with_condition,
                     const std::vector<std::string>& respondents = {}) {
  const fs::path study = dir / "study";
  fs::create_directories(study / "logs");
  std::string log = std::string("participant,") + (with_condition ? "condition," : "") +
                    "iteration,strategy,target,t,pad,pad_speed\n";
  const char* ids[] = {"P1", "P2", "P3", "P4"};
  for (int p = 0; p < 4; ++p) {
    for (int it = 1; it <= 2; ++it) {
      for (int k = 0; k <= 5; ++k) {
        log += std::string(ids[p]) + ',' + (with_condition ? (p < 2 ? "adaptive," : "random,") : "") +
               std::to_string(it) + ',' + (it == 1 ? "L" : "R") + ",right," +
               std::to_string(k * 0.1 * scale) + ',' +
               std::to_string(0.5 + 0.05 * k * (p + 1) / 4.0 + 0.01 * it) + ",0.5\n";
      }
    }
  }
  feint::test::write_text(study / "logs" / "lab.csv", log);
  if (!respondents.empty()) {
    std::string q = "participant,condition,trust\n";
    for (std::size_t i = 0; i < respondents.size(); ++i) {
      q += respondents[i] + (i % 2 ? ",random," : ",adaptive,") + std::to_string(3 + i % 3) + "\n";
    }
    feint::test::write_text(study / "questionnaire.csv", q);
  }
  return study;
}

}  // namespace

TEST(AnalyzePipeline, EveryFigureInEveryFormatWithAltTextFromItsData) {
  TempDir dir;
  const auto out = dir / "out";
  const auto r = run_feint("analyze " + shell_quote(kDemo) + " -o " + shell_quote(out.string()) +
                           " --figure-formats pdf,svg,png --formats csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = read_text(out / "report.html");
  for (const std::string name :
       {"error", "confusion", "participants-error", "model-error", "model-confusion",
        "exposure-error", "exposure-confusion", "strategies", "traces", "likert", "likert-means"}) {
    for (const std::string file : {"-1col.pdf", "-1col.svg", "-1col.png", "-2col.pdf",
                                   "-2col.svg", "-2col.png"}) {
      EXPECT_GT(fs::file_size(out / "figures" / (name + file)), 500u) << name << file;
    }
    EXPECT_NE(html.find("<figure id=\"fig-" + name + "\">"), std::string::npos) << name;
  }
  // The alt text is the plot module's sentence from the data (numbers of this study), not a
  // generic description; the captions name what the new figures show.
  EXPECT_NE(html.find("The mixed model&#39;s fitted error per iteration (linear trend over the "
                      "iterations, random intercept) with its 95% band for adaptive and random"),
            std::string::npos);
  EXPECT_NE(html.find("Mean error against the number of times the participant had seen the "
                      "strategy, one panel per strategy"),
            std::string::npos);
  EXPECT_NE(html.find("Adaptive averages 0.48"), std::string::npos);
  EXPECT_EQ(html.find("Line chart: mean error per iteration"), std::string::npos)
      << "no hand-written generic alt text";
  const std::string md = read_text(out / "report.md");
  EXPECT_NE(md.find("Mixed model's fitted trend of error.** ![The mixed model's fitted error"),
            std::string::npos);
}

TEST(AnalyzePipeline, QuestionnaireIdsMissingOnEitherSideAreListed) {
  TempDir dir;
  const auto study = small_study(dir.path(), 1, true, {"P1", "P2", "P3", "P9"});
  const auto r = run_feint("analyze " + shell_quote(study.string()) + " -o " +
                           shell_quote((dir / "out").string()) + " --no-figures");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("feint: warning: participants: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("P4"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("P9"), std::string::npos) << r.err;
  const std::string md = read_text(dir / "out" / "report.md");
  EXPECT_NE(md.find("- participants 1 participant: in the logs but not in the questionnaire (P4)"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("- participants 1 participant: in the questionnaire but not in the logs (P9)"),
            std::string::npos);
  EXPECT_NE(md.find("Participant ids of the logs and the questionnaire: 3 in both, 1 only in the "
                    "logs, 1 only in the questionnaire."),
            std::string::npos);
  const std::string json = read_text(dir / "out" / "results.json");
  EXPECT_NE(json.find("\"examples\": [\"P9\"]"), std::string::npos);
  EXPECT_NE(json.find("\"participants_compared\": {\"in_both\": 3, \"only_in_logs\": [\"P4\"], "
                      "\"only_in_questionnaire\": [\"P9\"]}"),
            std::string::npos)
      << json;
}

TEST(AnalyzePipeline, MillisecondTimesAreWarnedInTheReport) {
  TempDir dir;
  const auto study = small_study(dir.path(), 1000, true);
  const auto r = run_feint("analyze " + shell_quote(study.string()) + " -o " +
                           shell_quote((dir / "out").string()) + " --no-figures");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string md = read_text(dir / "out" / "report.md");
  const auto at = md.find("- scoring: the median trial lasts 500 s");
  ASSERT_NE(at, std::string::npos) << md;
  EXPECT_NE(md.find("give --time-unit ms", at), std::string::npos);
  EXPECT_NE(md.find("[time-unit-ms-suspected]", at), std::string::npos);
  EXPECT_EQ(md.find("the median trial lasts", at + 12), std::string::npos) << "listed once";
  EXPECT_NE(md.find("500 s): implausible for seconds; if the logs' times are in milliseconds, give "
                    "--time-unit ms (every confusion and duration would otherwise be off by a "
                    "factor of 1000) (column 't') [time-unit-ms-suspected]"),
            std::string::npos);
  // No scratch path of the pipeline reaches the report (the ANOVA's note names scores.csv).
  EXPECT_EQ(md.find("feint-analyze-"), std::string::npos);
  EXPECT_NE(read_text(dir / "out" / "report.html").find("the median trial lasts 500 s"),
            std::string::npos);
}

// Times in milliseconds read with --time-unit ms draw the same mean pad traces as the same study in
// seconds: the figures read the logs as the scorer does (they used to read milliseconds as seconds).
TEST(AnalyzePipeline, MillisecondLogsDrawTheSameTracesAsSeconds) {
  TempDir dir;
  const auto in_s = small_study(dir / "s", 1.0, true);
  const auto in_ms = small_study(dir / "ms", 1000.0, true);
  auto r = run_feint("analyze " + shell_quote(in_s.string()) + " -o " +
                     shell_quote((dir / "out-s").string()) + " --figure-formats svg");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_feint("analyze " + shell_quote(in_ms.string()) + " --time-unit ms -o " +
                shell_quote((dir / "out-ms").string()) + " --figure-formats svg");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::size_t compared = 0;
  for (const auto& e : fs::directory_iterator(dir / "out-s" / "figures")) {
    const std::string name = e.path().filename().string();
    if (name.find("trace") == std::string::npos) continue;
    EXPECT_EQ(read_text(e.path()), read_text(dir / "out-ms" / "figures" / name)) << name;
    ++compared;
  }
  EXPECT_GE(compared, 1u);
}

TEST(AnalyzePipeline, TwoConditionsRefuseALogWithoutTheConditionColumn) {
  TempDir dir;
  const auto study = small_study(dir.path(), 1, false);
  const auto r = run_feint("analyze " + shell_quote(study.string()) + " -o " +
                           shell_quote((dir / "out").string()) +
                           " --no-figures --compare adaptive,random");
  EXPECT_EQ(r.exit_code, 65) << r.err;
  EXPECT_NE(r.err.find("lab.csv:1: no condition column 'condition', but the study has 2 "
                       "conditions (adaptive, random)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "report.html"));
}

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

// The report's Reproduce line is a command to run from the report's folder: its paths are relative
// to that folder, not to the shell's folder of whoever made it, so a shared report carries no one's
// folder layout, and the line run from there makes the same report again.
TEST(AnalyzePipeline, ReproduceLineRunsFromTheReportsFolder) {
  TempDir dir;
  small_study(dir / "lab", 1.0, true);
  fs::create_directories(dir / "elsewhere");
  const std::string run_from_elsewhere =
      "cd " + shell_quote((dir / "elsewhere").string()) + " && " + shell_quote(FEINT_EXE) +
      " analyze ../lab/study -o ../out/res --no-figures >/dev/null 2>&1; echo $?";
  ASSERT_EQ(shell_output(run_from_elsewhere), "0\n");
  const auto res = dir / "out" / "res";
  const std::string md = read_text(res / "report.md");
  const std::string line = "feint analyze ../../lab/study -o ../res --no-figures";
  ASSERT_NE(md.find("run from this report's folder"), std::string::npos) << md;
  ASSERT_NE(md.find("```\n" + line + "\n```"), std::string::npos) << md.substr(md.find("## Reproduce"));
  EXPECT_NE(read_text(res / "report.html").find("<pre>" + line + "</pre>"), std::string::npos);
  // Run it from the report's folder, as the report says: the same report again.
  const std::string again = "cd " + shell_quote(res.string()) + " && " + shell_quote(FEINT_EXE) +
                            line.substr(5) + " >/dev/null 2>&1; echo $?";
  ASSERT_EQ(shell_output(again), "0\n");
  EXPECT_EQ(read_text(dir / "out" / "res" / "report.md"), md);
}

// A study folder without feint.toml whose logs hold exactly two conditions compares them with no
// setting made by hand, says so in the report, and its printed settings name the comparison (so
// they reproduce the run). A settings file that names no comparison is obeyed.
TEST(AnalyzePipeline, TwoConditionsAreComparedByDefaultAndTheReportSaysSo) {
  TempDir dir;
  const auto study = small_study(dir.path(), 1.0, true);
  auto r = run_feint("analyze " + shell_quote(study.string()) + " -o " +
                     shell_quote((dir / "out").string()) + " --no-figures");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "out" / "table1_compare.csv"));
  const std::string md = read_text(dir / "out" / "report.md");
  EXPECT_NE(md.find("- Comparison: adaptive against random (compared by default: the logs hold "
                    "exactly these two conditions"),
            std::string::npos)
      << md.substr(0, 1500);
  EXPECT_NE(read_text(dir / "out" / "settings.toml").find("compare = \"adaptive,random\""),
            std::string::npos);

  // A settings file without a comparison: the study's own choice, no comparison.
  feint::test::write_text(study / "feint.toml", "alpha = 0.05\n");
  r = run_feint("analyze " + shell_quote(study.string()) + " -o " +
                shell_quote((dir / "out2").string()) + " --no-figures");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out2" / "table1_compare.csv"));
  EXPECT_NE(read_text(dir / "out2" / "report.md").find("- Comparison: none"), std::string::npos);
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

TEST(PlotCli, CompareRefusesAScoresFileWithoutTheConditionColumn) {
  TempDir dir;
  feint::test::write_text(dir / "scores.csv",
                          "participant,iteration,error,confusion\nP1,1,0.4,0.5\nP2,1,0.5,0.6\n"
                          "P1,2,0.3,0.5\nP2,2,0.6,0.7\n");
  const auto r = run_feint("plot " + shell_quote((dir / "scores.csv").string()) +
                           " --figure error --compare a,b -o " +
                           shell_quote((dir / "e.svg").string()));
  EXPECT_EQ(r.exit_code, 65) << r.err;
  EXPECT_NE(r.err.find("scores.csv:1: no condition column 'condition', but the study has 2 "
                       "conditions (a, b)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "e.svg"));
}

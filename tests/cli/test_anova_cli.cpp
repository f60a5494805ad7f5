// End-to-end tests of `feint anova` (runs FEINT_EXE): the numbers of the R goldens through the
// command line, every format, the notes, and the exit codes of bad input.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "cli/cli_helpers.hpp"
#include "feint/io/csv.hpp"

using feint::test::read_text;
using feint::test::run_feint;
using feint::test::RunResult;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

const std::string kGolden = std::string(FEINT_SOURCE_DIR) + "/tests/golden/models/";

/// One golden case as a scores file with metrics `error` (the case's values) and `confusion`
/// (the same values, so both metrics must agree with R).
std::string scores_of_case(const std::string& name) {
  std::ifstream in(kGolden + "anova_data.csv");
  std::string line, out = "participant,condition,iteration,error,confusion\n";
  std::getline(in, line);
  while (std::getline(in, line)) {
    const auto f = feint::io::split_csv_line(line);
    if (f[0] != name) continue;
    const std::string v = f.size() > 4 ? f[4] : "";
    out += f[1] + "," + f[2] + "," + f[3] + "," + v + "," + v + "\n";
  }
  return out;
}

/// Golden rows of a case: effect -> column -> text.
std::map<std::string, std::map<std::string, std::string>> golden_of_case(const std::string& name) {
  std::ifstream in(kGolden + "anova_golden.csv");
  std::string line;
  std::getline(in, line);
  const auto header = feint::io::split_csv_line(line);
  std::map<std::string, std::map<std::string, std::string>> out;
  while (std::getline(in, line)) {
    const auto f = feint::io::split_csv_line(line);
    if (f[0] != name) continue;
    for (std::size_t i = 0; i < header.size(); ++i) out[f[1]][header[i]] = f[i];
  }
  return out;
}

std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) rows.push_back(feint::io::split_csv_line(line));
  return rows;
}

TEST(AnovaCli, CsvCarriesAfexNumbersForEveryMetricOfThePaperDesign) {
  TempDir dir;
  const auto scores = dir.path() / "scores.csv";
  const std::string input = scores_of_case("paper_design");
  write_text(scores, input);
  const RunResult r = run_feint("anova " + shell_quote(scores.string()) + " --format csv --apa");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(scores), input);  // input untouched
  const auto rows = parse_csv(r.out);
  ASSERT_EQ(rows.size(), 7u);  // header + 2 metrics x 3 effects
  std::map<std::string, std::size_t> col;
  for (std::size_t i = 0; i < rows[0].size(); ++i) col[rows[0][i]] = i;
  const auto golden = golden_of_case("paper_design");
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto& g = golden.at(rows[i][col.at("effect")]);
    for (const auto& [ours, theirs] :
         std::map<std::string, std::string>{{"F", "F"},
                                            {"den_df", "afex_gg_den_df"},
                                            {"p.value", "afex_gg_p"},
                                            {"MSE", "afex_gg_mse"},
                                            {"ges", "ges"},
                                            {"pes", "pes"},
                                            {"gg_eps", "gg_eps"},
                                            {"hf_eps", "hf_eps"},
                                            {"mauchly_W", "mauchly_w"},
                                            {"p.value_uncorrected", "p"}}) {
      const std::string& mine = rows[i][col.at(ours)];
      if (g.at(theirs) == "NA") {
        EXPECT_EQ(mine, "") << ours;
        continue;
      }
      const double want = std::stod(g.at(theirs));
      EXPECT_NEAR(std::stod(mine), want, 1e-10 * std::abs(want)) << rows[i][1] << " " << ours;
    }
  }
  // pes with its interval as effectsize::F_to_eta2 on the reported table (tests/golden/models/
  // anova_pes_ci.R). effectsize's lower bounds come from a search (off by up to 7.1e-9 here: 3e-6
  // relative); feint's are exact roots, checked against uniroot(tol = 1e-15) (pes_low_exact) to
  // 2e-10 (measured 7.2e-11: both solve R's / Boost's noncentral F, R's pnbeta stops at 1e-9),
  // and effectsize's error is asserted to stay as small as measured.
  std::map<std::string, std::vector<std::string>> ci;
  for (const auto& g : parse_csv(read_text(std::string(FEINT_SOURCE_DIR) + "/tests/golden/models/anova_pes_ci.csv")))
    if (g.size() == 6 && g[0] == "paper_design") ci[g[1]] = g;
  ASSERT_EQ(ci.size(), 3u);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto& g = ci.at(rows[i][col.at("effect")]);
    const double low = std::stod(rows[i][col.at("pes_low")]), exact = std::stod(g[5]);
    EXPECT_NEAR(std::stod(rows[i][col.at("pes")]), std::stod(g[2]), 1e-10 * std::stod(g[2])) << rows[i][1];
    EXPECT_NEAR(low, exact, 2e-10) << rows[i][1];
    EXPECT_NEAR(std::stod(g[3]), exact, 1e-8) << rows[i][1] << " (effectsize's search)";
    EXPECT_EQ(std::stod(rows[i][col.at("pes_high")]), std::stod(g[4])) << rows[i][1];
  }
  EXPECT_EQ(rows[2][col.at("correction")], "GG");
  EXPECT_EQ(
      rows[2][col.at("apa")].rfind("F(4.81, 278.8) = 2.32, p = .046, \u03b7G\u00b2 = .002", 0), 0u)
      << rows[2][col.at("apa")];
}

TEST(AnovaCli, TextNamesExcludedParticipantsAndHfChangesTheDf) {
  TempDir dir;
  const auto scores = dir.path() / "scores.csv";
  write_text(scores, scores_of_case("missing_trials"));
  const RunResult r = run_feint("anova " + shell_quote(scores.string()) + " --metric error");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Excluded for a missing value (as afex): 3 (P07, P08, P13)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("Greenhouse-Geisser"), std::string::npos);
  const RunResult hf = run_feint("anova " + shell_quote(scores.string()) +
                                 " --metric error --correction HF --format json");
  ASSERT_EQ(hf.exit_code, 0) << hf.err;
  EXPECT_NE(hf.out.find("\"correction\": \"HF\""), std::string::npos) << hf.out;
  EXPECT_NE(hf.out.find("\"excluded\": \"P07;P08;P13\""), std::string::npos);
}

TEST(AnovaCli, SingularCaseSaysWhyInsteadOfEpsilons) {
  TempDir dir;
  const auto scores = dir.path() / "scores.csv";
  write_text(scores, scores_of_case("singular"));
  const RunResult r =
      run_feint("anova " + shell_quote(scores.string()) + " --metric error --format markdown");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("| singular |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("12 complete participants give 10 error df for 19 iteration contrasts"),
            std::string::npos);
}

TEST(AnovaCli, LatexIsABooktabsTable) {
  TempDir dir;
  const auto scores = dir.path() / "scores.csv";
  write_text(scores, scores_of_case("balanced_spherical"));
  const RunResult r = run_feint("anova " + shell_quote(scores.string()) + " --format latex");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\\toprule"), std::string::npos);
  EXPECT_NE(r.out.find("\\label{tab:feint-anova}"), std::string::npos);
}

TEST(AnovaCli, ParticipantInTwoConditionsExits65WithTheLine) {
  TempDir dir;
  const auto scores = dir.path() / "scores.csv";
  write_text(scores,
             "participant,condition,iteration,error\nP1,a,1,0.1\nP1,a,2,0.2\nP2,b,1,0.3\n"
             "P2,a,2,0.4\nP3,b,1,0.5\nP3,b,2,0.3\n");
  // Undeclared: some in two conditions, some in one; the design must be declared.
  const RunResult r = run_feint("anova " + shell_quote(scores.string()) + " --metric error");
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("scores.csv:5: participant 'P2' has trials in 2 conditions but participant 'P1' (line "
                       "2) in one only (1 of 3 participants saw more than one): declare the design"),
            std::string::npos)
      << r.err;
  // Declared between: the participant in two conditions, with both lines, and what to set.
  const RunResult b = run_feint("anova " + shell_quote(scores.string()) + " --metric error --design between");
  EXPECT_EQ(b.exit_code, 65);
  EXPECT_NE(b.err.find("scores.csv:5: participant 'P2' has trials in condition 'a' (line 5) and in 'b' (line 4), "
                       "but the design is declared between participants"),
            std::string::npos)
      << b.err;
  const RunResult bad = run_feint("anova " + shell_quote(scores.string()) + " --design crossed");
  EXPECT_EQ(bad.exit_code, 64);
  EXPECT_NE(bad.err.find("--design 'crossed': expected between"), std::string::npos) << bad.err;
}

TEST(AnovaCli, ConstantMetricExits65AndBadCorrectionExits64) {
  TempDir dir;
  const auto scores = dir.path() / "scores.csv";
  write_text(scores, "participant,iteration,error\nP1,1,0.5\nP1,2,0.5\nP2,1,0.5\nP2,2,0.5\n");
  RunResult r = run_feint("anova " + shell_quote(scores.string()) + " --metric error");
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("metric 'error' has no variance"), std::string::npos) << r.err;
  r = run_feint("anova " + shell_quote(scores.string()) + " --metric error --correction LB");
  EXPECT_EQ(r.exit_code, 64);
  EXPECT_NE(r.err.find("--correction 'LB': expected none, GG or HF"), std::string::npos) << r.err;
}

}  // namespace

namespace {

TEST(AnovaCli, AnalyzeWritesTheAnovaOfItsScoresInEveryFormatAsked) {
  TempDir dir;
  const auto out = dir.path() / "out";
  const std::string demo = std::string(FEINT_SOURCE_DIR) + "/data/demo";
  const RunResult r = run_feint("analyze " + shell_quote(demo) + " -o " +
                                shell_quote(out.string()) + " --formats csv,text");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(std::filesystem::exists(out / "anova.csv"));
  ASSERT_TRUE(std::filesystem::exists(out / "anova.txt"));
  EXPECT_FALSE(std::filesystem::exists(out / "anova.json"));
  // The same numbers as `feint anova` on the scores analyze wrote.
  const RunResult direct =
      run_feint("anova " + shell_quote((out / "scores.csv").string()) + " --format csv");
  ASSERT_EQ(direct.exit_code, 0) << direct.err;
  EXPECT_EQ(read_text(out / "anova.csv"), direct.out);
  EXPECT_EQ(parse_csv(direct.out).size(), 7u);  // error and confusion, 3 effects each
}

}  // namespace

namespace {

TEST(AnovaCli, LatexOfAnovaAndPowerCompilesInAPaper) {
  if (std::system(
          "command -v pdflatex >/dev/null 2>&1 && kpsewhich booktabs.sty >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "pdflatex with booktabs not installed: LaTeX compile check skipped";
  }
  TempDir dir;
  const auto scores = dir.path() / "scores.csv";
  write_text(scores, scores_of_case("singular"));
  const std::string s = shell_quote(scores.string());
  ASSERT_EQ(
      run_feint("anova " + s + " --apa --format latex -o " + shell_quote((dir / "a.tex").string()))
          .exit_code,
      0);
  ASSERT_EQ(run_feint("power t-test --d 0.4 --power 0.9 --welch --sd2 1.5 --format latex -o " +
                      shell_quote((dir / "b.tex").string()))
                .exit_code,
            0);
  ASSERT_EQ(run_feint("power simulate " + s + " --studies 20 --format latex -o " +
                      shell_quote((dir / "c.tex").string()))
                .exit_code,
            0);
  write_text(dir / "paper.tex",
             "\\documentclass{article}\n\\usepackage[T1]{fontenc}\n\\usepackage{booktabs}\n"
             "\\usepackage{graphicx}\n\\usepackage{amsmath}\n\\begin{document}\nText.\n"
             "\\input{a.tex}\n\\input{b.tex}\n\\input{c.tex}\n\\end{document}\n");
  const std::string cmd =
      "cd " + shell_quote(dir.path().string()) +
      " && pdflatex -interaction=nonstopmode -halt-on-error paper.tex > out.txt 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << read_text(dir / "out.txt");
  EXPECT_EQ(read_text(dir / "paper.log").find("Overfull \\hbox"), std::string::npos);
}

}  // namespace

namespace {

// When every participant of a condition has a missing value, `feint anova` stops
// (exit 65, as afex) instead of silently running the one-way ANOVA of the other condition;
// --drop-empty-conditions asks for that analysis and the note says what was dropped.
TEST(AnovaCli, ConditionWithEveryParticipantExcludedStopsUnlessAsked) {
  TempDir dir;
  std::string text = "participant,condition,iteration,error\n";
  for (int k = 0; k < 8; ++k)
    for (int j = 1; j <= 3; ++j) {
      const bool b = k >= 4;
      const bool missing = b && j == 1 + k % 3;
      text += "P" + std::to_string(k) + "," + (b ? "b" : "a") + "," + std::to_string(j) + "," +
              (missing ? "" : std::to_string(0.3 + 0.05 * j + 0.01 * ((k * 5 + j) % 7))) + "\n";
    }
  const auto p = dir.path() / "s.csv";
  write_text(p, text);
  const RunResult r = run_feint("anova " + shell_quote(p.string()) + " --metric error");
  EXPECT_EQ(r.exit_code, 65) << r.out;
  EXPECT_NE(r.err.find("every participant of condition 'b' (P4, P5, P6, P7) lacks a value"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("--drop-empty-conditions"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());

  const RunResult one =
      run_feint("anova " + shell_quote(p.string()) + " --metric error --drop-empty-conditions");
  EXPECT_EQ(one.exit_code, 0) << one.err;
  std::string flat = one.out;  // the note is wrapped
  for (char& c : flat)
    if (c == '\n') c = ' ';
  EXPECT_NE(flat.find("one-way repeated measures"), std::string::npos) << one.out;
  EXPECT_NE(flat.find("Dropped on request (--drop-empty-conditions): condition b"),
            std::string::npos)
      << one.out;
  const RunResult csv = run_feint("anova " + shell_quote(p.string()) +
                                  " --metric error --drop-empty-conditions --format csv");
  EXPECT_NE(csv.out.find("condition b dropped"), std::string::npos) << csv.out;
}

}  // namespace

namespace {

// feint anova --emmeans / --contrasts / --adjust: emmeans on the afex object (multivariate model,
// anova_emm_golden.R) through the tidy CSV; the tables in text, Markdown and LaTeX.
TEST(AnovaCli, EmmeansAndContrastsMatchEmmeansOnAfex) {
  TempDir dir;
  const auto p = dir.path() / "s.csv";
  std::string text = "participant,condition,iteration,error\n";
  {
    std::ifstream in(kGolden + "anova_data.csv");
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      const auto f = feint::io::split_csv_line(line);
      if (f[0] == "unbalanced_nonspherical")
        text += f[1] + "," + f[2] + "," + f[3] + "," + (f.size() > 4 ? f[4] : "") + "\n";
    }
  }
  write_text(p, text);
  std::map<std::string, double> g;
  {
    std::ifstream in(kGolden + "anova_emm_golden.csv");
    std::string line;
    while (std::getline(in, line)) {
      const auto f = feint::io::split_csv_line(line);
      if (f.size() == 4 && f[0] == "unbalanced_nonspherical") g[f[1] + "/" + f[2]] = std::stod(f[3]);
    }
  }
  const RunResult r = run_feint("anova " + shell_quote(p.string()) +
                                " --metric error --emmeans --contrasts simple --adjust holm --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::stringstream in(r.out);
  std::string line;
  std::getline(in, line);
  const auto header = feint::io::split_csv_line(line);
  std::map<std::string, std::size_t> col;
  for (std::size_t i = 0; i < header.size(); ++i) col.emplace(header[i], i);
  int means = 0, holm = 0;
  while (std::getline(in, line)) {
    const auto f = feint::io::split_csv_line(line);
    if (f[0] == "emmean" && f[col.at("term")] == "condition:iteration") {
      const std::string lv = f[col.at("level")];
      const std::string name = lv.substr(0, lv.find('|')) + "|X" + lv.substr(lv.find('|') + 1);
      EXPECT_NEAR(std::stod(f[col.at("estimate")]), g.at("cells.estimate/" + name), 1e-9) << name;
      EXPECT_NEAR(std::stod(f[col.at("std.error")]), g.at("cells.SE/" + name), 1e-9) << name;
      EXPECT_NEAR(std::stod(f[col.at("conf.low")]), g.at("cells.lower/" + name), 1e-9) << name;
      ++means;
    } else if (f[0] == "emm_contrast" && f[col.at("term")] == "pairwise ~ iteration | condition") {
      std::string c = f[col.at("contrast")];
      for (std::size_t k; (k = c.find("iteration")) != std::string::npos;) c.replace(k, 9, "X");
      const std::string name = c + "|" + f[col.at("group")];
      EXPECT_EQ(f[col.at("adjust")], "holm");
      EXPECT_NEAR(std::stod(f[col.at("p.adjusted")]), g.at("it_by_cond.holm.p/" + name),
                  1e-6 * std::max(1e-3, g.at("it_by_cond.holm.p/" + name)))
          << name;
      EXPECT_NEAR(std::stod(f[col.at("conf.high")]), g.at("it_by_cond.holm.upper/" + name), 1e-9);
      ++holm;
    }
  }
  EXPECT_EQ(means, 10);
  EXPECT_EQ(holm, 20);
  for (const std::string fmt : {"text", "markdown", "latex"}) {
    const RunResult t = run_feint("anova " + shell_quote(p.string()) +
                                  " --metric error --emmeans --contrasts poly --format " + fmt);
    ASSERT_EQ(t.exit_code, 0) << t.err;
    EXPECT_NE(t.out.find("estimated marginal means"), std::string::npos) << fmt;
    EXPECT_NE(t.out.find("(p adjustment: none)"), std::string::npos) << fmt;
  }
  EXPECT_EQ(run_feint("anova " + shell_quote(p.string()) + " --metric error --contrasts poly --adjust tukey")
                .exit_code,
            64);
  EXPECT_EQ(run_feint("anova " + shell_quote(p.string()) + " --metric error --adjust none").exit_code, 64);
}

}  // namespace

// The command line says what is wrong: `feint help`, unknown commands, R's spellings of
// --p-adjust, `-o` everywhere, one exit code for a condition the data do not have, --paired on a
// between-subjects design, and header-only inputs named in the message.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_helpers.hpp"

namespace fs = std::filesystem;
using feint::test::read_text;
using feint::test::run_feint;
using feint::test::RunResult;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {
const std::string kSmallScores = std::string(FEINT_TEST_DATA_DIR) + "/table/scores_small.csv";
const std::string kWideLikert = std::string(FEINT_TEST_DATA_DIR) + "/likert/wide.csv";
std::string q(const fs::path& p) { return shell_quote(p.string()); }
}  // namespace

TEST(CliUsage, HelpIsACommand) {
  RunResult r = run_feint("help");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Subcommands:"), std::string::npos) << r.out;
  r = run_feint("help table");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("--compare"), std::string::npos) << r.out;
}

TEST(CliUsage, AnUnknownCommandIsNamedWithTheCommandsThereAre) {
  const RunResult r = run_feint("tabel scores.csv");
  EXPECT_EQ(r.exit_code, 64);
  EXPECT_NE(r.err.find("unknown command 'tabel'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("table"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("analyze"), std::string::npos) << r.err;
  const RunResult h = run_feint("help tabel");
  EXPECT_EQ(h.exit_code, 64);
  EXPECT_NE(h.err.find("unknown command 'tabel'"), std::string::npos) << h.err;
}

TEST(CliUsage, PAdjustTakesRsSpellingsInAnyCase) {
  const std::string base = "table " + q(kSmallScores) + " --format csv --p-adjust ";
  const std::string holm = run_feint(base + "holm").out;
  ASSERT_FALSE(holm.empty());
  EXPECT_EQ(run_feint(base + "Holm").out, holm);
  EXPECT_EQ(run_feint(base + "HOLM").out, holm);
  const std::string bh = run_feint(base + "BH").out;
  ASSERT_FALSE(bh.empty());
  EXPECT_NE(bh, holm);
  EXPECT_EQ(run_feint(base + "bh").out, bh);
  EXPECT_EQ(run_feint(base + "fdr").out, bh);
  EXPECT_EQ(run_feint(base + "FDR").out, bh);
  EXPECT_EQ(run_feint("likert " + q(kWideLikert) + " --p-adjust Bonferroni").exit_code, 0);
  const RunResult bad = run_feint(base + "holmes");
  EXPECT_EQ(bad.exit_code, 64);
  EXPECT_NE(bad.err.find("--p-adjust 'holmes'"), std::string::npos) << bad.err;
}

TEST(CliUsage, SimulateStudyTakesDashO) {
  TempDir dir;
  const RunResult r =
      run_feint("simulate study -o " + q(dir / "s") + " --participants 2 --iterations 2");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "s" / "questionnaire.csv"));
}

TEST(CliUsage, AConditionTheDataDoNotHaveExits64InEveryCommand) {
  TempDir dir;
  // table, likert, and analyze on a study whose logs and questionnaire have adaptive and random.
  RunResult r = run_feint("table " + q(kSmallScores) + " --compare adaptive,fixed");
  EXPECT_EQ(r.exit_code, 64) << r.err;
  EXPECT_NE(r.err.find("fixed"), std::string::npos) << r.err;
  r = run_feint("table " + q(kSmallScores) + " --condition fixed");
  EXPECT_EQ(r.exit_code, 64) << r.err;
  r = run_feint("likert " + q(kWideLikert) + " --compare adaptive,fixed");
  EXPECT_EQ(r.exit_code, 64) << r.err;
  EXPECT_NE(r.err.find("fixed"), std::string::npos) << r.err;
  r = run_feint("likert " + q(kWideLikert) + " --condition fixed");
  EXPECT_EQ(r.exit_code, 64) << r.err;
  ASSERT_EQ(
      run_feint("simulate study -o " + q(dir / "s") + " --participants 2 --iterations 2").exit_code,
      0);
  r = run_feint("analyze " + q(dir / "s") + " -o " + q(dir / "out") + " --compare adaptive,fixed");
  EXPECT_EQ(r.exit_code, 64) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(CliUsage, PairedOnABetweenSubjectsDesignSaysWhatIsWrong) {
  TempDir dir;
  write_text(dir / "between.csv",
             "participant,condition,iteration,error,confusion\n"
             "P1,adaptive,1,0.5,0.9\nP2,adaptive,1,0.6,0.8\nP3,adaptive,1,0.4,0.7\n"
             "P4,random,1,0.5,0.9\nP5,random,1,0.7,0.6\nP6,random,1,0.3,0.8\n");
  const RunResult r =
      run_feint("table " + q(dir / "between.csv") + " --compare adaptive,random --paired");
  EXPECT_EQ(r.exit_code, 64) << r.out;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find("no participant occurs in both conditions adaptive and random"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("between-subjects"), std::string::npos) << r.err;
  // scores_small.csv has the same participants in both conditions: the paired test runs.
  EXPECT_EQ(run_feint("table " + q(kSmallScores) + " --compare adaptive,random --paired").exit_code,
            0);
}

TEST(CliUsage, AHeaderOnlyInputIsNamed) {
  TempDir dir;
  write_text(dir / "scores.csv", "participant,condition,iteration,error,confusion\n");
  RunResult r = run_feint("table " + q(dir / "scores.csv"));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("scores.csv"), std::string::npos) << r.err;
  write_text(dir / "q.csv", "participant,condition,trust\n");
  r = run_feint("likert " + q(dir / "q.csv"));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("q.csv"), std::string::npos) << r.err;
  // Without a final newline, and from standard input.
  write_text(dir / "q2.csv", "participant,condition,trust");
  r = run_feint("likert " + q(dir / "q2.csv"));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("q2.csv"), std::string::npos) << r.err;
  r = run_feint("likert -", std::string("participant,trust\n"));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("standard input"), std::string::npos) << r.err;
  write_text(dir / "long.csv", "participant,item,response\n");
  r = run_feint("likert " + q(dir / "long.csv"));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("long.csv"), std::string::npos) << r.err;
}

TEST(LatexOptions, LabelCaptionAndWideAreTheUsers) {
  RunResult r = run_feint("table " + q(kSmallScores) +
                          " --format latex --label tab:conf --caption 'Confusion, 20 rounds' "
                          "--latex-wide");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\\label{tab:conf}"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\\caption{Confusion, 20 rounds}"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\\begin{table*}[tp]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\\end{table*}"), std::string::npos) << r.out;
  // Default labels differ per table.
  r = run_feint("table " + q(kSmallScores) + " --format latex --compare adaptive,random");
  EXPECT_NE(r.out.find("\\label{tab:feint-table1-adaptive-vs-random}"), std::string::npos) << r.out;
  r = run_feint("table " + q(kSmallScores) + " --format latex --condition adaptive");
  EXPECT_NE(r.out.find("\\label{tab:feint-table1-adaptive}"), std::string::npos) << r.out;
  r = run_feint("likert " + q(kWideLikert) + " --format latex --label tab:q");
  EXPECT_NE(r.out.find("\\label{tab:q}"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\\label{tab:q-responses}"), std::string::npos) << r.out;
  r = run_feint("likert " + q(kWideLikert) + " --format latex --compare adaptive,random");
  EXPECT_NE(r.out.find("\\label{tab:feint-likert-adaptive-vs-random}"), std::string::npos);
  // A label that would break \label.
  r = run_feint("table " + q(kSmallScores) + " --format latex --label 'tab:a b'");
  EXPECT_EQ(r.exit_code, 64);
  EXPECT_NE(r.err.find("--label"), std::string::npos) << r.err;
}

// anova, model and power (the model commands) take the same options as table and likert.
TEST(LatexOptions, AnovaModelAndPowerTakeLabelCaptionAndWide) {
  const fs::path golden = fs::path(FEINT_SOURCE_DIR) / "tests" / "golden" / "models";
  // Two metrics (error and a made-up confusion), as the commands' defaults ask for.
  TempDir dir;
  std::string two_metrics;
  {
    const std::string in = read_text(golden / "lmm_balanced5.csv");
    int row = 0;
    for (std::size_t b = 0, e; (e = in.find('\n', b)) != std::string::npos; b = e + 1, ++row) {
      two_metrics +=
          in.substr(b, e - b) +
          (row == 0 ? ",confusion\n" : "," + std::to_string((row * 37 % 101) / 101.0) + "\n");
    }
  }
  write_text(dir / "scores.csv", two_metrics);
  const std::string scores = q(dir / "scores.csv");
  const std::string opts = " --format latex --label tab:mine --caption 'My caption' --latex-wide";
  const auto expect_users = [](const RunResult& r, const std::string& what) {
    ASSERT_EQ(r.exit_code, 0) << what << ": " << r.err;
    EXPECT_NE(r.out.find("\\label{tab:mine}"), std::string::npos) << what << r.out;
    EXPECT_NE(r.out.find("\\caption{My caption}"), std::string::npos) << what << r.out;
    EXPECT_NE(r.out.find("\\begin{table*}[tp]"), std::string::npos) << what << r.out;
    EXPECT_EQ(r.out.find("\\begin{table}"), std::string::npos) << what << r.out;
  };
  expect_users(run_feint("anova " + scores + opts), "anova");
  expect_users(run_feint("power t-test --d 0.5 --power 0.8" + opts), "power t-test");
  const std::string sim =
      "power simulate --means-a 0.5,0.4 --means-b 0.5,0.5 --sd-residual 0.1 --studies 20";
  expect_users(run_feint(sim + opts), "power simulate");
  // The model's first ANOVA gets the label and caption; its other tables derive their labels.
  RunResult r = run_feint("model " + scores + " --metric error" + opts);
  expect_users(r, "model");
  EXPECT_NE(r.out.find("\\label{tab:mine-random-error}"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\\label{tab:mine-contrasts-error}"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("\\caption{My caption}"), r.out.rfind("\\caption{My caption}"));
  // Default labels in the scheme of table and likert.
  r = run_feint("anova " + scores + " --format latex");
  EXPECT_NE(r.out.find("\\label{tab:feint-anova}"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\\begin{table}[htbp]"), std::string::npos) << r.out;
  r = run_feint("power t-test --d 0.5 --power 0.8 --format latex");
  EXPECT_NE(r.out.find("\\label{tab:feint-power}"), std::string::npos) << r.out;
  r = run_feint(sim + " --format latex");
  EXPECT_NE(r.out.find("\\label{tab:feint-power-simulated}"), std::string::npos) << r.out;
  r = run_feint("model " + scores + " --format latex");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* label : {"tab:feint-model-anova-error", "tab:feint-model-random-error",
                            "tab:feint-model-contrasts-error", "tab:feint-model-anova-confusion"}) {
    EXPECT_NE(r.out.find(std::string("\\label{") + label + "}"), std::string::npos) << label;
  }
  // A given label replaces tab:feint-model in the second metric's labels too.
  r = run_feint("model " + scores + " --format latex --label tab:m");
  EXPECT_NE(r.out.find("\\label{tab:m-anova-confusion}"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("\\label{tab:m-anova-error}"), std::string::npos) << r.out;
  r = run_feint("model " + q(golden / "lmm_exposure.csv") +
                " --metric error --exposure --format latex");
  EXPECT_NE(r.out.find("\\label{tab:feint-model-slopes-error}"), std::string::npos) << r.out;
  r = run_feint("anova " + scores + " --format latex --label 'tab:a b'");
  EXPECT_EQ(r.exit_code, 64);
  EXPECT_NE(r.err.find("--label"), std::string::npos) << r.err;
}

TEST(LatexOptions, NotesNameFilesNotFolders) {
  const RunResult r = run_feint("table " + q(kSmallScores) + " --format latex");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Source: scores\\_small.csv."), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find(FEINT_TEST_DATA_DIR), std::string::npos) << r.out;
}

TEST(LatexOptions, ThePapersAnalysisIsNamedOnlyWithPaper) {
  RunResult r = run_feint("likert " + q(kWideLikert));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("paper's analysis"), std::string::npos) << r.out;
  r = run_feint("likert " + q(kWideLikert) + " --paper");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(the paper's analysis)"), std::string::npos) << r.out;
}

// Input files are sacred: no command writes over one of its inputs, whatever name the
// output is given (the same path, a symbolic link, a hard link), and `feint analyze` replaces its
// output folder as one unit, never mixing runs and never touching the study.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <sstream>
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

// A study: two conditions x 4 participants x 2 iterations, optionally with a questionnaire.
void make_study(const fs::path& dir, bool with_questionnaire) {
  std::ostringstream logs;
  logs << "participant,condition,iteration,target,t,pad,pad_speed\n";
  const char* conditions[] = {"adaptive", "random"};
  for (int c = 0; c < 2; ++c) {
    for (int p = 1; p <= 4; ++p) {
      for (int it = 1; it <= 2; ++it) {
        double pad = 0.5;
        for (int k = 0; k <= 10; ++k) {
          logs << "P" << c << p << "," << conditions[c] << "," << it << ",right," << k * 0.1 << ","
               << pad << ",0.5\n";
          pad = std::min(1.0, std::max(0.0, pad + (k < p + c ? -0.04 : 0.05)));
        }
      }
    }
  }
  write_text(dir / "logs" / "session.csv", logs.str());
  if (with_questionnaire) {
    std::ostringstream qs;
    qs << "participant,condition,trust,fun\n";
    for (int c = 0; c < 2; ++c) {
      for (int p = 1; p <= 4; ++p) {
        qs << "P" << c << p << "," << conditions[c] << "," << (p + c) % 7 + 1 << "," << 7 - p
           << "\n";
      }
    }
    write_text(dir / "questionnaire.csv", qs.str());
  } else {
    fs::remove(dir / "questionnaire.csv");
  }
}

}  // namespace

TEST(InputsAreSacred, TableRefusesToWriteOverItsInputByAnyName) {
  TempDir dir;
  const auto input = dir / "scores.csv";
  const std::string original = read_text(kSmallScores);
  write_text(input, original);
  fs::create_symlink(input, dir / "link.csv");
  fs::create_hard_link(input, dir / "hard.csv");
  for (const auto& out : {input, dir / "link.csv", dir / "hard.csv", dir / "." / "scores.csv"}) {
    const RunResult r = run_feint("table " + q(input) + " -o " + q(out));
    EXPECT_EQ(r.exit_code, 64) << out << ": " << r.err;
    EXPECT_NE(r.err.find("also an input"), std::string::npos) << r.err;
    EXPECT_EQ(read_text(input), original) << out;
  }
  EXPECT_TRUE(fs::is_symlink(dir / "link.csv"));
  // The scores' sidecar, read for the note, is an input too.
  write_text(dir / "scores.csv.meta.json", "{\"confusion_normalisation\": \"raw\"}\n");
  const RunResult s =
      run_feint("table " + q(input) + " --format json -o " + q(dir / "scores.csv.meta.json"));
  EXPECT_EQ(s.exit_code, 64) << s.err;
  EXPECT_EQ(read_text(dir / "scores.csv.meta.json"), "{\"confusion_normalisation\": \"raw\"}\n");
  // Another output name is fine.
  EXPECT_EQ(run_feint("table " + q(input) + " -o " + q(dir / "t.txt")).exit_code, 0);
}

TEST(InputsAreSacred, LikertRefusesToWriteOverItsInputOrWithItsSummary) {
  TempDir dir;
  const auto input = dir / "q.csv";
  const std::string original = read_text(kWideLikert);
  write_text(input, original);
  fs::create_hard_link(input, dir / "hard.csv");
  for (const std::string& args :
       {"-o " + q(input), "-o " + q(dir / "hard.csv"), "-o - --summary " + q(input),
        "-o " + q(dir / "out.txt") + " --summary " + q(dir / "hard.csv")}) {
    const RunResult r = run_feint("likert " + q(input) + " " + args);
    EXPECT_EQ(r.exit_code, 64) << args << ": " << r.err;
    EXPECT_NE(r.err.find("also an input"), std::string::npos) << r.err;
    EXPECT_EQ(read_text(input), original) << args;
  }
  EXPECT_FALSE(fs::exists(dir / "out.txt"));
}

TEST(InputsAreSacred, AnalyzeRefusesAnOutputFolderInOrAroundItsInputs) {
  TempDir dir;
  const auto study = dir / "study";
  make_study(study, true);
  const std::string logs_before = read_text(study / "logs" / "session.csv");
  for (const auto& out : {study / "logs", study / "logs" / "out", study, dir.path()}) {
    const RunResult r = run_feint("analyze " + q(study) + " -o " + q(out));
    EXPECT_EQ(r.exit_code, 64) << out << ": " << r.err;
    EXPECT_NE(r.err.find("input"), std::string::npos) << r.err;
  }
  EXPECT_EQ(read_text(study / "logs" / "session.csv"), logs_before);
  EXPECT_FALSE(fs::exists(study / "logs" / "out"));
  EXPECT_FALSE(fs::exists(study / "scores.csv"));
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(study / "logs")) n += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(n, 1u);
  // A folder beside the logs, inside the study, is fine.
  const RunResult ok = run_feint("analyze " + q(study) + " -o " + q(study / "results"));
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST(InputsAreSacred, AnalyzeRerunRemovesTheFilesOfThePreviousRunThatItDoesNotWrite) {
  TempDir dir;
  const auto study = dir / "study";
  const auto out = dir / "out";
  make_study(study, true);
  RunResult r = run_feint("analyze " + q(study) + " -o " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(out / "likert.txt"));
  ASSERT_TRUE(fs::exists(out / ".feint-analyze.json"));
  EXPECT_NE(read_text(out / ".feint-analyze.json").find("\"likert.txt\""), std::string::npos);

  make_study(study, false);  // the new study has no questionnaire
  r = run_feint("analyze " + q(study) + " -o " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "table1.txt"));
  for (const auto& e : fs::directory_iterator(out)) {
    EXPECT_EQ(e.path().filename().string().rfind("likert", 0), std::string::npos)
        << "stale " << e.path();
  }
  EXPECT_EQ(read_text(out / ".feint-analyze.json").find("likert"), std::string::npos);
  // No staging folder is left beside the output.
  for (const auto& e : fs::directory_iterator(dir.path())) {
    EXPECT_EQ(e.path().filename().string().find("feint-staging"), std::string::npos) << e.path();
  }
}

TEST(InputsAreSacred, AnalyzeThatFailsLeavesTheOutputFolderAsItWas) {
  TempDir dir;
  const auto study = dir / "study";
  const auto out = dir / "out";
  make_study(study, true);
  ASSERT_EQ(run_feint("analyze " + q(study) + " -o " + q(out)).exit_code, 0);
  const std::string table_before = read_text(out / "table1.txt");
  const std::string likert_before = read_text(out / "likert.txt");
  // The questionnaire is now invalid: scoring and Table 1 would succeed, the questionnaire fails.
  write_text(study / "questionnaire.csv", "participant,condition,trust\nP01,adaptive,99\n");
  write_text(
      study / "logs" / "session2.csv",
      "participant,condition,iteration,target,t,pad,pad_speed\nP99,adaptive,1,left,0,0.5,0.5\n"
      "P99,adaptive,1,left,1,0.2,0.5\n");
  const RunResult r = run_feint("analyze " + q(study) + " -o " + q(out));
  EXPECT_EQ(r.exit_code, 65) << r.err;
  EXPECT_EQ(read_text(out / "table1.txt"), table_before);
  EXPECT_EQ(read_text(out / "likert.txt"), likert_before);
  for (const auto& e : fs::directory_iterator(dir.path())) {
    EXPECT_EQ(e.path().filename().string().find("feint-staging"), std::string::npos) << e.path();
  }
}

TEST(InputsAreSacred, AnalyzeRefusesAFolderHoldingFilesItDidNotWrite) {
  TempDir dir;
  const auto study = dir / "study";
  make_study(study, false);
  // A folder of the user's own files.
  const auto mine = dir / "mine";
  write_text(mine / "notes.txt", "my notes\n");
  RunResult r = run_feint("analyze " + q(study) + " -o " + q(mine));
  EXPECT_EQ(r.exit_code, 64) << r.err;
  EXPECT_NE(r.err.find("notes.txt"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(mine / "notes.txt"), "my notes\n");
  EXPECT_FALSE(fs::exists(mine / "scores.csv"));
  // A file added to a feint output folder is not deleted by the next run either.
  const auto out = dir / "out";
  ASSERT_EQ(run_feint("analyze " + q(study) + " -o " + q(out)).exit_code, 0);
  write_text(out / "draft.tex", "keep me\n");
  r = run_feint("analyze " + q(study) + " -o " + q(out));
  EXPECT_EQ(r.exit_code, 64) << r.err;
  EXPECT_NE(r.err.find("draft.tex"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(out / "draft.tex"), "keep me\n");
  // A folder written by a feint analyze from before the manifest is recognised by its names.
  const auto legacy = dir / "legacy";
  write_text(legacy / "scores.csv", "old\n");
  write_text(legacy / "likert.txt", "old\n");
  r = run_feint("analyze " + q(study) + " -o " + q(legacy));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(legacy / "likert.txt"));
  // An empty folder is fine.
  fs::create_directories(dir / "empty");
  EXPECT_EQ(run_feint("analyze " + q(study) + " -o " + q(dir / "empty")).exit_code, 0);
}

TEST(InputsAreSacred, AnalyzeRecordsTheFinalScoresPathInTheSidecar) {
  TempDir dir;
  const auto study = dir / "study";
  make_study(study, false);
  const auto out = dir / "out";
  ASSERT_EQ(run_feint("analyze " + q(study) + " -o " + q(out)).exit_code, 0);
  const std::string sidecar = read_text(out / "scores.csv.meta.json");
  EXPECT_EQ(sidecar.find("feint-staging"), std::string::npos) << sidecar;
  // The scores file is named relative to the sidecar's folder (the output folder): true wherever
  // the folder is moved, and no absolute path.
  EXPECT_NE(sidecar.find("\"output\": \"scores.csv\""), std::string::npos) << sidecar;
  EXPECT_EQ(sidecar.find(out.string()), std::string::npos) << sidecar;
}

// The commands added for the observer model never write over what they read: a
// pilot, an observer-parameter file, the logs of a fit, a path file.
TEST(InputsAreSacred, ObserverCommandsRefuseToWriteOverTheirInputs) {
  feint::test::TempDir dir;
  const auto pilot = (dir.path() / "pilot.csv").string();
  const std::string scores = "participant,condition,iteration,error\nP1,adaptive,1,0.5\n";
  feint::test::write_text(pilot, scores);
  const auto params = (dir.path() / "observer.txt").string();
  feint::test::write_text(params, "beta = 0.3\n");
  const auto path = (dir.path() / "path.csv").string();
  feint::test::write_text(path, "t,x,y\n0,0,0\n1,0.5,1\n2,1,2\n");
  const auto logs = dir.path() / "logs";
  std::filesystem::create_directories(logs);
  const auto log = (logs / "p1.csv").string();
  const std::string log_text =
      "participant,condition,iteration,strategy,variant,target,t,pad\nP1,adaptive,1,optimal,main,right,0,0.5\n";
  feint::test::write_text(log, log_text);
  for (const std::string& cmd :
       {"power observer --pilot " + shell_quote(pilot) + " -o " + shell_quote(pilot),
        "power observer --observer-file " + shell_quote(params) + " -o " + shell_quote(params),
        "observer fit " + shell_quote(logs.string()) + " -o " + shell_quote(log),
        "simulate trajectories --path " + shell_quote(path) + " -o " + shell_quote(path)}) {
    const RunResult r = run_feint(cmd);
    EXPECT_EQ(r.exit_code, 64) << cmd << "\n" << r.err;
    EXPECT_NE(r.err.find("never overwrites its inputs"), std::string::npos) << cmd << "\n" << r.err;
  }
  EXPECT_EQ(read_text(pilot), scores);
  EXPECT_EQ(read_text(params), "beta = 0.3\n");
  EXPECT_EQ(read_text(path), "t,x,y\n0,0,0\n1,0.5,1\n2,1,2\n");
  EXPECT_EQ(read_text(log), log_text);
}

// `feint score` on real-lab quirks (docs/scoring.md "Reading real lab files").
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli/cli_helpers.hpp"

using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

const std::string kHeader = "participant,condition,iteration,target,t,pad,pad_speed\n";

// metrics.md example E (error 25/54, confusion 287/1440), times multiplied by `unit`.
std::string example_e(const std::string& key, int unit) {
  const int t[] = {0, 300, 1000, 2000, 4000};
  const char* mu[] = {"0.5", "0.6", "0.4", "0.4", "0.9"};
  std::string s;
  for (int i = 0; i < 5; ++i) {
    s += key + ",right," + std::to_string(t[i] * unit / 1000) +
         (unit == 1 ? "." + std::to_string(t[i] % 1000 / 100) : "") + "," + mu[i] + ",1\n";
  }
  return s;
}

}  // namespace

TEST(ScoreTrustCli, TimeUnitMsConvertsAndASecondsReadingOfMsWarnsOnce) {
  TempDir d;
  const auto log = (d.path() / "ms.csv").string();
  write_text(log, kHeader + example_e("P1,A,1", 1000) + example_e("P2,A,1", 1000));
  const auto out = (d.path() / "s.csv").string();
  auto r = run_feint("score " + shell_quote(log) + " -o " + shell_quote(out) + " --time-unit ms");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  EXPECT_NE(read_text(out).find(",5,4,0.46296296296296"), std::string::npos) << read_text(out);
  EXPECT_NE(read_text(out + ".meta.json").find("\"time_unit\": \"ms\""), std::string::npos);

  // Read as seconds, these 4 s trials last 4000 s: they cannot be seconds: exit 65,
  // no table, the message names the file, line, column and the option.
  const auto refused = (d.path() / "refused.csv").string();
  r = run_feint("score " + shell_quote(log) + " -o " + shell_quote(refused));
  EXPECT_EQ(r.exit_code, 65) << r.err;
  EXPECT_NE(r.err.find("ms.csv:2: column 't': the median trial lasts 4000 s (2 trials; the "
                       "longest, trial P1/A/1, 4000 s): these times cannot be seconds"),
            std::string::npos) << r.err;
  EXPECT_NE(r.err.find("give --time-unit ms"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(refused));

  // 0.6 s trials logged in ms read as 600 s: implausible, not impossible: one warning.
  const auto slow = (d.path() / "slow.csv").string();
  write_text(slow, kHeader + example_e("P1,A,1", 150) + example_e("P2,A,1", 150));
  r = run_feint("score " + shell_quote(slow) + " -o " + shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto first = r.err.find("feint: warning: the median trial lasts 600 s (2 trials, longest "
                                "600 s): implausible for seconds");
  EXPECT_NE(first, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("feint: warning:", first + 1), std::string::npos) << "warned twice: " << r.err;
  EXPECT_NE(read_text(out + ".meta.json").find("\"time_unit\": \"s\""), std::string::npos);
  EXPECT_NE(read_text(out + ".meta.json").find("\"warnings\": [\"the median trial lasts 600 s"),
            std::string::npos);

  EXPECT_EQ(run_feint("score " + shell_quote(log) + " -o " + shell_quote(out) + " --time-unit h")
                .exit_code, 64);
  EXPECT_NE(run_feint("analyze --help").out.find("--time-unit"), std::string::npos);
}

TEST(ScoreTrustCli, ANonFiniteScoreIsExit65NeverWritten) {
  TempDir d;
  const auto log = (d.path() / "tiny.csv").string();
  write_text(log, kHeader + "P1,A,1,right,0,0.5,1\nP1,A,1,right,1e-310,1,1\n"
                            "P1,A,1,right,2e-310,0.5,1\n");
  const auto out = (d.path() / "s.csv").string();
  const auto r = run_feint("score " + shell_quote(log) + " -o " + shell_quote(out) +
                           " --confusion-norm raw");
  EXPECT_EQ(r.exit_code, 65) << r.err;
  EXPECT_NE(r.err.find(log + ":2: confusion is not a finite number (inf;"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(ScoreTrustCli, SignsAndUnderflowReadAsStrtod) {
  TempDir d;
  const auto log = (d.path() / "l.csv").string();
  write_text(log, kHeader + "P1,A,1,right,0,0.5,1\nP1,A,1,right,1,+-0.5,1\n");
  auto r = run_feint("score " + shell_quote(log) + " -o -");
  EXPECT_EQ(r.exit_code, 65) << r.out;
  EXPECT_NE(r.err.find("column 'pad': '+-0.5' is not a number"), std::string::npos) << r.err;
  write_text(log, kHeader + "P1,A,1,right,0,9e-325,1\nP1,A,1,right,1,0.5,1\n");
  r = run_feint("score " + shell_quote(log) + " -o -");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(ScoreTrustCli, HeaderOnlyInputNamesTheFile) {
  TempDir d;
  const auto log = (d.path() / "only_header.csv").string();
  write_text(log, kHeader);
  const auto r = run_feint("score " + shell_quote(log) + " -o -");
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find(log + ": no data rows"), std::string::npos) << r.err;
}

// Two `feint score` processes writing the same output at once: the scores and the sidecar left
// behind are always from the same run (they are committed as one unit under a folder lock).
TEST(ScoreTrustCli, ConcurrentProcessesLeaveAMatchingPair) {
  TempDir d;
  const auto a = (d.path() / "a.csv").string(), b = (d.path() / "b.csv").string();
  write_text(a, kHeader + example_e("PA,A,1", 1));
  write_text(b, kHeader + example_e("PB,A,1", 1) + example_e("PB,A,2", 1));
  const auto out = (d.path() / "s.csv").string();
  const std::string exe = shell_quote(FEINT_EXE);
  const std::string both = exe + " score " + shell_quote(a) + " -o " + shell_quote(out) +
                           " 2>/dev/null & " + exe + " score " + shell_quote(b) + " -o " +
                           shell_quote(out) + " 2>/dev/null & wait";
  for (int round = 0; round < 15; ++round) {
    ASSERT_EQ(std::system(both.c_str()), 0);
    const std::string scores = read_text(out), sidecar = read_text(out + ".meta.json");
    const bool is_a = scores.find("\nPA,") != std::string::npos;
    ASSERT_NE(sidecar.find(is_a ? "a.csv" : "b.csv"), std::string::npos) << "round " << round;
    ASSERT_EQ(sidecar.find(is_a ? "b.csv" : "a.csv"), std::string::npos) << "round " << round;
  }
}

// `feint score` on other labs' exports (tests/data/labs/), read right with
// the options docs/formats.md names, or refused (exit 65/64) with a message naming the option.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_helpers.hpp"

using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;

namespace {

std::string lab(const std::string& name) {
  return shell_quote(std::string(FEINT_TEST_DATA_DIR) + "/labs/" + name);
}

// The scores table's rows without the header.
std::string rows_of(const std::string& path) {
  const std::string text = read_text(path);
  return text.substr(text.find('\n') + 1);
}

}  // namespace

TEST(ScoreOtherLabsCli, EuropeanCsvDetectedOrDeclaredGivesTheSameScores) {
  TempDir d;
  const auto a = (d.path() / "a.csv").string(), b = (d.path() / "b.csv").string();
  auto r = run_feint("score " + lab("european.csv") + " -o " + shell_quote(a));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("feint: warning: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("numbers read with a decimal comma"), std::string::npos) << r.err;
  r = run_feint("score " + lab("european.csv") + " --delimiter ';' --decimal , -o " + shell_quote(b));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("decimal comma"), std::string::npos) << r.err;
  EXPECT_EQ(rows_of(a), rows_of(b));
  // 4 samples, 4.3 s: the decimal comma was read as a decimal mark.
  EXPECT_NE(rows_of(a).find("P01,adaptive,1,,,1,4,4.3,"), std::string::npos) << rows_of(a);
  EXPECT_EQ(run_feint("score " + lab("european.csv") + " --delimiter , --decimal , -o " +
                      shell_quote(b)).exit_code, 64);
  EXPECT_EQ(run_feint("score " + lab("european.csv") + " --decimal x -o " + shell_quote(b)).exit_code, 64);
}

TEST(ScoreOtherLabsCli, HeaderlessMatlabFile) {
  TempDir d;
  const auto out = (d.path() / "s.csv").string();
  auto r = run_feint("score " + lab("matlab_noheader.csv") + " --pad-speed 1 -o " + shell_quote(out));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("matlab_noheader.csv:1: no column 'participant' (required)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--no-header --columns participant,iteration,target,t,pad"), std::string::npos) << r.err;
  r = run_feint("score " + lab("matlab_noheader.csv") +
                " --pad-speed 1 --no-header --columns participant,iteration,target,t,pad -o " +
                shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto named = rows_of(out);
  EXPECT_NE(named.find("7,,1,,,1,3,0.066,"), std::string::npos) << named;
  r = run_feint("score " + lab("matlab_noheader.csv") + " --pad-speed 1 --no-header --map "
                "participant=1 --map iteration=2 --map target=3 --map t=4 --map pad=5 -o " +
                shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(rows_of(out), named);
  EXPECT_EQ(run_feint("score " + lab("matlab_noheader.csv") + " --no-header -o " + shell_quote(out)).exit_code, 64);
  EXPECT_EQ(run_feint("score " + lab("european.csv") + " --columns a,b -o " + shell_quote(out)).exit_code, 64);
}

TEST(ScoreOtherLabsCli, JsPsychSamplesColumn) {
  TempDir d;
  const auto out = (d.path() / "s.csv").string();
  const std::string maps = " --map participant=subject --map iteration=trial_index --pad-speed 1";
  auto r = run_feint("score " + lab("jspsych.csv") + maps + " -o " + shell_quote(out));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("--samples-column COLUMN"), std::string::npos) << r.err;
  r = run_feint("score " + lab("jspsych.csv") + maps + " --samples-column pad_trace -o " + shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(rows_of(out).find("s01,adaptive,1,,,1,3,1.25,"), std::string::npos) << rows_of(out);
  EXPECT_NE(rows_of(out).find("s01,adaptive,2,,,0,3,0.9,"), std::string::npos) << rows_of(out);
}

TEST(ScoreOtherLabsCli, NanPaddingIterationBaseAndIdsFromThePath) {
  TempDir d;
  const auto out = (d.path() / "s.csv").string();
  auto r = run_feint("score " + lab("fixed_length_nan.csv") + " --pad-speed 1 -o " + shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("dropped 3 trailing row(s) without t and pad"), std::string::npos) << r.err;
  EXPECT_NE(rows_of(out).find("P01,,1,,,1,3,1,"), std::string::npos) << rows_of(out);
  EXPECT_NE(read_text(out + ".meta.json").find("dropped 3 trailing row(s)"), std::string::npos);

  r = run_feint("score " + lab("psychopy") + " --pad-speed 1 -o " + shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("iterations start at 0"), std::string::npos) << r.err;
  EXPECT_NE(rows_of(out).find("P03,,0,"), std::string::npos) << rows_of(out);
  r = run_feint("score " + lab("psychopy") + " --pad-speed 1 --iteration-base 0 -o " + shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("iterations start at 0"), std::string::npos) << r.err;
  EXPECT_NE(rows_of(out).find("P03,,1,"), std::string::npos) << rows_of(out);
  EXPECT_NE(rows_of(out).find("P03,,2,"), std::string::npos) << rows_of(out);
  EXPECT_EQ(run_feint("score " + lab("psychopy") + " --iteration-base 2 -o " + shell_quote(out)).exit_code, 64);

  r = run_feint("score " + lab("by-folder") + " --pad-speed 1 -o " + shell_quote(out));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("--participant-from-path filename"), std::string::npos) << r.err;
  r = run_feint("score " + lab("by-folder") + " --pad-speed 1 --participant-from-path dirname -o " +
                shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(rows_of(out).find("sub-07,,1,"), std::string::npos) << rows_of(out);
  EXPECT_EQ(run_feint("score " + lab("by-folder") + " --participant-from-path 'sub-(' -o " +
                      shell_quote(out)).exit_code, 64);
}

TEST(ScoreOtherLabsCli, CaseConditionsAndTheMillisecondMessage) {
  TempDir d;
  const auto out = (d.path() / "s.csv").string();
  // `T` is a ms timer: `t` (exact case) is taken and the trial lasts 4.301 s, not 4,267 s.
  auto r = run_feint("score " + lab("timer_T_and_t.csv") + " --pad-speed 1 --map t=t -o " + shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(rows_of(out).find("P01,,1,,,1,3,4.301,"), std::string::npos) << rows_of(out);

  r = run_feint("score " + lab("group_column.csv") + " --pad-speed 1 -o " + shell_quote(out));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("column 'group' (column 2) looks like the condition"), std::string::npos) << r.err;
  r = run_feint("score " + lab("group_column.csv") + " --pad-speed 1 --map condition=group -o " + shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(rows_of(out).find("P02,random,1,"), std::string::npos) << rows_of(out);
  r = run_feint("score " + lab("group_column.csv") + " --pad-speed 1 --single-condition -o " + shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(rows_of(out).find("P02,,1,"), std::string::npos) << rows_of(out);

  const auto bad = (d.path() / "ms_bad.csv").string();
  feint::test::write_text(bad, "participant,iteration,target,t,pad\nP1,1,left,0,0.5\nP1,1,left,1e,0.5\n");
  r = run_feint("score " + shell_quote(bad) + " --pad-speed 1 --time-unit ms -o " + shell_quote(out));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("ms_bad.csv:3: column 't': '1e' is not a number (expected a time in milliseconds"),
            std::string::npos) << r.err;
}

// The progress line of `feint score`: drawn on stderr when it is a terminal (after the first
// second), never when it is not. `script` (util-linux, Essential in Debian) gives the
// process a pseudo-terminal.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "cli/cli_helpers.hpp"

using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

std::string trial_rows(int iteration) {
  std::string rows;
  for (int k = 0; k <= 10; ++k) {
    rows += "P01,adaptive," + std::to_string(iteration) + ",right," + std::to_string(k) + ",0.5\n";
  }
  return rows;
}

}  // namespace

TEST(ScoreProgress, IsDrawnOnATerminalAndNeverOtherwise) {
  if (std::system("script -qec true /dev/null >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "no `script` command or no pseudo-terminal here: progress line not checked";
  }
  TempDir dir;
  write_text(dir / "first.csv",
             "participant,condition,iteration,target,t,pad\n" + trial_rows(1) + trial_rows(2));
  write_text(dir / "rest.csv", trial_rows(3) + trial_rows(4));
  // The input arrives in two parts 2.5 s apart, so scoring outlasts the first second even when
  // feint itself takes a second to start (a sanitizer build on a busy machine: with 1.3 s, the
  // second part came 0.7 s after the progress line's clock started and nothing was drawn).
  const std::string feed = "{ cat " + shell_quote((dir / "first.csv").string()) +
                           "; sleep 2.5; cat " + shell_quote((dir / "rest.csv").string()) + "; }";
  const std::string pipeline = feed + " | " + shell_quote(FEINT_EXE) +
                               " score - --pad-speed 1 -o " +
                               shell_quote((dir / "scores.csv").string());
  const std::string cmd = "script -qec " + shell_quote(pipeline) + " /dev/null > " +
                          shell_quote((dir / "tty.txt").string()) + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string tty = read_text(dir / "tty.txt");
  EXPECT_NE(tty.find("M rows/s"), std::string::npos) << tty;
  EXPECT_NE(tty.find("feint score: 44 rows read"), std::string::npos) << tty;

  // Not a terminal: only the summary line.
  const auto r = run_feint("score - --pad-speed 1 -o " + shell_quote((dir / "s2.csv").string()),
                           read_text(dir / "first.csv") + read_text(dir / "rest.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("M rows/s"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("44 rows read"), std::string::npos) << r.err;
}

// End-to-end tests of `feint observer fit` on logs of K targets and a pointer (docs/observer.md,
// "Fitting the observer to pointer traces (K targets)"): the shipped demo of three targets placed
// per round, and the logs and options it refuses.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>

#include "cli_helpers.hpp"

using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

const std::string kDemo = std::string(FEINT_SOURCE_DIR) + "/data/demo-k3/logs";

const char* kHeader =
    "participant,condition,iteration,strategy,variant,target,t,belief_x,belief_y,start_x,start_y,target0_x,"
    "target0_y,target1_x,target1_y,target2_x,target2_y,robot_x,robot_y\n";

/// One trial of a pointer log: the robot straight from (0, 0) to target 2 at (2, 4) at ~1 m/s, the
/// pointer drifting toward it; `samples` rows.
std::string trial_rows(const std::string& participant, int iteration, int samples) {
  std::string rows;
  for (int i = 0; i < samples; ++i) {
    const double f = static_cast<double>(i) / std::max(1, samples - 1);
    rows += participant + ",c," + std::to_string(iteration) + ",optimal,main,2," + std::to_string(0.5 * i) + "," +
            std::to_string(0.3 + 1.5 * f) + "," + std::to_string(4.2 - 0.1 * f) + ",0,0,-2,4,0,4,2,4," +
            std::to_string(2 * f) + "," + std::to_string(4 * f) + "\n";
  }
  return rows;
}

/// The pooled fits' (unit, beta, tau) of the text output, e.g. "adaptive   adaptive  240 ...".
std::smatch pooled_row(const std::string& out, const std::string& unit) {
  std::smatch m;
  const std::regex row("\n" + unit + R"( +\S+ +\d+ +\d+ +([0-9.]+) \[[<=]*([0-9.]+), ([0-9.]+)\S*\] +([0-9.]+) \[[<=]*([0-9.]+), ([0-9.]+)\S*\] +([0-9.]+) +([0-9.-]+))");
  std::regex_search(out, m, row);
  return m;
}

}  // namespace

// The shipped demo (24 participants, 20 rounds, three targets placed per round): the K-goal model
// is fitted with no flag, the output says so, and the estimates lie where the simulated people put
// them (beta 0.3 /m in the simulation; tau also holds the pointer's lag: decisions every 0.2 s, a
// pointer of bounded speed).
TEST(ObserverFitPointerCli, FitsTheDemoOfThreeTargetsWithNoFlag) {
  const auto r = run_feint("observer fit " + shell_quote(kDemo));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("fitted to 480 pointer trial(s) (robot path from the logs' robot_x, robot_y); K-goal observer "
                       "over 3 targets (targets placed per round, 480 layouts)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("sigma in layout scales"), std::string::npos);
  EXPECT_NE(r.out.find("Model-human agreement (model mean m(t)"), std::string::npos);
  EXPECT_NE(r.out.find("\nP24 "), std::string::npos);
  EXPECT_NE(r.out.find("Conditions compared on the participants' fits (adaptive against random"), std::string::npos);
  for (const char* unit : {"adaptive", "random"}) {
    const auto m = pooled_row(r.out, unit);
    ASSERT_FALSE(m.empty()) << unit << "\n" << r.out;
    const double beta = std::stod(m[1]), tau = std::stod(m[4]), sigma = std::stod(m[7]), phi = std::stod(m[8]);
    EXPECT_GT(beta, 0.1) << unit;
    EXPECT_LT(beta, 1.0) << unit;
    EXPECT_LT(std::stod(m[2]), beta);
    EXPECT_GT(std::stod(m[3]), beta);
    EXPECT_GT(tau, 0.1) << unit;
    EXPECT_LT(tau, 1.5) << unit;
    EXPECT_GT(sigma, 0.0);
    EXPECT_LT(sigma, 0.1);
    EXPECT_GT(phi, 0.5);
    EXPECT_LE(phi, 1.0);
  }
  const auto j = run_feint("observer fit " + shell_quote(kDemo) + " -f json");
  ASSERT_EQ(j.exit_code, 0) << j.err;
  EXPECT_NE(j.out.find("\"model\": \"pointer\""), std::string::npos) << j.out.substr(0, 400);
  EXPECT_NE(j.out.find("\"targets\": {\"min\": 3, \"max\": 3}, \"layouts\": 480, \"sigma.unit\": \"layout scales\""),
            std::string::npos)
      << j.out.substr(0, 400);
}

TEST(ObserverFitPointerCli, PadOptionsAreUsageErrors) {
  for (const char* option : {"--fit-prior", "--prior 0.3", "--pad-speed 1.2"}) {
    const auto r = run_feint("observer fit " + shell_quote(kDemo) + " " + option);
    EXPECT_EQ(r.exit_code, 64) << option;
    const std::string name = std::string(option).substr(0, std::string(option).find(' '));
    EXPECT_NE(r.err.find(name + " is an option of pad-trace logs; these are logs of K targets and a pointer"),
              std::string::npos)
        << r.err;
  }
}

TEST(ObserverFitPointerCli, APointerLogAmongPadLogsIsRefusedByName) {
  TempDir dir;
  write_text(dir / "logs" / "a_pad.csv",
             "participant,condition,iteration,strategy,variant,target,t,pad\n"
             "P1,c,1,optimal,main,right,0,0.5\nP1,c,1,optimal,main,right,0.04,0.52\n"
             "P1,c,1,optimal,main,right,0.08,0.55\n");
  write_text(dir / "logs" / "b_pointer.csv", kHeader + trial_rows("P2", 1, 8));
  const auto r = run_feint("observer fit " + shell_quote((dir / "logs").string()));
  EXPECT_EQ(r.exit_code, 65) << r.out;
  EXPECT_NE(r.err.find("b_pointer.csv is a log of K targets and a pointer (a belief_x column, no pad), but "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("a_pad.csv is not: one data set is one kind of log"), std::string::npos) << r.err;
  // The other order: the pointer log first.
  write_text(dir / "logs" / "c_pad.csv", read_text(dir / "logs" / "a_pad.csv"));
  std::filesystem::remove(dir / "logs" / "a_pad.csv");
  const auto r2 = run_feint("observer fit " + shell_quote((dir / "logs").string()));
  EXPECT_EQ(r2.exit_code, 65);
  EXPECT_NE(r2.err.find("c_pad.csv is not"), std::string::npos) << r2.err;
}

TEST(ObserverFitPointerCli, EmptyAndShortTracesExit65SayingWhy) {
  TempDir dir;
  write_text(dir / "empty.csv", kHeader);
  auto r = run_feint("observer fit " + shell_quote((dir / "empty.csv").string()));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("no trial to fit the observer to: 0 trial(s) read from the logs of K targets and a pointer"),
            std::string::npos)
      << r.err;
  // Two samples: read (the reader needs 2), but the fit needs 3.
  write_text(dir / "short.csv", kHeader + trial_rows("P1", 1, 2));
  r = run_feint("observer fit " + shell_quote((dir / "short.csv").string()));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("1 trial(s) read"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("P1/c/1: the pointer trace has 2 sample(s); at least 3 are needed"), std::string::npos)
      << r.err;
  // Without robot_x, robot_y the path is not rebuilt: the trial is left out, by file and line.
  std::string no_robot = "participant,condition,iteration,strategy,variant,target,t,belief_x,belief_y,start_x,"
                         "start_y,target0_x,target0_y,target1_x,target1_y,target2_x,target2_y\n";
  for (int i = 0; i < 5; ++i) no_robot += "P1,c,1,optimal,main,2," + std::to_string(i) + ",0,4,0,0,-2,4,0,4,2,4\n";
  write_text(dir / "norobot.csv", no_robot);
  r = run_feint("observer fit " + shell_quote((dir / "norobot.csv").string()));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("norobot.csv:2: the log has no robot_x, robot_y"), std::string::npos) << r.err;
}

TEST(ObserverFitPointerCli, AShortTrialIsLeftOutAndTheRestFitted) {
  TempDir dir;
  std::string log = kHeader;
  for (int it = 1; it <= 4; ++it) log += trial_rows("P1", it, 12);
  log += trial_rows("P1", 5, 2);
  write_text(dir / "p1.csv", log);
  const auto r = run_feint("observer fit " + shell_quote((dir / "p1.csv").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("fitted to 4 pointer trial(s)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("one fixed layout"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("P1/c/5: the pointer trace has 2 sample(s)"), std::string::npos) << r.out;
}

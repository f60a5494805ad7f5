// End-to-end tests of `feint simulate trajectories` and `feint observer fit` (docs/observer.md).
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "cli_helpers.hpp"

using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

TEST(SimulateTrajectoriesCli, EveryStrategyVersionAndTargetAsCsv) {
  const auto r = run_feint("simulate trajectories --beta 2 --tau 0.3 -f csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')),
            "strategy,variant,target,duration,path_length,cost_overhead,legibility,time_deceived,"
            "last_deceptive_point,final_belief,belief_error,belief_confusion,belief_overspeed_segments,"
            "beta,tau,prior_right,pad_speed");
  // 3 deceptive strategies x 2 versions x 2 targets + optimal x 2 targets, plus the header.
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 15);
  EXPECT_NE(r.out.find("\noptimal,main,right,"), std::string::npos);
  EXPECT_NE(r.out.find("\nswitching,v2,left,"), std::string::npos);
}

TEST(SimulateTrajectoriesCli, TextNamesTheObserverAndPadSpeed) {
  const auto r = run_feint("simulate trajectories");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("beta = 1 1/m, tau = 0 s, P(right) = 0.5"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("pad speed v = 0.8"), std::string::npos) << r.out;
}

TEST(SimulateTrajectoriesCli, BadParametersAndPathsAreRefused) {
  auto r = run_feint("simulate trajectories --beta -1");
  EXPECT_EQ(r.exit_code, 64);
  EXPECT_NE(r.err.find("beta"), std::string::npos) << r.err;
  r = run_feint("simulate trajectories --prior 1");
  EXPECT_EQ(r.exit_code, 64);
  TempDir dir;
  write_text(dir / "still.csv", "t,x,y\n0,1,1\n1,1,1\n2,1,1\n");
  r = run_feint("simulate trajectories --path " + shell_quote((dir / "still.csv").string()));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("still.csv: the robot path never moves"), std::string::npos) << r.err;
  write_text(dir / "bad.csv", "t,x,y\n0,0,0\n1,abc,1\n");
  r = run_feint("simulate trajectories --path " + shell_quote((dir / "bad.csv").string()));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("bad.csv:3: column 'x'"), std::string::npos) << r.err;
}

TEST(ObserverFitCli, FitsASimulatedStudyAndNamesTheBadTrials) {
  TempDir dir;
  const auto study = dir / "study";
  auto r = run_feint("simulate study --out " + shell_quote(study.string()) +
                     " --participants 2 --iterations 6 --seed 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // An extra log: a trial whose strategy cannot be rebuilt, and one with two pad samples.
  write_text(study / "logs" / "extra.csv",
             "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed\n"
             "X1,random,1,teleport,main,right,0,0.5,0.8\n"
             "X1,random,1,teleport,main,right,0.04,0.5,0.8\n"
             "X1,random,1,teleport,main,right,0.08,0.5,0.8\n"
             "X1,random,2,optimal,main,left,0,0.5,0.8\n"
             "X1,random,2,optimal,main,left,0.04,0.49,0.8\n");
  r = run_feint("observer fit " + shell_quote((study / "logs").string()) + " -o " +
                shell_quote((dir / "fit.txt").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string out = read_text(dir / "fit.txt");
  // The simulated logs carry robot_x, robot_y; the extra log has none, so its trials are rebuilt.
  EXPECT_NE(out.find("robot path from the logs for"), std::string::npos) << out;
  EXPECT_NE(out.find("rebuilt from strategy, variant, target and the default geometry"), std::string::npos);
  EXPECT_NE(out.find("fitted to 24 trial(s)"), std::string::npos) << out;
  for (const char* p : {"\nP01 ", "\nP02 ", "\nP03 ", "\nP04 ", "\nadaptive ", "\nrandom "}) {
    EXPECT_NE(out.find(p), std::string::npos) << p << "\n" << out;
  }
  EXPECT_NE(out.find("X1/random/1: "), std::string::npos) << out;
  EXPECT_NE(out.find("'teleport'"), std::string::npos) << out;
  EXPECT_NE(out.find("X1/random/2: the pad trace has 2 sample(s); at least 3"), std::string::npos) << out;
  EXPECT_NE(out.find("Learning: beta_k"), std::string::npos);
  EXPECT_NE(out.find("Model-human agreement"), std::string::npos);

  r = run_feint("observer fit " + shell_quote((study / "logs").string()) + " -f json --no-learning");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"participants\": ["), std::string::npos);
  EXPECT_NE(r.out.find("\"beta\": {\"estimate\": "), std::string::npos);
  EXPECT_NE(r.out.find("\"learning\": []"), std::string::npos);
}

// docs/observer.md's example: P03's tau profile is rough. A brute-force profile (tau on a 0.001 s
// grid, beta re-maximised at each) is below the cut-off on [0.357, 0.419], [0.495, 0.508] and
// [0.526, 0.660], the first beyond a barrier of deviance 5.4: the CI is the hull of all three,
// which the scan beyond the ends finds (the probes alone, 2 SE out, stopped at 0.494).
TEST(ObserverFitCli, ARoughProfilesCiCoversEveryRegionBelowTheCutOff) {
  TempDir dir;
  const auto study = dir / "study";
  auto r = run_feint("simulate study -o " + shell_quote(study.string()) + " -p 3 -n 20 --seed 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_feint("observer fit " + shell_quote((study / "logs").string()) + " -f json --no-learning");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto p03 = r.out.find("\"unit\": \"P03\"");
  ASSERT_NE(p03, std::string::npos) << r.out;
  const auto tau = r.out.find("\"tau\": {", p03);
  const auto low = r.out.find("\"conf.low\": ", tau);
  const auto high = r.out.find("\"conf.high\": ", tau);
  ASSERT_TRUE(tau != std::string::npos && low != std::string::npos && high != std::string::npos);
  EXPECT_NEAR(std::strtod(r.out.c_str() + low + 12, nullptr), 0.357, 0.002) << r.out.substr(tau, 200);
  EXPECT_NEAR(std::strtod(r.out.c_str() + high + 13, nullptr), 0.660, 0.002) << r.out.substr(tau, 200);
  r = run_feint("observer fit " + shell_quote((study / "logs").string()) + " --no-learning");
  EXPECT_NE(r.out.find("P03: the profile likelihood of tau is not unimodal"), std::string::npos) << r.out;
}

TEST(ObserverFitCli, BadOptionsAreUsageErrors) {
  TempDir dir;
  write_text(dir / "log.csv", "participant,iteration,strategy,variant,target,t,pad\nP1,1,optimal,main,right,0,0.5\n"
                              "P1,1,optimal,main,right,1,0.6\nP1,1,optimal,main,right,2,0.7\n");
  auto r = run_feint("observer fit " + shell_quote((dir / "log.csv").string()) + " --noise pink");
  EXPECT_EQ(r.exit_code, 64);
  EXPECT_NE(r.err.find("--noise 'pink'"), std::string::npos) << r.err;
  r = run_feint("observer fit " + shell_quote((dir / "log.csv").string()) + " --beta-max 0");
  EXPECT_EQ(r.exit_code, 64);
  EXPECT_NE(r.err.find("beta_max"), std::string::npos) << r.err;
}

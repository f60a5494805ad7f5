// End-to-end tests of `feint simulate trajectories` and `feint observer fit` (docs/observer.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_helpers.hpp"
#include "feint/io/csv.hpp"

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

namespace {

// A simulated study's logs as one CSV in feint's own format and as a lab would write them:
// `subject` for participant, `time_ms` (milliseconds) for t; neither has robot_x, robot_y.
void write_own_and_lab_logs(const std::filesystem::path& logs, const std::filesystem::path& own,
                            const std::filesystem::path& lab) {
  std::string own_text =
      "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed\n";
  std::string lab_text =
      "subject,condition,iteration,strategy,variant,target,time_ms,pad,pad_speed\n";
  for (const char* id : {"P01", "P02", "P03", "P04"}) {
    feint::io::CsvReader r((logs / (std::string(id) + ".csv.gz")).string());
    while (r.next()) {
      const std::string t(r.field(6));  // seconds as written -> milliseconds, digits shifted
      const auto dot = t.find('.');
      std::string frac = dot == std::string::npos ? "" : t.substr(dot + 1);
      frac.resize(std::max<std::size_t>(frac.size(), 3), '0');
      std::string ms = t.substr(0, dot) + frac.substr(0, 3);
      ms.erase(0, std::min(ms.find_first_not_of('0'), ms.size() - 1));
      if (frac.size() > 3) ms += "." + frac.substr(3);
      // The first 9 columns (robot_x, robot_y dropped), with `time` as column 7.
      const auto row = [&](const std::string& time) {
        std::string out;
        for (std::size_t i = 0; i < 9; ++i)
          out += (i == 6 ? time : std::string(r.field(i))) + (i == 8 ? "\n" : ",");
        return out;
      };
      own_text += row(t);
      lab_text += row(ms);
    }
  }
  write_text(own, own_text);
  write_text(lab, lab_text);
}

// Every number after `"estimate": ` in a JSON fit, in order.
std::vector<double> estimates(const std::string& json) {
  std::vector<double> out;
  const std::string key = "\"estimate\": ";
  for (auto at = json.find(key); at != std::string::npos; at = json.find(key, at + 1))
    out.push_back(std::strtod(json.c_str() + at + key.size(), nullptr));
  return out;
}

// The lines of `help` that describe `option` (its line and the description's continuation lines).
std::string help_of(const std::string& help, const std::string& option) {
  std::string out;
  bool in = false;
  std::size_t begin = 0;
  while (begin < help.size()) {
    const std::size_t end = std::min(help.find('\n', begin), help.size());
    const std::string line = help.substr(begin, end - begin);
    const std::string head = "  " + option;
    if (line.rfind(head, 0) == 0 && (line.size() == head.size() || line[head.size()] == ' ')) {
      in = true;
      out += line + "\n";
    } else if (in && line.rfind(std::string(20, ' '), 0) == 0) {
      out += line + "\n";
    } else {
      in = false;
    }
    begin = end + 1;
  }
  return out;
}

}  // namespace

// A lab's logs (other column names, milliseconds) read with the loader options of `feint score`
// give the same fit as the same data in feint's own format.
TEST(ObserverFitCli, ALabsLogsReadWithMapGiveTheSameFitAsFeintsFormat) {
  TempDir dir;
  const auto study = dir / "study";
  auto r = run_feint("simulate study --out " + shell_quote(study.string()) +
                     " --participants 2 --iterations 6 --seed 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  write_own_and_lab_logs(study / "logs", dir / "own.csv", dir / "lab.csv");
  r = run_feint("observer fit " + shell_quote((dir / "own.csv").string()) +
                " -f json --no-learning");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<double> own = estimates(r.out);
  r = run_feint("observer fit " + shell_quote((dir / "lab.csv").string()) +
                " -f json --no-learning --map participant=subject --map t=time_ms --time-unit ms");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<double> lab = estimates(r.out);
  // beta and tau of 4 participants and 2 conditions (12), then the conditions compared on log beta
  // and on tau (Welch's estimate, and the rank test's, which has none: 0).
  ASSERT_EQ(own.size(), 16u);
  EXPECT_NE(r.out.find("\"comparisons\": [\n    {\"parameter\": \"log beta\""), std::string::npos) << r.out;
  ASSERT_EQ(lab.size(), own.size()) << r.out;
  for (std::size_t i = 0; i < own.size(); ++i)
    EXPECT_NEAR(lab[i], own[i], 1e-6 * std::max(1.0, std::abs(own[i]))) << i << "\n" << r.out;
  EXPECT_NE(r.out.find("\"unit\": \"P03\""), std::string::npos) << r.out;
  // Neither file has robot_x, robot_y: the header says the paths were rebuilt, nothing else.
  r = run_feint("observer fit " + shell_quote((dir / "lab.csv").string()) +
                " --no-learning --map participant=subject --map t=time_ms --time-unit ms");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string header = r.out.substr(0, r.out.find('\n'));
  EXPECT_NE(header.find("fitted to 24 trial(s) (path rebuilt from strategy, variant, target and "
                        "the default geometry)"),
            std::string::npos)
      << header;
  EXPECT_EQ(header.find("robot_x"), std::string::npos) << header;
}

TEST(ObserverFitCli, NoUsableTrialExits65SayingWhy) {
  TempDir dir;
  // No strategy and no robot_x, robot_y: no trial has a robot path.
  write_text(dir / "nopath.csv",
             "participant,iteration,target,t,pad\nP1,1,1,0,0.5\nP1,1,1,1,0.6\n"
             "P1,1,1,2,0.7\nP2,1,0,0,0.5\nP2,1,0,1,0.4\nP2,1,0,2,0.3\n");
  auto r = run_feint("observer fit " + shell_quote((dir / "nopath.csv").string()) + " -o " +
                     shell_quote((dir / "fit.txt").string()));
  EXPECT_EQ(r.exit_code, 65) << r.out << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "fit.txt"));
  EXPECT_EQ(r.err.find("fitted to 0 trial(s)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no trial to fit the observer to: 2 trial(s) read from the logs, 2 left out "
                       "while reading them, 0 left out by the fit's checks; first: P1/1: "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("the trial has no strategy"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--map strategy=COLUMN"), std::string::npos) << r.err;
  // Read, but left out by the fit's checks (two pad samples each).
  write_text(dir / "short.csv",
             "participant,iteration,strategy,variant,target,t,pad\n"
             "P1,1,optimal,main,right,0,0.5\nP1,1,optimal,main,right,1,0.6\n");
  r = run_feint("observer fit " + shell_quote((dir / "short.csv").string()));
  EXPECT_EQ(r.exit_code, 65) << r.out << r.err;
  EXPECT_NE(
      r.err.find("1 left out by the fit's checks; first: P1/1: the pad trace has 2 sample(s)"),
      std::string::npos)
      << r.err;
}

namespace {

// The line of `out` that starts with `start` (after its indent), and how often it names `file`.
std::size_t names_in_line(const std::string& out, const std::string& start,
                          const std::string& file) {
  const auto at = out.find("\n  " + start);
  if (at == std::string::npos) return 0;
  const std::string line = out.substr(at + 1, out.find('\n', at + 1) - at - 1);
  std::size_t names = 0;
  for (auto f = line.find(file); f != std::string::npos; f = line.find(file, f + 1)) ++names;
  return names;
}

}  // namespace

TEST(ObserverFitCli, ARejectLineNamesItsFileOnce) {
  TempDir dir;
  const auto study = dir / "study";
  auto r = run_feint("simulate study --out " + shell_quote(study.string()) +
                     " --participants 1 --iterations 4 --seed 5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // X1/1: no strategy, so no robot path.
  write_text(study / "logs" / "extra.csv",
             "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed\n"
             "X1,random,1,,main,right,0,0.5,0.8\nX1,random,1,,main,right,1,0.6,0.8\n"
             "X1,random,1,,main,right,2,0.7,0.8\n");
  const std::string logs = shell_quote((study / "logs").string());
  r = run_feint("observer fit " + logs + " --no-learning");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(names_in_line(r.out, "X1/random/1: ", "extra.csv"), 1u) << r.out;
  // X2/1: a pad outside [0, 1], the reader's rejection: --on-error strict (the default) stops.
  write_text(study / "logs" / "bad.csv",
             "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed\n"
             "X2,random,1,optimal,main,left,0,0.5,0.8\nX2,random,1,optimal,main,left,1,1.7,0.8\n"
             "X2,random,1,optimal,main,left,2,0.3,0.8\n");
  r = run_feint("observer fit " + logs + " --no-learning");
  EXPECT_EQ(r.exit_code, 65) << r.out;
  EXPECT_NE(r.err.find("bad.csv:3: column 'pad': 1.7 is outside [0, 1]"), std::string::npos)
      << r.err;
  r = run_feint("observer fit " + logs + " --no-learning --on-error skip");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("2 trial(s) left out while reading the logs"), std::string::npos) << r.out;
  EXPECT_EQ(names_in_line(r.out, "X1/random/1: ", "extra.csv"), 1u) << r.out;
  EXPECT_EQ(names_in_line(r.out, "X2/random/1: ", "bad.csv"), 1u) << r.out;
}

TEST(ObserverFitCli, HelpListsTheLoaderOptionsOfScoreWithTheSameText) {
  const auto score = run_feint("score --help");
  const auto fit = run_feint("observer fit --help");
  ASSERT_EQ(score.exit_code, 0);
  ASSERT_EQ(fit.exit_code, 0);
  for (const char* option : {"--map", "--delimiter", "--on-error", "--time-unit", "--decimal",
                             "--no-header", "--columns", "--iteration-base",
                             "--participant-from-path", "--samples-column", "--single-condition"}) {
    const std::string in_score = help_of(score.out, option);
    ASSERT_FALSE(in_score.empty()) << option << "\n" << score.out;
    EXPECT_EQ(help_of(fit.out, option), in_score) << option << "\n" << fit.out;
  }
  // The scoring options stay with feint score (observer fit has a --pad-speed of its own).
  for (const char* option : {"--trim", "--deadband", "--belief-deadband", "--confusion-norm"})
    EXPECT_EQ(help_of(fit.out, option), "") << option;
}

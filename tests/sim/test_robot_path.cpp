// The robot's path of a logged trial (feint/sim/robot_path.hpp, docs/formats.md "Robot path"): the
// rebuilt path is the strategy's exact polyline; simulated logs carry it (robot_x, robot_y), and
// rebuilding it from strategy, variant and target gives the same path; every reason it cannot be
// rebuilt names the trial.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/io/trace.hpp"
#include "feint/sim/robot_path.hpp"
#include "feint/sim/study.hpp"

using namespace feint::sim;

namespace {

feint::io::Trial trial(std::string strategy, std::string variant, double target) {
  feint::io::Trial t;
  t.participant = "P07";
  t.condition = "adaptive";
  t.iteration = 3;
  t.strategy = std::move(strategy);
  t.variant = std::move(variant);
  t.target = target;
  t.times = {10, 10.5, 11, 20};
  t.pads = {0.5, 0.5, 0.6, 1};
  t.file = "p07.csv";
  t.line = 12;
  return t;
}

std::string rebuild_error(const feint::io::Trial& t) {
  try {
    robot_path(t, Geometry{});
  } catch (const feint::InvalidData& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST(RobotPath, RebuiltPositionsAreTheTrajectorysSamples) {
  const Geometry g;
  for (const Strategy s : {Strategy::exaggerating, Strategy::switching, Strategy::ambiguous,
                           Strategy::optimal}) {
    for (const Variant v : {Variant::main, Variant::v2}) {
      if (s == Strategy::optimal && v == Variant::v2) continue;
      for (const Target target : {Target::left, Target::right}) {
        const auto path = trajectory(s, v, target, g);
        std::vector<double> times;
        for (const auto& p : path) times.push_back(p.t);
        const auto got = robot_positions(s, v, target, g, times);
        ASSERT_EQ(got.size(), path.size());
        for (std::size_t i = 0; i < path.size(); ++i) {
          EXPECT_NEAR(got[i].x, path[i].x, 1e-12) << to_string(s) << " " << i;
          EXPECT_NEAR(got[i].y, path[i].y, 1e-12) << to_string(s) << " " << i;
        }
      }
    }
  }
}

TEST(RobotPath, OptimalIsAStraightLineAtTheRobotsSpeedAndRestsAtTheTarget) {
  Geometry g;  // targets at (+-2, 4): the optimal path to the right is 2 sqrt(5) m long
  g.speed = 2;
  const double len = std::hypot(2.0, 4.0);
  const auto p = robot_positions(Strategy::optimal, Variant::main, Target::right, g,
                                 std::vector<double>{-1, 0, 1, len / 2, 100});
  EXPECT_EQ(p[0].x, 0);  // before the start: at the start
  EXPECT_EQ(p[0].y, 0);
  EXPECT_NEAR(p[2].x, 2 * 2 / len, 1e-12);  // 2 m along the line
  EXPECT_NEAR(p[2].y, 2 * 4 / len, 1e-12);
  EXPECT_NEAR(p[3].x, 2, 1e-12);  // the end
  EXPECT_NEAR(p[3].y, 4, 1e-12);
  EXPECT_EQ(p[4].x, 2);  // at rest on the target
  EXPECT_EQ(p[4].y, 4);
}

TEST(RobotPath, ColumnsAreUsedAsLoggedAndNotRebuilt) {
  auto t = trial("", "", 0.3);  // could not be rebuilt: the columns are what counts
  t.robot_x = {0, 0.1, 0.2, 0.2};
  t.robot_y = {0, 0.5, 1, 1};
  const auto p = robot_path(t, Geometry{});
  EXPECT_FALSE(p.rebuilt);
  ASSERT_EQ(p.samples.size(), 4U);
  EXPECT_EQ(p.samples[1].t, 0.5);  // since the trial's first sample
  EXPECT_EQ(p.samples[3].t, 10);
  EXPECT_EQ(p.samples[2].x, 0.2);
  EXPECT_EQ(p.samples[2].y, 1);
}

TEST(RobotPath, WithoutColumnsItIsRebuiltAndSaysSo) {
  const auto p = robot_path(trial("Exaggerating", "main", 0), Geometry{});
  EXPECT_TRUE(p.rebuilt);
  const auto want = robot_positions(Strategy::exaggerating, Variant::main, Target::left, Geometry{},
                                    std::vector<double>{0, 0.5, 1, 10});
  ASSERT_EQ(p.samples.size(), 4U);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(p.samples[i].t, want[i].t);
    EXPECT_EQ(p.samples[i].x, want[i].x);
    EXPECT_EQ(p.samples[i].y, want[i].y);
  }
  EXPECT_GT(p.samples[1].x, 0);  // exaggerating toward the false (right) side first
  EXPECT_TRUE(robot_path(trial("optimal", "", 1), Geometry{}).rebuilt);  // no variant = main
}

TEST(RobotPath, EveryReasonItCannotBeRebuiltNamesTheTrial) {
  const std::string where = "p07.csv:12: cannot rebuild the robot's path: ";
  const std::string who = "(trial P07/adaptive/3)";
  for (const auto& [t, what] : std::vector<std::pair<feint::io::Trial, std::string>>{
           {trial("", "main", 1), "the trial has no strategy"},
           {trial("zigzag", "main", 1), "strategy 'zigzag' is not exaggerating"},
           {trial("switching", "v3", 1), "variant 'v3' is not main or v2"},
           {trial("optimal", "v2", 1), "the optimal strategy has no v2"},
           {trial("switching", "main", 0.3), "target 0.3 is not left (0) or right (1)"}}) {
    const std::string msg = rebuild_error(t);
    EXPECT_EQ(msg.rfind(where + what, 0), 0U) << msg;
    EXPECT_NE(msg.find(who), std::string::npos) << msg;
    EXPECT_NE(msg.find("robot_x and robot_y columns"), std::string::npos) << msg;
  }
  auto t = trial("switching", "main", 1);
  t.robot_x = {0, 0};
  t.robot_y = {0, 0};
  const std::string msg = rebuild_error(t);
  EXPECT_NE(msg.find("2 robot_x and 2 robot_y values for 4 samples"), std::string::npos) << msg;
  EXPECT_NE(msg.find(who), std::string::npos) << msg;
}

TEST(RobotPath, SimulatedLogsCarryThePathThatRebuildingGives) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("feint-robot-path-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  StudySettings s;
  s.participants = 1;
  s.iterations = 8;
  write_study(s, dir.string());
  feint::io::TraceOptions opt;
  opt.read_robot_path = true;
  feint::io::TraceReader reader(feint::io::expand_inputs({(dir / "logs").string()}), opt);
  feint::io::Trial t;
  int trials = 0;
  while (reader.next(t)) {
    ++trials;
    ASSERT_EQ(t.robot_x.size(), t.times.size());
    const auto logged = robot_path(t, s.geometry);
    EXPECT_FALSE(logged.rebuilt);
    t.robot_x.clear();
    t.robot_y.clear();
    const auto rebuilt = robot_path(t, s.geometry);
    EXPECT_TRUE(rebuilt.rebuilt);
    ASSERT_EQ(rebuilt.samples.size(), logged.samples.size());
    for (std::size_t i = 0; i < logged.samples.size(); ++i) {
      // The log rounds to 0.1 mm.
      EXPECT_NEAR(logged.samples[i].x, rebuilt.samples[i].x, 0.5e-4 + 1e-12) << t.label() << " " << i;
      EXPECT_NEAR(logged.samples[i].y, rebuilt.samples[i].y, 0.5e-4 + 1e-12) << t.label() << " " << i;
    }
    // It starts at the start and ends on the true target.
    EXPECT_EQ(logged.samples.front().x, 0);
    EXPECT_EQ(logged.samples.front().y, 0);
    EXPECT_EQ(logged.samples.back().x, t.target == 0 ? -2 : 2);
    EXPECT_EQ(logged.samples.back().y, 4);
  }
  EXPECT_EQ(trials, 16);
  std::filesystem::remove_all(dir);
}

// feint collect writes the robot's position with every sample (robot_x, robot_y; docs/formats.md
// "Robot path"), computed from the round's plan, never from the page; a log begun by an older
// feint (without the columns) keeps its layout when the study is resumed.
#include <gtest/gtest.h>

#include <cmath>

#include "collect_helpers.hpp"
#include "feint/collect/study.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/sim/robot_path.hpp"

namespace feint::collect {
namespace {

namespace fs = std::filesystem;
using namespace testing;

TEST(CollectRobotPath, EverySampleCarriesTheRobotsPlannedPosition) {
  const auto dir = fresh_dir("robot");
  Study study(dir, fast_settings());
  study.join("P01");
  std::vector<Round> rounds;
  const auto& s = study.settings();
  for (int i = 0; i < s.practice + s.iterations; ++i) {
    const Round r = study.start_round("P01");
    study.submit_round("P01", r.kind, r.iteration, valid_trace(r, s.pad_speed, r.iteration % 2));
    if (r.kind == RoundKind::main) rounds.push_back(r);
  }
  const auto log = lines(slurp(dir / "logs" / "P01.csv"));
  ASSERT_EQ(rounds.size(), 6U);
  std::size_t row = 1;
  for (const auto& r : rounds) {
    const auto trace = valid_trace(r, s.pad_speed, r.iteration % 2);
    std::vector<double> times;
    for (const auto& x : trace) times.push_back(x.t);
    const auto want = sim::robot_positions(r.strategy, r.variant, r.target, s.geometry, times);
    for (std::size_t i = 0; i < trace.size(); ++i, ++row) {
      ASSERT_LT(row, log.size());
      const auto f = io::split_csv_line(log[row]);
      ASSERT_EQ(f.size(), 11U) << log[row];
      EXPECT_EQ(f[2], std::to_string(r.iteration));
      EXPECT_NEAR(*io::parse_double(f[9]), want[i].x, 0.5e-4 + 1e-12) << log[row];
      EXPECT_NEAR(*io::parse_double(f[10]), want[i].y, 0.5e-4 + 1e-12) << log[row];
    }
    // The round ends with the robot on its true target.
    const auto last = io::split_csv_line(log[row - 1]);
    EXPECT_EQ(last[9], r.target == sim::Target::left ? "-2" : "2");
    EXPECT_EQ(last[10], "4");
  }
  EXPECT_EQ(row, log.size());
}

TEST(CollectRobotPath, ALogWithoutRobotColumnsKeepsItsLayoutWhenResumed) {
  const auto dir = fresh_dir("legacy");
  {
    Study study(dir, fast_settings());
    study.join("P1");
    for (int i = 0; i < 3; ++i) {  // two practice rounds and the first main round
      const Round r = study.start_round("P1");
      study.submit_round("P1", r.kind, r.iteration, valid_trace(r, 0.8));
    }
  }
  // Rewrite the main log as an older feint wrote it: no robot_x, robot_y.
  const fs::path path = dir / "logs" / "P1.csv";
  std::string legacy;
  for (const auto& l : lines(slurp(path))) {
    const auto cut = l.rfind(',', l.rfind(',') - 1);
    legacy += l.substr(0, cut) + "\n";
  }
  ASSERT_EQ(legacy.substr(0, legacy.find('\n')),
            "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed");
  { std::ofstream(path, std::ios::binary | std::ios::trunc) << legacy; }
  Study study(dir, fast_settings());
  EXPECT_EQ(study.status("P1")->rounds_saved, 1);
  const Round r = study.start_round("P1");
  EXPECT_EQ(r.iteration, 2);
  study.submit_round("P1", r.kind, r.iteration, valid_trace(r, 0.8));
  const auto log = lines(slurp(path));
  EXPECT_EQ(slurp(path).substr(0, legacy.size()), legacy);
  for (std::size_t i = 1; i < log.size(); ++i) {
    EXPECT_EQ(io::split_csv_line(log[i]).size(), 9U) << log[i];
  }
  EXPECT_EQ(study.status("P1")->rounds_saved, 2);
}

}  // namespace
}  // namespace feint::collect

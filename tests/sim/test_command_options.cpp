// What `feint simulate` and `feint observer fit` hand to the library (feint/sim/options.hpp,
// feint/sim/observer_logs.hpp, read_path_file in trajectory_measures.hpp): the options turned into
// settings, with every rejection naming the option, file, row or column.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "feint/error.hpp"
#include "feint/sim/observer_logs.hpp"
#include "feint/sim/options.hpp"
#include "feint/sim/trajectory_measures.hpp"

using namespace feint::sim;
namespace fs = std::filesystem;

namespace {

std::string write_file(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("feint-options-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p.string();
}

template <class E, class F>
std::string message_of(F f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "(no exception)";
}

}  // namespace

TEST(PathFile, ReadsTheColumnsByNameInAnyOrderAndSkipsBlankLines) {
  const auto file = write_file("path.csv", "robot_y,T,note,robot_x\n0,0,a,0\n\n1.5,0.5,b,-0.25\n");
  const auto path = read_path_file(file);
  ASSERT_EQ(path.size(), 2u);
  EXPECT_DOUBLE_EQ(path[1].t, 0.5);
  EXPECT_DOUBLE_EQ(path[1].x, -0.25);
  EXPECT_DOUBLE_EQ(path[1].y, 1.5);
}

TEST(PathFile, NamesTheFileRowAndColumnOfEachProblem) {
  const auto no_y = write_file("no_y.csv", "t,x\n0,0\n");
  EXPECT_EQ(message_of<feint::InvalidData>([&] { read_path_file(no_y); }),
            no_y + ":1: the header must name the columns t, x and y (got 't,x')");
  const auto bad = write_file("bad.csv", "t,x,y\n0,0,0\n1,abc,2\n");
  EXPECT_EQ(message_of<feint::InvalidData>([&] { read_path_file(bad); }),
            bad + ":3: column 'x': 'abc' is not a number");
  EXPECT_EQ(message_of<feint::IoError>([&] { read_path_file("/nonexistent/p.csv"); }),
            "/nonexistent/p.csv: cannot open the path file");
}

TEST(SimulateOptions, SelectionCompareRunsTheFourAlgorithmsAndUnknownNamesAreRefused) {
  SelectionOptions o;
  o.compare = true;
  o.runs = 3;
  const auto all = selection_settings(o);
  ASSERT_EQ(all.size(), 4u);
  for (const auto& s : all) EXPECT_EQ(s.runs, 3u);
  o.algorithm = "roulette";
  EXPECT_THROW(selection_settings(o), feint::UsageError);
}

TEST(SimulateOptions, StudySettingsTakeTheObserverAssignments) {
  StudyOptions o;
  o.pad_speed = 1.25;
  o.observer = {"beta=2.5"};
  const StudySettings s = study_settings(o);
  EXPECT_DOUBLE_EQ(s.observer.beta, 2.5);
  EXPECT_DOUBLE_EQ(s.observer.pad_speed, 1.25);
  o.observer = {"no_such_parameter=1"};
  EXPECT_THROW(study_settings(o), feint::UsageError);
}

TEST(SimulateOptions, TrajectoriesOfACustomPathNeedLeftOrRight) {
  TrajectoriesOptions o;
  o.path = write_file("straight.csv", "t,x,y\n0,0,0\n1,1,2\n2,2,4\n");
  o.target = "Up";
  EXPECT_EQ(message_of<feint::UsageError>([&] { trajectory_measures(o); }),
            "--target 'Up': expected left or right");
  o.target = "RIGHT";
  const TrajectoryMeasures m = trajectory_measures(o);
  ASSERT_EQ(m.rows.size(), 1u);
  EXPECT_EQ(m.rows[0].strategy, "custom");
  EXPECT_EQ(m.rows[0].target, "right");
  EXPECT_DOUBLE_EQ(m.settings.observer.beta, 1.0);
  // A straight run to the right target: no detour.
  EXPECT_NEAR(m.rows[0].measures.cost_overhead, 0.0, 1e-12);
}

TEST(ObserverFitOptions, NoiseAndFormatAreCheckedAndTheRestCopied) {
  ObserverFitOptions o;
  o.noise = "independent";
  o.no_learning = true;
  o.level = 0.9;
  const auto s = observer_fit_settings(o);
  EXPECT_EQ(s.noise, feint::models::PadNoise::independent);
  EXPECT_FALSE(s.learning);
  EXPECT_DOUBLE_EQ(s.level, 0.9);
  o.noise = "gauss";
  EXPECT_EQ(message_of<feint::UsageError>([&] { observer_fit_settings(o); }),
            "--noise 'gauss': expected ar1 or independent");
  o.noise = "ar1";
  o.format = "csv";
  EXPECT_EQ(message_of<feint::UsageError>([&] { observer_fit_settings(o); }),
            "--format 'csv': expected text or json");
}

TEST(ObserverFitOptions, PathSourceSaysWhereThePathsCameFrom) {
  ObservedLogs logs;
  logs.paths_logged = 3;
  EXPECT_EQ(logs.path_source(), "robot path from the logs' robot_x, robot_y");
  logs.paths_rebuilt = 2;
  EXPECT_EQ(logs.path_source(),
            "robot path from the logs for 3 trials, rebuilt from strategy, variant, target and the "
            "default geometry for 2");
  logs.paths_logged = 0;
  EXPECT_EQ(logs.path_source(),
            "path rebuilt from strategy, variant, target and the default geometry");
  logs.paths_rebuilt = 0;  // no trial: no claim
  EXPECT_EQ(logs.path_source(), "no robot path (no trial was read)");
}

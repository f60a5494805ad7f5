// The map's data (metrics/mean_map.hpp) and where the figure gets it (analysis::FigureData::map):
// the canonical frame and the means at normalised time by hand, the same means from a log of a
// small constructed study (only its scored trials), the map of data/demo-k3 resting on exactly the
// scored trials, and the figure drawn from the results after the logs are gone.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli/cli_helpers.hpp"
#include "feint/analysis/analyze.hpp"
#include "feint/error.hpp"
#include "feint/io/scores.hpp"
#include "feint/metrics/mean_map.hpp"
#include "feint/publish/study_report.hpp"

namespace fs = std::filesystem;
using namespace feint;
using metrics::MapPoint;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

constexpr double kTol = 1e-12;

void expect_point(MapPoint got, double x, double y, const char* what) {
  EXPECT_NEAR(got.x, x, kTol) << what;
  EXPECT_NEAR(got.y, y, kTol) << what;
}

metrics::Layout layout(MapPoint start, std::vector<MapPoint> targets) {
  return metrics::Layout{start, std::move(targets)};
}

metrics::MapTrial trial(const metrics::Layout& l, std::size_t target, std::vector<double> t,
                        std::vector<double> px, std::vector<double> py,
                        std::vector<double> rx = {}, std::vector<double> ry = {}) {
  metrics::MapTrial m;
  m.strategy = "exaggerating";
  m.variant = "main";
  m.layout = l;
  m.true_target = target;
  m.times = std::move(t);
  m.pointer_x = std::move(px);
  m.pointer_y = std::move(py);
  m.robot_x = std::move(rx);
  m.robot_y = std::move(ry);
  return m;
}

}  // namespace

// Start (1, 2), true target (4, 6): d = (3, 4), |d|^2 = 25, x = (v.x d.y - v.y d.x) / 25,
// y = (v.x d.x + v.y d.y) / 25. Decoy (5, 2): v = (4, 0) -> (16/25, 12/25), bearing atan(4/3) =
// 53.1 deg, on the right; decoy (-2, 6): v = (-3, 4) -> (-24/25, 7/25), bearing 73.7 deg. The
// nearest decoy by bearing is on the right: the frame mirrors x. Pointer (4, 2): v = (3, 0) ->
// (12/25, 9/25), mirrored (-0.48, 0.36).
TEST(MapFrame, HandExampleMirrorsTheNearestDecoyToTheLeft) {
  const auto l = layout({1, 2}, {{5, 2}, {4, 6}, {-2, 6}});
  const metrics::CanonicalFrame f = metrics::canonical_frame(l, 1);
  EXPECT_TRUE(f.mirrored);
  expect_point(f({1, 2}), 0, 0, "start");
  expect_point(f({4, 6}), 0, 1, "true target");
  expect_point(f({5, 2}), -0.64, 0.48, "nearest decoy");
  expect_point(f({-2, 6}), 0.96, 0.28, "other decoy");
  expect_point(f({4, 2}), -0.48, 0.36, "pointer");
}

// Start (0, 0), true target (0, 2): x = v.x / 2, y = v.y / 2. Decoy (-1, 2) -> (-0.5, 1), bearing
// 26.6 deg, already on the left (no mirror); decoy (3, 1) -> (1.5, 0.5); pointer (1, 1) -> (0.5,
// 0.5).
TEST(MapFrame, HandExampleWithTheNearestDecoyOnTheLeftIsNotMirrored) {
  const auto l = layout({0, 0}, {{-1, 2}, {3, 1}, {0, 2}});
  const metrics::CanonicalFrame f = metrics::canonical_frame(l, 2);
  EXPECT_FALSE(f.mirrored);
  expect_point(f({0, 2}), 0, 1, "true target");
  expect_point(f({-1, 2}), -0.5, 1, "nearest decoy");
  expect_point(f({3, 1}), 1.5, 0.5, "other decoy");
  expect_point(f({1, 1}), 0.5, 0.5, "pointer");
  EXPECT_THROW(metrics::canonical_frame(l, 3), InvalidData);
}

// One fixed layout, two trials with true target 0. A: t = 0, 1, 2, pointer (0,0) (1,0) (1,2), with
// a robot path; B: t = 10, 14, pointer (2,2) -> (4,6), no robot path. At u = 0.25 A is at t = 0.5,
// (0.5, 0), B at t = 11, (2.5, 3): mean (1.5, 1.5). u = 0.5: (1, 0), (3, 4) -> (2, 2). u = 0.75:
// (1, 1), (3.5, 5) -> (2.25, 3). The robot's mean rests on A alone.
TEST(MapMeans, MeanAtNormalisedTimeIsTheHandAverage) {
  const auto l = layout({0, 0}, {{-2, 4}, {2, 4}});
  metrics::MapAccumulator acc;
  acc.add(trial(l, 0, {0, 1, 2}, {0, 1, 1}, {0, 0, 2}, {0, -1, -2}, {0, 2, 4}));
  acc.add(trial(l, 0, {10, 14}, {2, 4}, {2, 6}));
  const metrics::MeanMap d = acc.data();
  EXPECT_FALSE(d.canonical);
  EXPECT_EQ(d.layouts, 1u);
  ASSERT_EQ(d.panels.size(), 1u);
  ASSERT_EQ(d.panels[0].means.size(), 1u);
  const metrics::MapMean& m = d.panels[0].means[0];
  EXPECT_EQ(m.trials, 2u);
  EXPECT_EQ(m.robot_trials, 1u);
  ASSERT_EQ(m.pointer.size(), metrics::kMapPoints);
  expect_point(m.pointer[0], 1, 1, "u = 0");
  expect_point(m.pointer[25], 1.5, 1.5, "u = 0.25");
  expect_point(m.pointer[50], 2, 2, "u = 0.5");
  expect_point(m.pointer[75], 2.25, 3, "u = 0.75");
  expect_point(m.pointer[100], 2.5, 4, "u = 1");
  expect_point(m.robot[50], -1, 2, "robot, u = 0.5 (trial A only)");
  EXPECT_TRUE(d.panels[0].decoys.empty());
}

// Two layouts: each trial goes to the canonical frame before the mean. Trial 1: start (0, 0),
// true target (0, 2), decoy (-1, 2) -> (-0.5, 1); pointer (0, 0) -> (0, 2), i.e. (0, 0) -> (0, 1).
// Trial 2: start (1, 1), true target (3, 1) (east), decoy (3, 2) (north: on the left) -> (-0.5, 1);
// pointer from the decoy (3, 2) to the target (3, 1), i.e. (-0.5, 1) -> (0, 1). At u = 0.5:
// (0, 0.5) and (-0.25, 1), mean (-0.125, 0.75).
TEST(MapMeans, LayoutsPerRoundAreAveragedInTheCanonicalFrame) {
  metrics::MapAccumulator acc;
  acc.add(trial(layout({0, 0}, {{0, 2}, {-1, 2}}), 0, {0, 1}, {0, 0}, {0, 2}));
  acc.add(trial(layout({1, 1}, {{3, 2}, {3, 1}}), 1, {5, 9}, {3, 3}, {2, 1}));
  const metrics::MeanMap d = acc.data();
  EXPECT_TRUE(d.canonical);
  EXPECT_EQ(d.layouts, 2u);
  EXPECT_EQ(d.mirrored, 0u);
  EXPECT_EQ(d.targets, 2u);
  ASSERT_EQ(d.panels.size(), 1u);
  const metrics::MapMean& m = d.panels[0].means.at(0);
  EXPECT_EQ(m.trials, 2u);
  EXPECT_EQ(m.robot_trials, 0u);
  EXPECT_TRUE(m.robot.empty());
  expect_point(m.pointer[0], -0.25, 0.5, "u = 0");
  expect_point(m.pointer[50], -0.125, 0.75, "u = 0.5");
  expect_point(m.pointer[100], 0, 1, "u = 1");
  ASSERT_EQ(d.panels[0].decoys.size(), 2u);
  expect_point(d.panels[0].decoys[0], -0.5, 1, "decoy of trial 1");
  expect_point(d.panels[0].decoys[1], -0.5, 1, "decoy of trial 2");
  expect_point(d.layout.targets.at(0), 0, 1, "the canonical true target");
}

TEST(MapMeans, ABadTrialIsRefusedAndAddsNothing) {
  const auto l = layout({0, 0}, {{-2, 4}, {2, 4}});
  metrics::MapAccumulator acc;
  EXPECT_THROW(acc.add(trial(l, 0, {0, 1}, {0, 1, 2}, {0, 1})), InvalidData);  // sizes differ
  EXPECT_THROW(acc.add(trial(l, 0, {1, 1}, {0, 1}, {0, 1})), InvalidData);     // t not increasing
  EXPECT_THROW(acc.add(trial(l, 2, {0, 1}, {0, 1}, {0, 1})), InvalidData);     // no target 2
  EXPECT_EQ(acc.data().trials, 0u);
  EXPECT_TRUE(acc.data().panels.empty());
}

namespace {

// A log of K = 2 targets and a pointer (docs/formats.md "Logs of K targets and a pointer"), one
// row per sample; every trial is of condition "adaptive", strategy "exaggerating", version "main".
struct LogTrial {
  std::string participant;
  std::size_t target = 0;
  metrics::Layout layout;
  std::vector<std::vector<double>> samples;  // t, belief_x, belief_y, robot_x, robot_y
};

std::string number(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

std::string pointer_log(const std::vector<LogTrial>& trials) {
  std::string s =
      "participant,condition,iteration,strategy,variant,target,t,belief_x,belief_y,start_x,"
      "start_y,target0_x,target0_y,target1_x,target1_y,robot_x,robot_y\n";
  for (const auto& tr : trials) {
    const metrics::Layout& l = tr.layout;
    for (const auto& x : tr.samples) {
      s += tr.participant + ",adaptive,1,exaggerating,main," + std::to_string(tr.target);
      for (const double v : {x[0], x[1], x[2], l.start.x, l.start.y, l.targets[0].x,
                             l.targets[0].y, l.targets[1].x, l.targets[1].y, x[3], x[4]}) {
        s += "," + number(v);
      }
      s += "\n";
    }
  }
  return s;
}

// The scores of the trials named (participant; condition adaptive, iteration 1): the trials the
// map is to rest on.
io::ScoresTable scores_of(const std::vector<std::string>& participants) {
  io::ScoresTable t;
  t.has_condition = true;
  for (const auto& p : participants) t.records.push_back({p, "adaptive", 1, {}, 0});
  return t;
}

const metrics::Layout kFixed{{0, 0}, {{-2, 4}, {2, 4}}};

}  // namespace

// A small study of one fixed layout, start (0, 0), T0 (-2, 4), T1 (2, 4), two scored trials with
// true target T0. A: t = 0, 1, 2, pointer (0,0) (1,0) (1,2), robot (0,0) (-1,2) (-2,4). B: t = 10,
// 14, pointer (2,2) -> (4,6), robot (0,0) -> (0,4). At normalised time u, A is at t = 2u and B at
// t = 10 + 4u, each interpolated linearly:
//   u = 0:    pointer (0, 0), (2, 2)     -> mean (1, 1);      robot (0, 0), (0, 0) -> (0, 0)
//   u = 0.25: pointer (0.5, 0), (2.5, 3) -> mean (1.5, 1.5);  robot (-0.5, 1), (0, 1) -> (-0.25, 1)
//   u = 0.5:  pointer (1, 0), (3, 4)     -> mean (2, 2);      robot (-1, 2), (0, 2) -> (-0.5, 2)
//   u = 1:    pointer (1, 2), (4, 6)     -> mean (2.5, 4);    robot (-2, 4), (0, 4) -> (-1, 4)
// C (pointer at (100, 100) throughout) is in the log but not in the scores: it must not count.
// D has t not increasing: the reader rejects it (the scorer did too), and the map goes on.
TEST(MeanMapFromLogs, TheScoredTrialsOfASmallStudyGiveTheHandMean) {
  TempDir dir;
  const fs::path log = dir / "p.csv";
  write_text(log, pointer_log({
                      {"A", 0, kFixed, {{0, 0, 0, 0, 0}, {1, 1, 0, -1, 2}, {2, 1, 2, -2, 4}}},
                      {"B", 0, kFixed, {{10, 2, 2, 0, 0}, {14, 4, 6, 0, 4}}},
                      {"C", 0, kFixed, {{0, 100, 100, 0, 0}, {1, 100, 100, 0, 4}}},
                      {"D", 1, kFixed, {{0, 1, 1, 0, 0}, {0, 1, 1, 0, 0}}},
                  }));
  const auto map = metrics::mean_map({log.string()}, {}, scores_of({"A", "B", "D"}));
  ASSERT_TRUE(map.has_value());
  EXPECT_FALSE(map->canonical);
  EXPECT_EQ(map->trials, 2u);
  EXPECT_EQ(map->layouts, 1u);
  EXPECT_EQ(map->targets, 2u);
  expect_point(map->layout.targets.at(1), 2, 4, "the study's layout, T1");
  ASSERT_EQ(map->panels.size(), 1u);
  EXPECT_EQ(map->panels[0].strategy, "exaggerating");
  EXPECT_EQ(map->panels[0].variant, "main");
  ASSERT_EQ(map->panels[0].means.size(), 1u);
  const metrics::MapMean& m = map->panels[0].means[0];
  EXPECT_EQ(m.true_target, 0u);
  EXPECT_EQ(m.trials, 2u);
  EXPECT_EQ(m.robot_trials, 2u);
  ASSERT_EQ(m.pointer.size(), metrics::kMapPoints);
  ASSERT_EQ(m.robot.size(), metrics::kMapPoints);
  expect_point(m.pointer[0], 1, 1, "pointer, u = 0");
  expect_point(m.pointer[25], 1.5, 1.5, "pointer, u = 0.25");
  expect_point(m.pointer[50], 2, 2, "pointer, u = 0.5");
  expect_point(m.pointer[100], 2.5, 4, "pointer, u = 1");
  expect_point(m.robot[0], 0, 0, "robot, u = 0");
  expect_point(m.robot[25], -0.25, 1, "robot, u = 0.25");
  expect_point(m.robot[50], -0.5, 2, "robot, u = 0.5");
  expect_point(m.robot[100], -1, 4, "robot, u = 1");
}

// Two layouts in the log: the means are taken in the canonical frame (the hand example of
// MapMeans.LayoutsPerRoundAreAveragedInTheCanonicalFrame, read from a log): trial A's pointer goes
// (0, 0) -> (0, 1), B's (-0.5, 1) -> (0, 1); at u = 0.5 the mean is (-0.125, 0.75).
TEST(MeanMapFromLogs, LayoutsPerRoundAreAveragedInTheCanonicalFrame) {
  TempDir dir;
  const fs::path log = dir / "p.csv";
  write_text(log, pointer_log({
                      {"A", 0, {{0, 0}, {{0, 2}, {-1, 2}}}, {{0, 0, 0, 0, 0}, {1, 0, 2, 0, 0}}},
                      {"B", 1, {{1, 1}, {{3, 2}, {3, 1}}}, {{5, 3, 2, 1, 1}, {9, 3, 1, 1, 1}}},
                  }));
  const auto map = metrics::mean_map({log.string()}, {}, scores_of({"A", "B"}));
  ASSERT_TRUE(map.has_value());
  EXPECT_TRUE(map->canonical);
  EXPECT_EQ(map->layouts, 2u);
  ASSERT_EQ(map->panels.size(), 1u);
  const metrics::MapMean& m = map->panels[0].means.at(0);
  EXPECT_EQ(m.trials, 2u);
  expect_point(m.pointer[0], -0.25, 0.5, "u = 0");
  expect_point(m.pointer[50], -0.125, 0.75, "u = 0.5");
  expect_point(m.pointer[100], 0, 1, "u = 1");
  ASSERT_EQ(map->panels[0].decoys.size(), 2u);
  expect_point(map->panels[0].decoys[1], -0.5, 1, "decoy of trial B");
}

TEST(MeanMapFromLogs, APadStudyHasNoMapAndAMapWithoutScoredTrialsIsEmpty) {
  const std::string pad_log = std::string(FEINT_SOURCE_DIR) + "/data/demo/logs/P01.csv.gz";
  EXPECT_FALSE(metrics::mean_map({pad_log}, {}, scores_of({"P01"})).has_value());
  EXPECT_FALSE(metrics::mean_map({}, {}, scores_of({"P01"})).has_value());
  TempDir dir;
  const fs::path log = dir / "p.csv";
  write_text(log, pointer_log({{"A", 0, kFixed, {{0, 0, 0, 0, 0}, {1, 1, 0, -1, 2}}}}));
  const auto map = metrics::mean_map({log.string()}, {}, scores_of({"Z"}));
  ASSERT_TRUE(map.has_value());
  EXPECT_EQ(map->trials, 0u);
  EXPECT_TRUE(map->panels.empty());
}

namespace {

const std::string kDemoK3 = std::string(FEINT_SOURCE_DIR) + "/data/demo-k3";

// data/demo-k3 copied to `dir`, analysed as it is (its feint.toml).
analysis::StudyResults analyze_copy_of_demo_k3(const fs::path& dir) {
  fs::copy(kDemoK3, dir, fs::copy_options::recursive);
  const analysis::Study study = analysis::load_study(dir.string(), {});
  return analysis::analyze(study, "test");
}

}  // namespace

// The analysis computes the map: of the scored trials exactly, per strategy and version as the
// scores label them (the scores file, not the logs, is the count's source).
TEST(AnalyzeMap, TheResultsCarryTheMapOfTheScoredTrials) {
  TempDir dir;
  const analysis::StudyResults r = analyze_copy_of_demo_k3(dir / "study");
  ASSERT_TRUE(r.figures.map.has_value());
  EXPECT_TRUE(r.figures.map_note.empty()) << r.figures.map_note;
  const metrics::MeanMap& map = *r.figures.map;
  EXPECT_TRUE(map.canonical);  // targets placed per round
  EXPECT_EQ(map.targets, 3u);
  EXPECT_EQ(map.trials, r.scores.records.size());
  EXPECT_EQ(map.trials, 480u);
  std::map<std::pair<std::string, std::string>, std::size_t> labelled;
  for (const auto& l : r.figures.labels) ++labelled[{l.strategy, l.variant}];
  ASSERT_EQ(map.panels.size(), labelled.size());
  for (const auto& p : map.panels) {
    EXPECT_EQ(p.trials, (labelled[{p.strategy, p.variant}])) << p.strategy << "/" << p.variant;
    ASSERT_EQ(p.means.size(), 1u);
    // Each trial is mapped so that its start is (0, 0), where its robot path begins.
    expect_point(p.means[0].robot.front(), 0, 0, "the mean robot path starts at the start");
  }
}

// The figure is drawn from the results: with the logs deleted after the analysis, publish still
// draws the map (before, publish read the logs again and said "No map figure: ...").
TEST(AnalyzeMap, TheMapIsDrawnFromTheResultsAfterTheLogsAreGone) {
  TempDir dir;
  const analysis::StudyResults r = analyze_copy_of_demo_k3(dir / "study");
  fs::remove_all(dir / "study" / "logs");
  ASSERT_FALSE(fs::exists(dir / "study" / "logs"));
  const publish::DrawnFigures drawn = publish::draw_figures(r, {"svg"}, (dir / "out").string());
  const publish::RenderedFigure* map = nullptr;
  for (const auto& f : drawn.figures) {
    if (f.name == "map") map = &f;
  }
  for (const auto& n : drawn.notes) EXPECT_EQ(n.find("No map figure"), std::string::npos) << n;
  ASSERT_NE(map, nullptr);
  EXPECT_NE(map->caption.find("(480 trials in all)"), std::string::npos) << map->caption;
  EXPECT_TRUE(fs::exists(dir / "out" / "figures" / "map-2col.svg"));
}

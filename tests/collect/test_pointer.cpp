// feint collect with K targets and the belief as a point held on the map: settings, the log's
// layout, every rejection of a pointer trace, the restart after a crash (docs/collect.md "Many
// targets and a pointer").
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "collect_helpers.hpp"
#include "feint/collect/options.hpp"
#include "feint/collect/server.hpp"
#include "feint/collect/study.hpp"
#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/sim/robot_path.hpp"

namespace feint::collect {
namespace {

namespace fs = std::filesystem;
using namespace testing;

Settings pointer_settings(std::size_t k = 3, LayoutMode layout = LayoutMode::random) {
  Settings s = fast_settings();
  s.targets = k;
  s.layout = layout;
  s.belief = BeliefInput::pointer;
  return s;
}

/// A trace a person could have made: 25 Hz from the first touch, the point moving in a straight
/// line from `from` to `to` over the round, the last sample at its end.
std::vector<PointerSample> pointer_trace(const Round& r, metrics::MapPoint from,
                                         metrics::MapPoint to) {
  std::vector<PointerSample> s;
  const double d = r.duration();
  for (int i = 0;; ++i) {
    const double t = i / 25.0;
    if (t >= d) break;
    s.push_back({t, from.x + (to.x - from.x) * t / d, from.y + (to.y - from.y) * t / d});
  }
  s.push_back({d, to.x, to.y});
  return s;
}

int rejection(const std::function<void()>& f, std::string* code = nullptr) {
  try {
    f();
  } catch (const Rejection& r) {
    if (code) *code = r.code();
    return r.status();
  }
  return 0;
}

TEST(CollectPointer, LogHasTheKTargetColumnsAndTheRoundsLayout) {
  const auto dir = fresh_dir("pointer-log");
  Settings s = pointer_settings(3);
  s.iterations = 12;
  Study study(dir, s);
  study.join("P1");
  std::set<std::size_t> true_targets;
  std::set<std::string> layouts;
  for (int i = 0; i < s.practice + s.iterations; ++i) {
    const Round r = study.start_round("P1");
    ASSERT_EQ(r.layout.targets.size(), 3u);
    const auto& g = r.layout.targets[r.target_index];
    study.submit_round("P1", r.kind, r.iteration, pointer_trace(r, {0, 1}, {g.x, g.y}));
  }
  const auto rows = lines(slurp(dir / "logs" / "P1.csv"));
  ASSERT_GT(rows.size(), 1u);
  EXPECT_EQ(rows[0],
            "participant,condition,iteration,strategy,variant,target,t,belief_x,belief_y,start_x,"
            "start_y,target0_x,target0_y,target1_x,target1_y,target2_x,target2_y,robot_x,robot_y");
  const auto b = map_bounds(s);
  int last = 0;
  std::string trial_fields;
  std::vector<std::string> prev;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto f = io::split_csv_line(rows[i], ',');
    ASSERT_EQ(f.size(), 19u) << rows[i];
    const int it = std::stoi(f[2]);
    // Trial-level fields (strategy .. target, start, targets) constant within a trial.
    std::string trial = f[3] + f[4] + f[5];
    for (int c = 9; c < 17; ++c) trial += "," + f[c];
    if (it != last) {
      // The previous trial ended with the robot at its true target.
      if (!prev.empty()) {
        const int k = std::stoi(prev[5]);
        EXPECT_EQ(prev[17], prev[11 + 2 * k]);
        EXPECT_EQ(prev[18], prev[12 + 2 * k]);
      }
      EXPECT_EQ(it, last + 1);
      last = it;
      trial_fields = trial;
      true_targets.insert(std::stoul(f[5]));
      layouts.insert(trial);
      EXPECT_EQ(f[6], "0");
      EXPECT_EQ(f[7], "0");  // the first touch, at (0, 1)
      EXPECT_EQ(f[8], "1");
      EXPECT_EQ(f[9], "0");  // the start
      EXPECT_EQ(f[10], "0");
    }
    EXPECT_EQ(trial, trial_fields) << "row " << i;
    const double x = std::stod(f[7]), y = std::stod(f[8]);
    EXPECT_TRUE(x >= b.x_min && x <= b.x_max && y >= b.y_min && y <= b.y_max) << rows[i];
    prev = f;
  }
  EXPECT_EQ(last, s.iterations);
  EXPECT_EQ(true_targets, (std::set<std::size_t>{0, 1, 2}));  // K > 2: any target is the true one
  EXPECT_EQ(layouts.size(), static_cast<std::size_t>(s.iterations));  // random: drawn per round
}

TEST(CollectPointer, TheRobotColumnsAreItsExactPositionOnThePlannedPath) {
  const auto dir = fresh_dir("pointer-robot");
  Study study(dir, pointer_settings(4));
  study.join("P1");
  Round r = study.start_round("P1");
  const auto trace = pointer_trace(r, {1, 2}, {-1, 3});
  study.submit_round("P1", r.kind, r.iteration, trace);
  const auto rows = lines(slurp(dir / "practice" / "P1.csv"));
  ASSERT_EQ(rows.size(), trace.size() + 1);
  for (std::size_t i = 0; i < trace.size(); ++i) {
    const auto f = io::split_csv_line(rows[i + 1], ',');
    const auto p = sim::position_on_path(r.waypoints, 8.0, trace[i].t);
    EXPECT_EQ(f[f.size() - 2], sim::format_metres(p.x));
    EXPECT_EQ(f[f.size() - 1], sim::format_metres(p.y));
    EXPECT_EQ(f[6], io::format_double(trace[i].t));
    EXPECT_EQ(f[7], io::format_double(trace[i].x));
  }
  EXPECT_EQ(r.waypoints.back().x, r.layout.targets[r.target_index].x);
}

TEST(CollectPointer, EveryInvalidTraceIsRefusedAndNothingIsWritten) {
  const auto dir = fresh_dir("pointer-reject");
  Settings s = pointer_settings(3);
  s.max_samples = 500;
  Study study(dir, s);
  study.join("P1");
  const Round r = study.start_round("P1");
  const auto good = pointer_trace(r, {0, 1}, {1, 3});
  const auto b = map_bounds(s);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto with = [&](std::size_t i, PointerSample p) {
    auto t = good;
    t[i] = p;
    return t;
  };
  const std::size_t mid = good.size() / 2;
  const double tm = good[mid].t;
  std::vector<std::pair<std::string, std::vector<PointerSample>>> bad = {
      {"one sample", {good.front()}},
      {"first t not 0", with(0, {0.01, 0, 1})},
      {"t NaN", with(mid, {nan, 0, 1})},
      {"x NaN", with(mid, {tm, nan, 1})},
      {"y infinite", with(mid, {tm, 0, inf})},
      {"x left of the map", with(mid, {tm, b.x_min - 1e-9, 1})},
      {"x right of the map", with(mid, {tm, b.x_max + 1e-9, 1})},
      {"y below the map", with(mid, {tm, 0, b.y_min - 1e-9})},
      {"y above the map", with(mid, {tm, 0, b.y_max + 1e-9})},
      {"times equal", with(mid, {good[mid - 1].t, 0, 1})},
      {"times decreasing", with(mid, {good[mid - 1].t - 0.001, 0, 1})},
      {"last before the end", with(good.size() - 1, {r.duration() - 1e-9, 0, 1})},
  };
  for (const auto& [what, trace] : bad) {
    std::string code;
    EXPECT_EQ(rejection([&] { study.submit_round("P1", r.kind, r.iteration, trace); }, &code), 422)
        << what;
    EXPECT_EQ(code, "invalid_trace") << what;
  }
  std::vector<PointerSample> many(501, good.back());
  std::string code;
  EXPECT_EQ(rejection([&] { study.submit_round("P1", r.kind, r.iteration, many); }, &code), 413);
  EXPECT_EQ(code, "too_many_samples");
  // The pad's trace in a pointer study, and the pointer's in a pad study.
  EXPECT_EQ(rejection([&] {
              study.submit_round("P1", r.kind, r.iteration, std::vector<PadSample>{{0, 0.5}});
            }),
            400);
  EXPECT_FALSE(fs::exists(dir / "practice" / "P1.csv"));
  // The points on the map's edges are inside it; the same round then saves.
  auto edge = good;
  edge[1] = {edge[1].t, b.x_min, b.y_max};
  edge[2] = {edge[2].t, b.x_max, b.y_min};
  EXPECT_EQ(study.submit_round("P1", r.kind, r.iteration, edge).practice_saved, 1);

  const auto pad_dir = fresh_dir("pad-reject");
  Study pad(pad_dir, fast_settings());
  pad.join("P1");
  const Round pr = pad.start_round("P1");
  EXPECT_EQ(rejection([&] { pad.submit_round("P1", pr.kind, pr.iteration, good); }), 400);
}

TEST(CollectPointer, TheHttpBodyIsThreeNumbersPerLine) {
  const auto dir = fresh_dir("pointer-http");
  Study study(dir, pointer_settings(3));
  auto post = [&](const std::string& target, const std::string& body) {
    return handle_request(study, "tok", "POST", target, body);
  };
  ASSERT_EQ(post("/api/join?participant=P1", "").status, 200);
  const auto start = post("/api/round/start?participant=P1", "");
  ASSERT_EQ(start.status, 200);
  EXPECT_NE(start.body.find("\"layout\":[["), std::string::npos) << start.body;
  const std::string q = "/api/round/submit?participant=P1&kind=practice&iteration=1";
  for (const std::string body : {"0,0.5\n1,0.5\n", "0,1,2\n1,a,2\n", "0,1,2,3\n", "0;1;2\n"}) {
    const auto r = post(q, body);
    EXPECT_EQ(r.status, 400) << body;
    EXPECT_NE(r.body.find("malformed"), std::string::npos) << r.body;
  }
  const auto joined = post("/api/join?participant=P1", "");
  EXPECT_NE(joined.body.find("\"belief\":\"pointer\",\"targets\":3"), std::string::npos)
      << joined.body;
  EXPECT_NE(joined.body.find("\"map\":{\"x_min\":-4,\"x_max\":4,\"y_min\":-1,\"y_max\":6}"),
            std::string::npos)
      << joined.body;
}

TEST(CollectPointer, ARestartResumesWithTheSameLayoutsAndRepairsACutRound) {
  const auto dir = fresh_dir("pointer-restart");
  const Settings s = pointer_settings(3);
  std::vector<std::string> planned;
  {
    Study study(dir, s);
    study.join("P1");
    for (int i = 0; i < s.practice + 2; ++i) {
      const Round r = study.start_round("P1");
      study.submit_round("P1", r.kind, r.iteration, pointer_trace(r, {0, 1}, {0, 3}));
    }
    for (int it = 1; it <= s.iterations; ++it) {
      const Round r = study.plan_round(0, 0, RoundKind::main, it);
      planned.push_back(fmt::format("{},{},{}", r.target_index, r.layout.targets[0].x,
                                    r.layout.targets[2].y));
    }
  }
  // A crash in the middle of round 3's write: its first rows and half a line.
  const fs::path log = dir / "logs" / "P1.csv";
  const std::string before = slurp(log);
  const auto two = lines(before);
  {
    std::ofstream out(log, std::ios::app | std::ios::binary);
    const std::string row = two.back();
    out << "P1" << row.substr(row.find(',')).replace(row.find(",2,") - row.find(','), 3, ",3,")
        << "\nP1,adap";
  }
  Study again(dir, s);
  EXPECT_EQ(again.status("P1")->rounds_saved, 2);
  EXPECT_EQ(slurp(log), before);  // the complete rounds, exactly
  EXPECT_EQ(fs::is_directory(dir / "collect" / "damaged"), true);
  for (int it = 1; it <= s.iterations; ++it) {
    const Round r = again.plan_round(0, 0, RoundKind::main, it);
    EXPECT_EQ(fmt::format("{},{},{}", r.target_index, r.layout.targets[0].x, r.layout.targets[2].y),
              planned[static_cast<std::size_t>(it - 1)]);
  }
  const Round r3 = again.start_round("P1");
  EXPECT_EQ(r3.iteration, 3);
  again.submit_round("P1", r3.kind, r3.iteration, pointer_trace(r3, {0, 1}, {0, 3}));
  EXPECT_EQ(again.status("P1")->rounds_saved, 3);
}

TEST(CollectPointer, APadLogInAPointerStudyStopsTheServer) {
  const auto dir = fresh_dir("pointer-mixed");
  {
    Study pad(dir, fast_settings());
    pad.join("P1");
    play_all(pad, "P1");
  }
  EXPECT_THROW(Study(dir, pointer_settings(2, LayoutMode::fixed)), InvalidData);
}

TEST(CollectPointerOptions, PadIsTheDefaultForTwoTargetsAndRefusedForMore) {
  const auto dir = fresh_dir("pointer-options");
  CollectOptions o;
  EXPECT_EQ(study_settings(o, dir).belief, BeliefInput::pad);
  o.targets = 3;
  EXPECT_EQ(study_settings(o, dir).belief, BeliefInput::pointer);
  o.belief = "pad";
  EXPECT_THROW(study_settings(o, dir), UsageError);
  o.targets = 2;
  o.layout = "random";
  EXPECT_THROW(study_settings(o, dir), UsageError);
  o.belief = "";
  EXPECT_EQ(study_settings(o, dir).belief, BeliefInput::pointer);
  o.layout = "scattered";
  EXPECT_THROW(study_settings(o, dir), UsageError);
  o.layout = "fixed";
  o.belief = "mouse";
  EXPECT_THROW(study_settings(o, dir), UsageError);
  // Settings made in code are checked by the Study too.
  Settings s = fast_settings();
  s.targets = 3;
  EXPECT_THROW(Study(fresh_dir("pointer-pad3"), s), UsageError);
  // Six targets in a 4 m row are 0.8 m apart, closer than the minimum spacing of 1 m.
  s = pointer_settings(6, LayoutMode::fixed);
  EXPECT_THROW(Study(fresh_dir("pointer-crowded"), s), UsageError);
  s.geometry.target_distance = 5;
  EXPECT_NO_THROW(Study(fresh_dir("pointer-row"), s));
  EXPECT_EQ(fixed_layout(s).targets[1].x, -1.5);
}

TEST(CollectPointerOptions, TheStudyTomlPinsTheDesignAtItsEnd) {
  Settings s = pointer_settings(3);
  const std::string toml = study_toml(s, "test");
  const auto at = toml.find("\n[collect]\ntargets = 3\nlayout = \"random\"\nbelief = \"pointer\"\n");
  ASSERT_NE(at, std::string::npos) << toml;
  EXPECT_GT(at, toml.find("likert-scale"));  // top-level keys stay before the section
  EXPECT_EQ(study_toml(fast_settings(), "test").find("[collect]"), std::string::npos);
}

}  // namespace
}  // namespace feint::collect

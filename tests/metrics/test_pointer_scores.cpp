// Scoring logs of K targets and a pointer (docs/many-targets.md "Studies of K targets"): at K = 2
// on the paper's layout, with the pointer on the line between the targets, every trial of a
// participant of data/demo scores exactly as its pad log (1e-12), through the same score_each.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <tuple>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/pointer_trace.hpp"
#include "feint/io/trace.hpp"
#include "feint/metrics/belief_point.hpp"
#include "feint/metrics/score.hpp"

namespace fs = std::filesystem;
using namespace feint;

namespace {

using Key = std::tuple<std::string, std::string, long long>;

std::map<Key, metrics::TrialScore> score_all(const std::string& file, const metrics::ScoreSettings& s) {
  std::map<Key, metrics::TrialScore> out;
  metrics::score_each({file}, s, [&](const io::Trial& t, const metrics::TrialScore& sc) {
    out[{t.participant, t.condition, t.iteration}] = sc;
  });
  return out;
}

// The pad log's trials written as a log of 2 targets: the pointer at pad_point(mu).
std::string as_pointer_log(const std::string& pad_log) {
  const metrics::Layout layout = metrics::paper_layout();
  std::string text =
      "participant,condition,iteration,strategy,variant,target,t,belief_x,belief_y,start_x,start_y,target0_x,"
      "target0_y,target1_x,target1_y,robot_x,robot_y\n";
  io::TraceReader r({pad_log}, {});
  io::Trial t;
  while (r.next(t)) {
    for (std::size_t i = 0; i < t.times.size(); ++i) {
      const metrics::MapPoint b = metrics::pad_point(layout, t.pads[i]);
      text += fmt::format("{},{},{},{},{},{},{:.17g},{:.17g},{:.17g},0,0,-2,4,2,4,0,0\n", t.participant,
                          t.condition, t.iteration, t.strategy, t.variant, t.target, t.times[i], b.x, b.y);
    }
  }
  return text;
}

// `speed_known`: both logs have the speed (the pad log's pad_speed column; the pointer log has none,
// so in the raw normalisation its overspeed count is -1, unknown).
void expect_same(const std::map<Key, metrics::TrialScore>& pad, const std::map<Key, metrics::TrialScore>& point,
                 bool speed_known) {
  ASSERT_EQ(pad.size(), point.size());
  ASSERT_GT(pad.size(), 10U);
  for (const auto& [k, a] : pad) {
    const auto& b = point.at(k);
    EXPECT_EQ(a.n_samples, b.n_samples);
    EXPECT_NEAR(a.duration, b.duration, 1e-12);
    EXPECT_NEAR(a.error, b.error, 1e-12);
    EXPECT_NEAR(a.confusion, b.confusion, 1e-12);
    EXPECT_EQ(a.reversals, b.reversals);
    EXPECT_EQ(std::isnan(a.reversal_time), std::isnan(b.reversal_time));
    if (!std::isnan(a.reversal_time)) {
      EXPECT_NEAR(a.reversal_time, b.reversal_time, 1e-12);
    }
    EXPECT_EQ(b.overspeed_segments, speed_known ? a.overspeed_segments : -1);
  }
}

}  // namespace

TEST(PointerScores, TwoTargetsOnThePaperLayoutScoreAsThePadLog) {
  const std::string pad_log = std::string(FEINT_SOURCE_DIR) + "/data/demo/logs/P01.csv.gz";
  const fs::path dir = fs::temp_directory_path() / ("feint-test-pointer-scores-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string pointer_log = (dir / "P01-pointer.csv").string();
  std::ofstream(pointer_log, std::ios::binary) << as_pointer_log(pad_log);
  ASSERT_TRUE(io::is_pointer_log(pointer_log));

  metrics::ScoreSettings raw;
  raw.check_durations = false;
  raw.on_warning = [](const std::string&) {};
  expect_same(score_all(pad_log, raw), score_all(pointer_log, raw), false);

  metrics::ScoreSettings speed = raw;
  speed.metrics.norm = metrics::ConfusionNorm::speed;
  speed.metrics.pad_speed = 0.8;
  expect_same(score_all(pad_log, speed), score_all(pointer_log, speed), true);
  fs::remove_all(dir);
}

TEST(PointerScores, SpeedNormalisationWithoutAPointerSpeedSaysHowToGiveIt) {
  const fs::path dir = fs::temp_directory_path() / ("feint-test-pointer-speed-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string f = (dir / "k.csv").string();
  std::ofstream(f, std::ios::binary)
      << "participant,iteration,target,t,belief_x,belief_y,start_x,start_y,target0_x,target0_y,target1_x,"
         "target1_y\nP1,1,0,0,0,1,0,0,-2,4,2,4\nP1,1,0,1,-1,2,0,0,-2,4,2,4\n";
  metrics::ScoreSettings s;
  s.metrics.norm = metrics::ConfusionNorm::speed;
  try {
    score_all(f, s);
    ADD_FAILURE() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--pad-speed"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

namespace {

// The cells of the scores file's first data row, by header name.
std::map<std::string, std::string> first_row(const std::string& csv) {
  std::istringstream in(csv);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  std::map<std::string, std::string> out;
  std::istringstream h(header), r(row);
  for (std::string name, cell; std::getline(h, name, ',');) {
    cell.clear();
    std::getline(r, cell, ',');
    out[name] = cell;
  }
  return out;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

// docs/pointer-measures.md "In the scores table": the worked example's trace (metres, seconds) on a
// layout of scale 8 (targets (-4, 4), (4, 4), (0, 8)): distances are read in layout scales, so AUC
// = 6 / 8^2, MAD = 2 sqrt2 / 8; flips, initiation and idle times as in the worked example.
TEST(PointerScores, ScoresFileOfAPointerLogHasTheMousetrapColumnsInLayoutScales) {
  const fs::path dir = fs::temp_directory_path() / ("feint-test-pointer-mt-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string f = (dir / "k.csv").string();
  std::ofstream out(f, std::ios::binary);
  out << "participant,iteration,target,t,belief_x,belief_y,start_x,start_y,target0_x,target0_y,target1_x,"
         "target1_y,target2_x,target2_y\n";
  const double t[] = {0, 0.010, 0.030, 0.045, 0.055, 0.060}, x[] = {0, 0, 2, 1, -1, -4}, y[] = {0, 0, 2, 1, 3, 4};
  for (int i = 0; i < 6; ++i) out << fmt::format("P1,1,0,{},{},{},0,0,-4,4,4,4,0,8\n", t[i], x[i], y[i]);
  out.close();
  metrics::ScoreSettings s;
  const std::string scores = (dir / "scores.csv").string();
  metrics::score_to_file({f}, s, scores);
  const auto row = first_row(read_text(scores));
  ASSERT_EQ(row.count("auc"), 1U) << read_text(scores);
  EXPECT_NEAR(std::stod(row.at("auc")), 6.0 / 64.0, 1e-12);
  EXPECT_NEAR(std::stod(row.at("mad")), 2 * std::sqrt(2.0) / 8, 1e-12);
  EXPECT_NEAR(std::stod(row.at("mad_time")), 0.030, 1e-12);
  EXPECT_EQ(row.at("xpos_flips"), "1");
  EXPECT_EQ(row.at("ypos_flips"), "2");
  EXPECT_NEAR(std::stod(row.at("initiation_time")), 0.010, 1e-12);
  EXPECT_NEAR(std::stod(row.at("idle_time")), 0.010, 1e-12);
  EXPECT_EQ(row.at("final_pad"), "");  // a pad's measure: not defined for a point
  fs::remove_all(dir);
}

// A pad log's scores file keeps its columns (the pointer measures are only for pointer logs).
TEST(PointerScores, ScoresFileOfAPadLogHasNoPointerColumns) {
  const fs::path dir = fs::temp_directory_path() / ("feint-test-pad-cols-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string f = (dir / "pad.csv").string();
  std::ofstream(f, std::ios::binary) << "participant,iteration,target,t,pad\nP1,1,1,0,0.5\nP1,1,1,1,0.9\n";
  const std::string scores = (dir / "scores.csv").string();
  metrics::score_to_file({f}, metrics::ScoreSettings{}, scores);
  const std::string text = read_text(scores);
  std::string header = text.substr(0, text.find('\n'));
  std::string expected;
  for (const auto& c : metrics::score_columns()) expected += (expected.empty() ? "" : ",") + c;
  EXPECT_EQ(header, expected);
  fs::remove_all(dir);
}

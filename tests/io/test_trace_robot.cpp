// The optional robot_x / robot_y columns of pad-trace logs (docs/formats.md): read when
// asked, renameable, both or neither, every value a number; ignored when not asked for.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/io/trace.hpp"

namespace fs = std::filesystem;
using feint::io::Rejection;
using feint::io::TraceOptions;
using feint::io::TraceReader;
using feint::io::Trial;

namespace {

std::string write(const std::string& name, const std::string& content) {
  const fs::path d = fs::temp_directory_path() / ("feint-test-robot-" + std::to_string(::getpid()));
  fs::create_directories(d);
  const fs::path p = d / name;
  std::ofstream(p, std::ios::binary) << content;
  return p.string();
}

TraceOptions robot_options() {
  TraceOptions o;
  o.read_robot_path = true;
  return o;
}

std::vector<Trial> read_all(const std::string& file, TraceOptions opt) {
  TraceReader r({file}, std::move(opt));
  std::vector<Trial> out;
  Trial t;
  while (r.next(t)) out.push_back(t);
  return out;
}

std::string strict_error(const std::string& file, TraceOptions opt) {
  try {
    read_all(file, std::move(opt));
  } catch (const feint::InvalidData& e) {
    return e.what();
  }
  return {};
}

const char* kLog =
    "participant,iteration,target,t,pad,robot_x,robot_y\n"
    "P1,1,right,0,0.5,0,0\n"
    "P1,1,right,0.04,0.5,0.03,0.04\n"
    "P1,1,right,0.08,0.52,-0.25,0.08\n"
    "P1,2,left,0,0.5,0,0\n"
    "P1,2,left,0.04,0.49,-0.02,1e-1\n";

}  // namespace

TEST(TraceRobot, ReadsBothColumnsPerSample) {
  const auto trials = read_all(write("robot.csv", kLog), robot_options());
  ASSERT_EQ(trials.size(), 2U);
  EXPECT_EQ(trials[0].robot_x, (std::vector<double>{0, 0.03, -0.25}));
  EXPECT_EQ(trials[0].robot_y, (std::vector<double>{0, 0.04, 0.08}));
  EXPECT_EQ(trials[1].robot_x, (std::vector<double>{0, -0.02}));
  EXPECT_EQ(trials[1].robot_y, (std::vector<double>{0, 0.1}));
}

TEST(TraceRobot, NotReadUnlessAskedAndEmptyWithoutColumns) {
  const auto ignored = read_all(write("robot.csv", kLog), TraceOptions{});
  ASSERT_EQ(ignored.size(), 2U);
  EXPECT_TRUE(ignored[0].robot_x.empty());
  // Not asked for, a bad robot value does not matter (an extra column).
  const auto bad = write("bad_ignored.csv", "participant,iteration,target,t,pad,robot_x,robot_y\n"
                                            "P1,1,right,0,0.5,oops,0\nP1,1,right,1,0.6,0,0\n");
  EXPECT_EQ(read_all(bad, TraceOptions{}).size(), 1U);
  const auto none = write("none.csv", "participant,iteration,target,t,pad\nP1,1,1,0,0.5\nP1,1,1,1,1\n");
  const auto trials = read_all(none, robot_options());
  ASSERT_EQ(trials.size(), 1U);
  EXPECT_TRUE(trials[0].robot_x.empty());
  EXPECT_TRUE(trials[0].robot_y.empty());
}

TEST(TraceRobot, ColumnsCanBeRenamed) {
  const auto f = write("renamed.csv", "participant,iteration,target,t,pad,rx,ry\n"
                                      "P1,1,right,0,0.5,0,0\nP1,1,right,1,0.6,0.5,0.25\n");
  auto opt = robot_options();
  opt.column_map = {{"robot_x", "rx"}, {"robot_y", "ry"}};
  const auto trials = read_all(f, opt);
  ASSERT_EQ(trials.size(), 1U);
  EXPECT_EQ(trials[0].robot_x, (std::vector<double>{0, 0.5}));
  EXPECT_EQ(trials[0].robot_y, (std::vector<double>{0, 0.25}));
}

TEST(TraceRobot, OneColumnWithoutTheOtherIsAFileError) {
  const auto f = write("half.csv", "participant,iteration,target,t,pad,robot_x\n"
                                   "P1,1,right,0,0.5,0\nP1,1,right,1,0.6,0.5\n");
  const std::string msg = strict_error(f, robot_options());
  EXPECT_NE(msg.find("half.csv:1: column 'robot_x' without 'robot_y'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--map robot_y=COLUMN"), std::string::npos) << msg;
}

TEST(TraceRobot, BadValueNamesFileLineColumnAndTrialStrictOrLenient) {
  const std::string content =
      "participant,iteration,target,t,pad,robot_x,robot_y\n"
      "P1,1,right,0,0.5,0,0\nP1,1,right,1,0.6,nan,0.2\n"
      "P1,2,right,0,0.5,0,0\nP1,2,right,1,0.6,0.1,\n"
      "P1,3,right,0,0.5,0,0\nP1,3,right,1,0.6,0.1,0.2\n";
  const auto f = write("badrobot.csv", content);
  const std::string msg = strict_error(f, robot_options());
  EXPECT_NE(msg.find("badrobot.csv:3: column 'robot_x': 'nan' is not a number (expected the "
                     "robot's position in metres) (trial P1/1)"),
            std::string::npos)
      << msg;
  std::vector<Rejection> rejected;
  auto opt = robot_options();
  opt.on_reject = [&](const Rejection& r) { rejected.push_back(r); };
  const auto trials = read_all(f, opt);
  ASSERT_EQ(trials.size(), 1U);
  EXPECT_EQ(trials[0].iteration, 3);
  ASSERT_EQ(rejected.size(), 2U);
  EXPECT_NE(rejected[1].reason.find("badrobot.csv:5: column 'robot_y': empty"), std::string::npos)
      << rejected[1].reason;
  EXPECT_EQ(rejected[0].rows + rejected[1].rows + trials[0].rows, 6U);
}

TEST(TraceRobot, UnsortedModeKeepsEachTrialsPositionsWithItsSamples) {
  const auto f = write("interleaved.csv", "participant,iteration,target,t,pad,robot_x,robot_y\n"
                                          "P1,1,right,0,0.5,0,0\n"
                                          "P1,2,left,0,0.5,0,0\n"
                                          "P1,1,right,1,0.6,0.25,1\n"
                                          "P1,2,left,1,0.4,-0.25,2\n");
  auto opt = robot_options();
  opt.unsorted = true;
  const auto trials = read_all(f, opt);
  ASSERT_EQ(trials.size(), 2U);
  EXPECT_EQ(trials[0].robot_x, (std::vector<double>{0, 0.25}));
  EXPECT_EQ(trials[0].robot_y, (std::vector<double>{0, 1}));
  EXPECT_EQ(trials[1].robot_x, (std::vector<double>{0, -0.25}));
  EXPECT_EQ(trials[1].robot_y, (std::vector<double>{0, 2}));
}

// Logs of K targets and a pointer (docs/formats.md "Logs of K targets and a pointer"): read into
// trials, and every rejection names the file, the line and the column.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/io/pointer_trace.hpp"

namespace fs = std::filesystem;
using feint::io::PointerTraceReader;
using feint::io::Rejection;
using feint::io::TraceOptions;
using feint::io::Trial;

namespace {

std::string write(const std::string& name, const std::string& content) {
  const fs::path d = fs::temp_directory_path() / ("feint-test-pointer-" + std::to_string(::getpid()));
  fs::create_directories(d);
  const fs::path p = d / name;
  std::ofstream(p, std::ios::binary) << content;
  return p.string();
}

std::vector<Trial> read_all(const std::string& file, TraceOptions opt = {}) {
  PointerTraceReader r({file}, std::move(opt));
  std::vector<Trial> out;
  Trial t;
  while (r.next(t)) out.push_back(t);
  return out;
}

std::string strict_error(const std::string& file) {
  try {
    read_all(file);
  } catch (const feint::InvalidData& e) {
    return e.what();
  }
  return "(no error)";
}

const std::string kHeader =
    "participant,condition,iteration,strategy,variant,target,t,belief_x,belief_y,start_x,start_y,"
    "target0_x,target0_y,target1_x,target1_y,target2_x,target2_y,robot_x,robot_y\n";

std::string row(const std::string& it, const std::string& target, const std::string& t, const std::string& bx,
                const std::string& layout = "0,0,-2,4,0,4,2,4") {
  return "P1,adaptive," + it + ",optimal,main," + target + "," + t + "," + bx + ",1," + layout + ",0,0\n";
}

}  // namespace

TEST(PointerTrace, ReadsKTargetsTheLayoutAndThePointer) {
  const auto f = write("ok.csv", kHeader + row("1", "2", "0", "0") + row("1", "2", "0.04", "0.1") +
                                     row("2", "0", "0", "0", "0,0,-1,3,0,5,3,2") +
                                     row("2", "0", "0.5", "-0.5", "0,0,-1,3,0,5,3,2"));
  EXPECT_TRUE(feint::io::is_pointer_log(f));
  const auto trials = read_all(f);
  ASSERT_EQ(trials.size(), 2U);
  EXPECT_EQ(trials[0].target_index, 2U);
  EXPECT_EQ(trials[0].target, 2.0);
  EXPECT_EQ(trials[0].targets_x, (std::vector<double>{-2, 0, 2}));
  EXPECT_EQ(trials[0].targets_y, (std::vector<double>{4, 4, 4}));
  EXPECT_EQ(trials[0].belief_x, (std::vector<double>{0, 0.1}));
  EXPECT_EQ(trials[0].times, (std::vector<double>{0, 0.04}));
  EXPECT_TRUE(trials[0].pads.empty());
  EXPECT_EQ(trials[1].targets_x, (std::vector<double>{-1, 0, 3}));
  EXPECT_EQ(trials[1].robot_y, (std::vector<double>{0, 0}));
}

TEST(PointerTrace, PadLogsAreNotPointerLogs) {
  EXPECT_FALSE(feint::io::is_pointer_log(write("pad.csv", "participant,iteration,target,t,pad,belief_x\nP,1,1,0,0.5,0\n")));
  EXPECT_FALSE(feint::io::is_pointer_log("-"));
}

TEST(PointerTrace, RejectsFewerThanTwoTargets) {
  const auto f = write("k1.csv",
                       "participant,iteration,target,t,belief_x,belief_y,start_x,start_y,target0_x,target0_y\n"
                       "P1,1,0,0,0,1,0,0,1,1\n");
  const auto msg = strict_error(f);
  EXPECT_NE(msg.find("k1.csv:1: column 'target1_x': missing: a log of K targets needs K >= 2"), std::string::npos)
      << msg;
}

TEST(PointerTrace, RejectsAMissingPairAndAGap) {
  const auto half = write("half.csv",
                          "participant,iteration,target,t,belief_x,belief_y,start_x,start_y,target0_x,target0_y,"
                          "target1_x\nP1,1,0,0,0,1,0,0,1,1,2\n");
  auto msg = strict_error(half);
  EXPECT_NE(msg.find("half.csv:1: column 'target1_x': without 'target1_y'"), std::string::npos) << msg;
  const auto gap = write("gap.csv",
                         "participant,iteration,target,t,belief_x,belief_y,start_x,start_y,target0_x,target0_y,"
                         "target2_x,target2_y\nP1,1,0,0,0,1,0,0,1,1,2,2\n");
  msg = strict_error(gap);
  EXPECT_NE(msg.find("gap.csv:1: column 'target1_x': missing"), std::string::npos) << msg;
}

TEST(PointerTrace, RejectsNonFiniteValues) {
  auto msg = strict_error(write("nan.csv", kHeader + row("1", "2", "0", "0") + row("1", "2", "0.04", "nan")));
  EXPECT_NE(msg.find("nan.csv:3: column 'belief_x': 'nan' is not a finite number (trial P1/adaptive/1)"),
            std::string::npos)
      << msg;
  msg = strict_error(write("inf.csv", kHeader + row("1", "2", "0", "0", "0,0,-2,4,0,4,inf,4")));
  EXPECT_NE(msg.find("inf.csv:2: column 'target2_x': 'inf' is not a finite number"), std::string::npos) << msg;
}

TEST(PointerTrace, RejectsATargetIndexOutOfRange) {
  for (const std::string bad : {"3", "-1", "right", "0.5"}) {
    const auto msg = strict_error(write("index.csv", kHeader + row("1", bad, "0", "0") + row("1", bad, "1", "0")));
    EXPECT_NE(msg.find("index.csv:2: column 'target': '" + bad + "' is not a target index (expected 0 to 2"),
              std::string::npos)
        << msg;
  }
}

TEST(PointerTrace, RejectsALayoutThatChangesWithinATrial) {
  const auto msg = strict_error(write("moves.csv", kHeader + row("1", "1", "0", "0") +
                                                       row("1", "1", "0.04", "0", "0,0,-2,4,0,4.5,2,4")));
  EXPECT_NE(msg.find("moves.csv:3: column 'target1_y': '4.5' differs from '4' on line 2 (a trial-level field"),
            std::string::npos)
      << msg;
  const auto target = strict_error(write("target.csv", kHeader + row("1", "1", "0", "0") + row("1", "2", "1", "0")));
  EXPECT_NE(target.find("target.csv:3: column 'target': '2' differs from '1'"), std::string::npos) << target;
}

TEST(PointerTrace, RejectsCoincidentTargetsAndATargetAtTheStart) {
  auto msg = strict_error(
      write("same.csv", kHeader + row("1", "1", "0", "0", "0,0,-2,4,2,4,2,4") + row("1", "1", "1", "0", "0,0,-2,4,2,4,2,4")));
  EXPECT_NE(msg.find("same.csv:2: column 'target2_x': targets 1 and 2 are at one point (2, 4)"), std::string::npos)
      << msg;
  msg = strict_error(
      write("start.csv", kHeader + row("1", "1", "0", "0", "0,0,-2,4,0,0,2,4") + row("1", "1", "1", "0", "0,0,-2,4,0,0,2,4")));
  EXPECT_NE(msg.find("start.csv:2: column 'target1_x': target 1 is at the start (0, 0)"), std::string::npos) << msg;
}

TEST(PointerTrace, RejectsTimesNotIncreasingAndOneSampleTrials) {
  auto msg = strict_error(write("time.csv", kHeader + row("1", "1", "0.5", "0") + row("1", "1", "0.5", "0")));
  EXPECT_NE(msg.find("time.csv:3: column 't': 0.5 is not after the previous time"), std::string::npos) << msg;
  msg = strict_error(write("one.csv", kHeader + row("1", "1", "0", "0") + row("2", "1", "0", "0") + row("2", "1", "1", "0")));
  EXPECT_NE(msg.find("one.csv:2: column 't': 1 sample(s); a trial needs at least 2 (trial P1/adaptive/1)"),
            std::string::npos)
      << msg;
}

TEST(PointerTrace, LenientModeRejectsTheWholeTrialAndKeepsReading) {
  std::vector<Rejection> rejected;
  TraceOptions o;
  o.on_reject = [&](const Rejection& r) { rejected.push_back(r); };
  const auto f = write("lenient.csv", kHeader + row("1", "2", "0", "0") + row("1", "2", "0.04", "x") +
                                          row("2", "1", "0", "0") + row("2", "1", "1", "0"));
  PointerTraceReader r({f}, o);
  std::vector<Trial> trials;
  Trial t;
  while (r.next(t)) trials.push_back(t);
  ASSERT_EQ(trials.size(), 1U);
  EXPECT_EQ(trials[0].iteration, 2);
  ASSERT_EQ(rejected.size(), 1U);
  EXPECT_EQ(rejected[0].rows, 2U);
  EXPECT_NE(rejected[0].reason.find("lenient.csv:3: column 'belief_x'"), std::string::npos) << rejected[0].reason;
  EXPECT_EQ(r.rows_read(), r.rows_in_trials() + r.rows_rejected());
}

TEST(PointerTrace, SpeedNormalisationWithoutASpeedIsAUsageError) {
  TraceOptions o;
  o.require_pad_speed = true;
  EXPECT_THROW(PointerTraceReader({write("ok2.csv", kHeader)}, o), feint::UsageError);
}

// The loader options of pad logs that apply to pointer logs: --iteration-base (0-based iterations
// become 1-based; rows of a trial stay one trial), a time unit, and the condition column's checks.
TEST(PointerTrace, ZeroBasedIterationsAreShiftedAsForPadLogs) {
  const auto f = write("base0.csv", kHeader + row("0", "2", "0", "0") + row("0", "2", "40", "0.1") +
                                        row("1", "0", "0", "0") + row("1", "0", "40", "0.2"));
  TraceOptions opt;
  opt.iteration_base = 0;
  opt.time_divisor = 1000;  // milliseconds
  const auto trials = read_all(f, opt);
  ASSERT_EQ(trials.size(), 2U);
  EXPECT_EQ(trials[0].iteration, 1);
  EXPECT_EQ(trials[1].iteration, 2);
  EXPECT_EQ(trials[0].times.size(), 2U);
  EXPECT_DOUBLE_EQ(trials[0].times[1], 0.04);
  // 1-based: an iteration 0 is invalid, named.
  opt.iteration_base = 1;
  try {
    read_all(f, opt);
    ADD_FAILURE() << "no error";
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("iteration 0, but the iterations are 1-based"), std::string::npos) << e.what();
  }
}

TEST(PointerTrace, AFileWithoutAConditionColumnIsNotPooledSilently) {
  const std::string header =
      "participant,group,iteration,target,t,belief_x,belief_y,start_x,start_y,target0_x,target0_y,target1_x,target1_y\n";
  const auto f = write("group.csv", header + "P1,a,1,0,0,0,1,0,0,-2,4,2,4\nP1,a,1,0,1,-1,2,0,0,-2,4,2,4\n");
  const std::string e = strict_error(f);
  EXPECT_NE(e.find("column 'group' (column 2) looks like the condition"), std::string::npos) << e;
  EXPECT_NE(e.find("--map condition=group"), std::string::npos) << e;
  TraceOptions pool;
  pool.single_condition = true;
  EXPECT_EQ(read_all(f, pool).size(), 1U);
  TraceOptions two;
  two.expected_conditions = {"adaptive", "random"};
  const auto g = write("nocond.csv", "participant,iteration,target,t,belief_x,belief_y,start_x,start_y,target0_x,"
                                     "target0_y,target1_x,target1_y\nP1,1,0,0,0,1,0,0,-2,4,2,4\n");
  try {
    read_all(g, two);
    ADD_FAILURE() << "no error";
  } catch (const feint::InvalidData& e2) {
    EXPECT_NE(std::string(e2.what()).find("the study has 2 conditions (adaptive, random)"), std::string::npos)
        << e2.what();
  }
}

TEST(PointerTrace, ParticipantsNamedByThePathAreRefusedNotIgnored) {
  const auto f = write("p.csv", kHeader + row("1", "2", "0", "0") + row("1", "2", "0.04", "0.1"));
  TraceOptions opt;
  opt.participant_from_path = "filename";
  EXPECT_THROW(read_all(f, opt), feint::UsageError);
}

// The observer fitted to logs (feint/sim/observer_logs.hpp): the logs read with the loader options
// of `feint score` (io::TraceOptions: column map, time unit, --on-error), the path source stated
// truly, the file named once per left-out trial, and no fit without a usable trial.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "feint/error.hpp"
#include "feint/sim/observer_logs.hpp"

using namespace feint::sim;
namespace fs = std::filesystem;

namespace {

std::string write_log(const std::string& name, const std::string& text) {
  const fs::path dir =
      fs::temp_directory_path() / ("feint-observer-logs-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p.string();
}

std::string invalid_data_message(const std::string& log, feint::io::TraceOptions reading = {}) {
  try {
    fit_observer_to_logs({log}, feint::models::ObserverFitSettings{}, std::move(reading));
  } catch (const feint::InvalidData& e) {
    return e.what();
  }
  return "(no InvalidData)";
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST(ObservedLogs, PathSourceMakesNoClaimWithoutATrial) {
  const ObservedLogs none;
  EXPECT_EQ(none.path_source().find("robot_x"), std::string::npos) << none.path_source();
  EXPECT_EQ(none.path_source(), "no robot path (no trial was read)");
}

TEST(ObservedLogs, ReadsALabsColumnsWithTheLoaderOptions) {
  // subject and time_ms instead of participant and t, in milliseconds; no robot_x, robot_y.
  const std::string log =
      write_log("lab.csv",
                "subject,iteration,strategy,variant,target,time_ms,pad\n"
                "S7,1,optimal,main,right,0,0.5\nS7,1,optimal,main,right,40,0.52\n"
                "S7,1,optimal,main,right,80,0.55\n");
  feint::io::TraceOptions reading;
  reading.column_map = {{"participant", "subject"}, {"t", "time_ms"}};
  reading.time_divisor = 1000;
  const ObservedLogs logs = read_observed_trials({log}, Geometry{}, reading);
  ASSERT_EQ(logs.trials.size(), 1u);
  EXPECT_EQ(logs.trials[0].participant, "S7");
  ASSERT_EQ(logs.trials[0].times.size(), 3u);
  EXPECT_DOUBLE_EQ(logs.trials[0].times[2], 0.08);
  EXPECT_EQ(logs.paths_rebuilt, 1u);
  EXPECT_EQ(logs.paths_logged, 0u);
  EXPECT_EQ(logs.trials_read, 1u);
  EXPECT_EQ(logs.path_source(),
            "path rebuilt from strategy, variant, target and the default geometry");
}

TEST(ObservedLogs, ALeftOutTrialNamesItsFileOnce) {
  const std::string log =
      write_log("once.csv",
                "participant,iteration,target,t,pad\nP1,1,1,0,0.5\nP1,1,1,1,0.6\nP1,1,1,2,0.7\n"
                "P2,1,1,0,0.5\nP2,1,1,1,1.7\nP2,1,1,2,0.7\n");
  feint::io::TraceOptions reading;
  std::size_t passed = 0;
  reading.on_reject = [&](const feint::io::Rejection&) { ++passed; };  // --on-error skip
  const ObservedLogs logs = read_observed_trials({log}, Geometry{}, reading);
  EXPECT_EQ(passed, 1u);
  EXPECT_EQ(logs.trials_read, 2u);
  EXPECT_EQ(logs.without_path, 1u);
  ASSERT_EQ(logs.rejected.size(), 2u);
  for (const auto& r : logs.rejected) {
    EXPECT_EQ(count(r.reason, "once.csv"), 1u) << r.label << ": " << r.reason;
    EXPECT_EQ(r.reason.rfind(log + ":", 0), 0u) << r.reason;
  }
  EXPECT_EQ(logs.rejected[0].label, "P1/1");  // no strategy: the path cannot be rebuilt
  EXPECT_EQ(logs.rejected[1].label, "P2/1");  // pad 1.7: the reader's rejection
}

TEST(ObservedLogs, StrictReadingStopsAtTheFirstInvalidTrial) {
  const std::string log =
      write_log("strict.csv",
                "participant,iteration,strategy,variant,target,t,pad\n"
                "P2,1,optimal,main,right,0,0.5\nP2,1,optimal,main,right,1,1.7\n");
  EXPECT_NE(invalid_data_message(log).find("strict.csv:3: column 'pad': 1.7 is outside [0, 1]"),
            std::string::npos)
      << invalid_data_message(log);
}

TEST(FitObserverToLogs, NoUsableTrialIsInvalidDataSayingWhy) {
  // No strategy and no robot_x, robot_y: no path; the message names the count and the --map.
  const std::string none =
      write_log("nopath.csv",
                "participant,iteration,target,t,pad\nP1,1,1,0,0.5\nP1,1,1,1,0.6\nP1,1,1,2,0.7\n");
  const std::string m = invalid_data_message(none);
  EXPECT_EQ(m.rfind("no trial to fit the observer to: 1 trial(s) read from the logs, 1 left out "
                    "while reading them, 0 left out by the fit's checks; first: P1/1: ",
                    0),
            0u)
      << m;
  EXPECT_NE(m.find("the trial has no strategy"), std::string::npos) << m;
  EXPECT_NE(m.find("--map strategy=COLUMN"), std::string::npos) << m;
  // Read, but every trial left out by the fit's checks (2 pad samples).
  const std::string two =
      write_log("two.csv",
                "participant,iteration,strategy,variant,target,t,pad\n"
                "P1,1,optimal,main,right,0,0.5\nP1,1,optimal,main,right,1,0.6\n");
  const std::string t = invalid_data_message(two);
  EXPECT_NE(t.find("1 trial(s) read from the logs, 0 left out while reading them, 1 left out by "
                   "the fit's checks; first: P1/1: the pad trace has 2 sample(s)"),
            std::string::npos)
      << t;
  EXPECT_EQ(t.find("--map"), std::string::npos) << t;
}

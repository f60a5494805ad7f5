// The pad-trace loader in its three modes, and the metrics of every trial it accepts: a trial
// handed out satisfies metrics.md, and its scores are finite or the trial is rejected.
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "feint/error.hpp"
#include "feint/io/trace.hpp"
#include "feint/metrics/trial_metrics.hpp"
#include "harness.hpp"

namespace feint::fuzz {

namespace {

void check_trial(const io::Trial& t) {
  using detail::check;
  check(t.times.size() >= 2, "trial with fewer than 2 samples");
  check(t.times.size() == t.pads.size(), "times and pads differ in length");
  check(t.rows == t.times.size() + t.padding_rows, "rows != samples + padding in a valid trial");
  check(!t.participant.empty(), "empty participant");
  check(t.target >= 0 && t.target <= 1, "target outside [0, 1]");
  for (std::size_t i = 0; i < t.times.size(); ++i) {
    check(std::isfinite(t.times[i]), "time not finite");
    check(t.pads[i] >= 0 && t.pads[i] <= 1, "pad outside [0, 1]");
    if (i > 0) check(t.times[i] > t.times[i - 1], "times not strictly increasing");
  }
  if (t.pad_speed) check(std::isfinite(*t.pad_speed) && *t.pad_speed > 0, "bad pad speed");
  check(t.robot_x.size() == t.robot_y.size(), "robot_x and robot_y differ in length");
  check(t.robot_x.empty() || t.robot_x.size() == t.times.size(), "robot path and samples differ");
  for (std::size_t i = 0; i < t.robot_x.size(); ++i) {
    check(std::isfinite(t.robot_x[i]) && std::isfinite(t.robot_y[i]), "robot position not finite");
  }
  for (const auto norm : {metrics::ConfusionNorm::speed, metrics::ConfusionNorm::raw}) {
    metrics::MetricSettings s;
    s.norm = norm;
    if (norm == metrics::ConfusionNorm::speed && !t.pad_speed) s.pad_speed = 0.8;
    try {
      const auto sc = metrics::score_trial(t, s);
      check(std::isfinite(sc.duration) && sc.duration > 0, "duration not finite and > 0");
      check(std::isfinite(sc.error) && sc.error >= 0 && sc.error <= 1, "error not in [0, 1]");
      check(std::isfinite(sc.confusion) && sc.confusion >= 0, "confusion not finite and >= 0");
      if (norm == metrics::ConfusionNorm::speed) check(sc.confusion <= 1, "confusion > 1");
      check(std::isnan(sc.reversal_time) || std::isfinite(sc.reversal_time),
            "reversal time infinite");
      // Belief-trace measures (metrics.md): in range, and empty (NaN) only where undefined.
      const bool middle = t.target == 0.5;
      check(middle == std::isnan(sc.signed_area), "signed_area NaN iff T = 0.5");
      check(middle == std::isnan(sc.max_deviation), "max_deviation NaN iff T = 0.5");
      check(middle == std::isnan(sc.time_deceived), "time_deceived NaN iff T = 0.5");
      check(middle || (sc.signed_area >= -1 && sc.signed_area <= 1), "signed_area outside [-1, 1]");
      check(middle || (sc.max_deviation >= -0.5 && sc.max_deviation <= 0.5),
            "max_deviation outside [-0.5, 0.5]");
      check(middle || (sc.time_deceived >= 0 && sc.time_deceived <= 1),
            "time_deceived outside [0, 1]");
      check(std::isnan(sc.final_belief_time) ||
                (sc.final_belief_time >= 0 && sc.final_belief_time <= sc.duration * (1 + 1e-12)),
            "final_belief_time outside [0, duration]");
      check(sc.flips >= 0 && static_cast<std::size_t>(sc.flips) < t.times.size(), "flips out of range");
    } catch (const InvalidData&) {
      // A score that cannot be represented: the trial is rejected with the reason.
    }
  }
}

void run(const std::string& path, bool lenient, bool unsorted) {
  io::TraceOptions opt;
  opt.unsorted = unsorted;
  opt.read_robot_path = unsorted;  // the optional robot columns, in one of the three modes
  std::uint64_t rejected_rows = 0, rejected_trials = 0;
  if (lenient) {
    opt.on_reject = [&](const io::Rejection& r) {
      detail::check(!r.reason.empty(), "rejection without a reason");
      rejected_rows += r.rows;
      ++rejected_trials;
    };
  }
  try {
    io::TraceReader reader({path}, opt);
    io::Trial t;
    std::uint64_t rows = 0;
    while (reader.next(t)) {
      check_trial(t);
      rows += t.rows;
    }
    detail::check(reader.rows_in_trials() == rows, "rows_in_trials miscounted");
    detail::check(reader.rows_rejected() == rejected_rows, "rows_rejected miscounted");
    detail::check(reader.trials_rejected() == rejected_trials, "trials_rejected miscounted");
    detail::check(reader.rows_read() == rows + rejected_rows, "row accounting does not add up");
  } catch (const Error&) {
    // Invalid data, an unreadable file or a bad setting: a clean, typed error.
  }
}

}  // namespace

// The JSON samples cell (--samples-column, jsPsych): any text is read or refused with a reason,
// never a crash; a read cell gives as many times as pads.
void json_cell(const std::uint8_t* data, std::size_t size) {
  const std::string_view cell(reinterpret_cast<const char*>(data), size);
  std::vector<double> times, pads;
  std::string error;
  if (io::detail::parse_json_samples(cell, "t", "pad", times, pads, error)) {
    detail::check(times.size() == pads.size(), "JSON samples: times and pads differ in length");
    detail::check(error.empty(), "JSON samples: an error with success");
  } else {
    detail::check(!error.empty(), "JSON samples refused without a reason");
  }
}

int trace(const std::uint8_t* data, std::size_t size) {
  if (size > 1 << 16) return 0;
  json_cell(data, size);
  const std::string path = detail::as_file(data, size);
  run(path, false, false);
  run(path, true, false);
  run(path, true, true);
  return 0;
}

}  // namespace feint::fuzz

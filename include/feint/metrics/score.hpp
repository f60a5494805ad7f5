// feint/metrics/score.hpp - scoring many pad-trace logs into one scores table (`feint score`).
//
// The library behind the command: `feint analyze` and other programs call score_to_file() (or
// score_each() to receive each trial's score without writing a file). Streaming: a trial is scored
// as soon as its last row is read, so memory does not grow with the input (except `unsorted`).
// See docs/scoring.md for the output columns, the sidecar and the rejects file.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "feint/io/trace.hpp"
#include "feint/metrics/trial_metrics.hpp"

namespace feint::metrics {

/// What to do with an invalid trial: stop with an error (strict) or skip it and list it (skip).
enum class OnError { strict, skip };

/// The unit of the logs' `t` column (`--time-unit`); scores are always in seconds.
enum class TimeUnit { s, ms };
std::string to_string(TimeUnit unit);
/// "s" or "ms" (case-insensitive); nullopt otherwise.
std::optional<TimeUnit> parse_time_unit(std::string_view text);

/// The plausibility rule for the time unit (docs/scoring.md "Time unit"): with seconds, a median
/// trial duration above this many seconds suggests milliseconds; with milliseconds, a median below
/// kMedianDurationLowMs (converted to seconds) suggests the times were seconds already.
inline constexpr double kMedianDurationHighS = 300;
/// Above this median trial duration (20 minutes) with `--time-unit s`, the times cannot be
/// seconds (a round of the game lasts seconds): the run is refused (InvalidData) naming the
/// longest trial and --time-unit ms, instead of warning.
inline constexpr double kMedianDurationRefuseS = 1200;
inline constexpr double kMedianDurationLowMs = 0.05;

/// Progress, reported after every trial (scored or rejected).
struct ScoreProgress {
  std::uint64_t rows_read = 0;
  std::uint64_t bytes_read = 0;  // compressed bytes for .gz input
  std::uint64_t trials_scored = 0;
  std::uint64_t trials_rejected = 0;
};

struct ScoreSettings {
  MetricSettings metrics;  // trim, dead band, normalisation, pad-speed override
  /// Our field name -> the study's column name (participant, condition, iteration, strategy,
  /// variant, target, t, pad, pad_speed).
  std::map<std::string, std::string> column_map;
  char delimiter = 0;  // 0 = detect per file
  TimeUnit time_unit = TimeUnit::s;  // of the `t` column; converted to seconds when read
  /// Other labs' exports: decimal mark, headerless files, iteration base, ids from the path,
  /// JSON samples, expected conditions (io::TraceOptions' fields of those names; the fields set
  /// above and below take precedence over the copies here).
  io::TraceOptions reading;
  /// Apply the time-unit plausibility rule (kMedianDuration*): warn, or refuse above 20 minutes.
  /// Off only for a library caller whose trials are not rounds of the game (e.g. numerical tests).
  bool check_durations = true;
  /// Called with each warning (e.g. trial durations implausible for the time unit); when empty,
  /// warnings go to standard error as `feint: warning: ...`.
  std::function<void(const std::string&)> on_warning;
  OnError on_error = OnError::strict;
  /// Where skip mode lists rejected trials (CSV). Empty: `<output>.rejects.csv`; required when
  /// the output is `-`. Must be empty in strict mode.
  std::string rejects_path;
  /// Buffer every row and group trials by key (rows of a trial need not be contiguous).
  bool unsorted = false;
  /// Where the settings are recorded (JSON). Empty: `<output>.meta.json`, or none for `-`.
  std::string sidecar_path;
  /// Recorded in the sidecar.
  std::string tool_version = "unknown";
  /// Called after each trial (may be empty).
  std::function<void(const ScoreProgress&)> on_progress;
};

struct ScoreSummary {
  std::uint64_t files = 0;
  std::uint64_t rows_read = 0;      // == rows_scored + rows_rejected
  std::uint64_t rows_scored = 0;    // rows in scored trials
  std::uint64_t rows_rejected = 0;  // rows in rejected trials
  std::uint64_t trials_scored = 0;
  std::uint64_t trials_rejected = 0;
  std::uint64_t overspeed_trials = 0;  // trials with at least one overspeed segment
  std::uint64_t bytes_read = 0;
  double median_duration = 0;  // of the scored trials, in seconds (after --time-unit)
  double max_duration = 0;
  std::vector<std::string> warnings;  // as passed to on_warning (recorded in the sidecar)
  /// The same notes, structured (the reader's and the time-unit check's), for a report to show.
  std::vector<io::Diagnostic> diagnostics;
  std::string output_path;
  std::string sidecar_path;  // empty when none was written
  std::string rejects_path;  // empty in strict mode
};

/// The scores table's columns, in order (formats.md).
const std::vector<std::string>& score_columns();

/// Checks settings against each other (throws UsageError), e.g. trims, --rejects without skip.
void validate(const ScoreSettings& settings, const std::string& output_path);

/// Reads `inputs` (files, directories, globs, `-`) and calls `on_trial` for every valid trial with
/// its score; invalid trials throw InvalidData (strict) or go to `on_reject` (skip). Does not
/// write files. Throws InvalidData when no trial is valid.
ScoreSummary score_each(const std::vector<std::string>& inputs, const ScoreSettings& settings,
                        const std::function<void(const io::Trial&, const TrialScore&)>& on_trial,
                        const std::function<void(const io::Rejection&)>& on_reject = {});

/// Scores `inputs` into the CSV `output_path` (`-` = stdout), atomically, plus the sidecar (and,
/// in skip mode, the rejects list). A failing run leaves no scores file behind. Throws
/// UsageError, InvalidData, IoError.
/// The log reader's options as the scorer reads the logs (column map, delimiter, time unit, pad
/// speed, unsorted rows; on_reject unset): every other reader of the same logs (the mean traces,
/// the observer fit) reads them through this, so that they see the trials the scores came from.
io::TraceOptions reading_options(const ScoreSettings& settings);

ScoreSummary score_to_file(const std::vector<std::string>& inputs, const ScoreSettings& settings,
                           const std::string& output_path);

/// What `feint score` says on standard error after a run: "feint score: N rows read from F
/// file(s), T trials scored, R rejected (list in ...) -> OUTPUT (settings in ...)", and a warning
/// line when trials moved faster than the pad speed. Each line ends with a newline.
std::string summary_text(const ScoreSummary& summary);

}  // namespace feint::metrics

// feint/io/trace.hpp - streaming pad-trace logs: trials from many files, validated, with precise
// errors.
//
// The input is the long format of formats.md: one row per pad sample,
//   participant,condition,iteration,strategy,variant,target,t,pad,pad_speed
// A trial is keyed by (participant, condition, iteration), the iteration by its value (`1`, `01`
// and `+1` are one iteration; a whole number from 0 to 1e9, the range the scores tables read); its
// rows are contiguous and its trial-level fields (target, strategy, variant, pad_speed) are
// constant. TraceReader reads any
// number of files (plain or .gz, `-` = stdin) as one data set and hands out one validated Trial at a
// time, as soon as its last row has been read, so memory does not grow with the input (except in
// `unsorted` mode, which buffers every row and groups them by key).
//
// Every violation of formats.md / metrics.md is reported as
//   `file:line: column 'pad': 1.7 is outside [0, 1] (trial P07/adaptive/3)`
// In strict mode (no `on_reject` callback) the first one throws feint::InvalidData; in lenient mode
// the whole trial is handed to `on_reject` (with the number of rows it had) and reading goes on.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "feint/io/diagnostic.hpp"

namespace feint::io {

/// One interaction: the samples (t_i, mu_i) of a trial and its trial-level fields.
struct Trial {
  std::string participant;
  std::string condition;  // empty when the data has no condition column
  long long iteration = 0;
  std::string strategy;  // empty when absent
  std::string variant;   // empty when absent
  double target = 0;     // the true target's pad coordinate T in [0, 1] (left = 0, right = 1)
  std::optional<double> pad_speed;  // pad units per second; the --pad-speed override if given
  std::vector<double> times;        // t_i in seconds, strictly increasing, size >= 2
  std::vector<double> pads;         // mu_i in [0, 1], same size as times
  /// The robot's position (m, the study's geometry) at each sample, from the optional robot_x and
  /// robot_y columns; empty when the log has neither (then sim::robot_path rebuilds the path).
  std::vector<double> robot_x;
  std::vector<double> robot_y;
  /// Logs of K targets and a pointer (formats.md; io/pointer_trace.hpp); empty for pad logs. The
  /// pointer (m) at each sample, the true target's index (also in `target`), the start and the K
  /// targets (m), constant within the trial.
  std::vector<double> belief_x;
  std::vector<double> belief_y;
  std::size_t target_index = 0;
  double start_x = 0;
  double start_y = 0;
  std::vector<double> targets_x;
  std::vector<double> targets_y;
  bool is_pointer() const noexcept { return !belief_x.empty(); }
  std::string file;                 // file of the trial's first row (`<stdin>` for `-`)
  std::uint64_t line = 0;           // physical line of its first row (header = line 1)
  std::uint64_t rows = 0;           // rows read for this trial (== times.size() + padding_rows when valid)
  std::uint64_t padding_rows = 0;   // trailing all-NaN t/pad rows dropped (fixed-length arrays)

  /// `participant/condition/iteration` (or `participant/iteration` without conditions), as used
  /// in every message.
  std::string label() const;
};

/// A trial that failed validation (lenient mode).
struct Rejection {
  std::string file;         // where the offending row (or the trial) is
  std::uint64_t line = 0;   // the offending row's line (or the trial's first line)
  std::string participant;  // the trial's key as written in the file
  std::string condition;
  std::string iteration;
  std::uint64_t rows = 0;  // rows of the trial, all excluded from scoring
  std::string reason;      // the full message, `file:line: ... (trial P/C/I)`
};

/// The column names the loader looks for (formats.md), matched case-insensitively.
/// Keys: participant, condition, iteration, strategy, variant, target, t, pad, pad_speed, robot_x,
/// robot_y (the last two optional, read together).
const std::vector<std::string>& trace_field_names();

struct TraceOptions {
  /// Our field name -> the study's column name (`--map pad=position`). Unknown field names are a
  /// UsageError at construction.
  std::map<std::string, std::string> column_map;
  /// 0 = detect per file from its header (`,` `;` TAB).
  char delimiter = 0;
  /// Replaces any pad_speed column (pad units per second, > 0). The column is then not read.
  std::optional<double> pad_speed;
  /// Every trial must have a pad speed (the `speed` confusion normalisation): a file without a
  /// pad_speed column and no override is a UsageError that says how to give it.
  bool require_pad_speed = false;
  /// Buffer every row and group by key (rows of a trial need not be contiguous or in one file).
  bool unsorted = false;
  /// The unit of the `t` column: times are divided by this to give seconds (1 = seconds, 1000 =
  /// milliseconds; `--time-unit`). Messages quote the times as written.
  double time_divisor = 1;
  /// Read the optional robot_x / robot_y columns into Trial::robot_x / robot_y (both or neither;
  /// every row a finite number). Off by default: scoring and the figures do not use the robot's
  /// path, so for them the columns are ignored like any extra column and cost nothing.
  bool read_robot_path = false;
  /// Lenient mode: called for each invalid trial instead of throwing.
  std::function<void(const Rejection&)> on_reject;

  // ---- other labs' exports (docs/formats.md "Files from other labs") ----
  /// Decimal mark of the numbers (t, pad, target, pad_speed): '.', ',' or 0 = per file: '.' in a
  /// `,`-delimited file; in any other, the first number (target, pad_speed, t, pad) holding a `,`
  /// or a `.` decides
  /// (`0,033` = decimal comma; a "decimal-comma" diagnostic says so). With a decimal comma, a `.`
  /// in a number is invalid (it would be a thousands separator).
  char decimal = 0;
  /// A file without a header row (MATLAB): CsvOptions::no_header and column_names. Without names,
  /// columns are called `1`, `2`, ... so `--map t=3` reads the third column.
  bool no_header = false;
  std::vector<std::string> column_names;
  /// -1 = iterations as written (a data set whose smallest iteration is 0 gets an
  /// "iteration-base-0" diagnostic); 0 = 0-based, 1 is added (PsychoPy's 0..19 become 1..20);
  /// 1 = 1-based, an iteration 0 is invalid.
  int iteration_base = -1;
  /// The participant id from each file's path instead of a column: "filename" (the file name
  /// without its extensions), "dirname" (the parent folder's name), or an ECMAScript regular
  /// expression searched in the path whose first capture group is the id.
  std::string participant_from_path;
  /// A column holding each trial's samples as JSON (jsPsych): `[{"t":0,"pad":0.5},...]` or
  /// `{"t":[...],"pad":[...]}`; the keys are the t and pad names (`--map t=KEY`). The t and pad
  /// columns are then not read.
  std::string samples_column;
  /// The study's conditions (settings, --compare): two or more make a file without a condition
  /// column invalid instead of pooling them.
  std::vector<std::string> expected_conditions;
  /// Pool every trial into one condition although a column looks like a condition (`group`,
  /// `cond...`, `arm`, `treatment`); without it such a file is refused.
  bool single_condition = false;
};

namespace detail {
/// A header name that suggests the study's condition (`cond...`, `group`, `arm`, `treatment`,
/// `between`): pooling such a file into one condition silently would be wrong.
bool looks_like_condition(std::string_view header_cell);
/// Reads a JSON samples cell (TraceOptions::samples_column); false with `error` set when malformed.
/// JSON null is NaN (padding).
bool parse_json_samples(std::string_view cell, std::string_view t_key, std::string_view pad_key,
                        std::vector<double>& times, std::vector<double>& pads, std::string& error);
}  // namespace detail

/// Expands command-line inputs into a list of files, in command-line order: a file as given, a
/// directory as every *.csv, *.tsv, *.txt (optionally .gz) below it (sorted by path) — a study
/// folder (a feint.toml beside a logs/ folder) as the files below its logs/ — a pattern
/// with * ? [ via glob(3) (sorted); `-` is standard input. A file named twice is read once. Throws IoError for a missing path, a pattern without match or a
/// directory without data files.
std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs);

class TraceReader {
 public:
  /// `files` as returned by expand_inputs (read in this order). Throws UsageError for a bad
  /// column_map or pad_speed.
  TraceReader(std::vector<std::string> files, TraceOptions options);
  ~TraceReader();
  TraceReader(const TraceReader&) = delete;
  TraceReader& operator=(const TraceReader&) = delete;

  /// Reads the next valid trial into `trial` (its vectors' capacity is reused); false at the end of
  /// all inputs. Throws InvalidData (strict mode, or a file-level problem such as a missing
  /// column or malformed CSV), IoError (cannot read), UsageError (no pad speed when required).
  bool next(Trial& trial);

  /// Data rows read so far (all files).
  std::uint64_t rows_read() const noexcept;
  /// Rows in trials handed out by next() / in rejected trials, so far.
  std::uint64_t rows_in_trials() const noexcept;
  std::uint64_t rows_rejected() const noexcept;
  std::uint64_t trials_rejected() const noexcept;
  /// Bytes of input consumed so far (compressed bytes for .gz), for progress reports.
  std::uint64_t bytes_consumed() const noexcept;
  /// Files opened so far.
  std::size_t files_read() const noexcept;
  /// Trailing all-NaN rows dropped so far (counted in rows_in_trials) and the trials they ended.
  std::uint64_t rows_padding() const noexcept;
  std::uint64_t trials_padded() const noexcept;
  /// What the reader noticed about the input so far (decimal comma detected, NaN padding dropped,
  /// iterations starting at 0); complete once next() has returned false.
  std::vector<Diagnostic> diagnostics() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace feint::io

// feint/io/pointer_trace.hpp - logs of K >= 2 targets and a pointer (formats.md "Logs of K targets
// and a pointer"): one row per pointer sample,
//   participant,condition,iteration,strategy,variant,target,t,belief_x,belief_y,start_x,start_y,
//   target0_x,target0_y,...,target{K-1}_x,target{K-1}_y,robot_x,robot_y
// `target` is the true target's index 0..K-1; the start and the targets (metres on the study's
// map) are trial-level fields, constant within a trial; K is read from the header.
//
// A reader parallel to TraceReader (same interface, same Trial), so that today's pad logs are read
// by exactly today's code. It fills Trial's pointer fields (belief_x, belief_y, target_index,
// start, targets) and sets Trial::target to the index; Trial::pads stays empty.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "feint/io/trace.hpp"

namespace feint::io {

/// True when `file`'s header has a `belief_x` column and no `pad` column (names matched ignoring
/// case, after TraceOptions::column_map), i.e. a log of K targets. `-` (stdin) is never peeked at:
/// false. Throws IoError / InvalidData as CsvReader does.
bool is_pointer_log(const std::string& file, const TraceOptions& options = {});

/// Reads logs of K targets. Options used: column_map (the names above as fields: participant,
/// condition, iteration, strategy, variant, target, t, belief_x, belief_y; the layout columns are
/// read by their own names), delimiter, time_divisor, pad_speed (copied into Trial::pad_speed),
/// on_reject (lenient mode). require_pad_speed without pad_speed is a UsageError (a pointer log has
/// no speed column: the `speed` normalisation needs --pad-speed, in layout scales per second).
/// Other labs' options (decimal comma, no header, JSON samples, unsorted rows) are not supported
/// for these logs (UsageError when set).
///
/// Rejected, with file, line and column: K < 2, a target{k}_x without target{k}_y (or the reverse),
/// a target index missing below the highest, a number that is not finite, `target` not an index
/// 0..K-1, a trial-level field that changes within a trial, a layout with two targets at one point
/// or a target at the start (metrics::validate(layout, 0, 0)'s rules; io does not link metrics),
/// t not strictly increasing, a trial of fewer than 2 samples, a trial that reappears.
class PointerTraceReader {
 public:
  PointerTraceReader(std::vector<std::string> files, TraceOptions options);
  ~PointerTraceReader();
  PointerTraceReader(const PointerTraceReader&) = delete;
  PointerTraceReader& operator=(const PointerTraceReader&) = delete;

  bool next(Trial& trial);
  std::uint64_t rows_read() const noexcept;
  std::uint64_t rows_in_trials() const noexcept;
  std::uint64_t rows_rejected() const noexcept;
  std::uint64_t trials_rejected() const noexcept;
  std::uint64_t bytes_consumed() const noexcept;
  std::size_t files_read() const noexcept;
  std::vector<Diagnostic> diagnostics() const;
  /// The number of targets K of the files read so far (0 before the first file).
  std::size_t targets() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace feint::io

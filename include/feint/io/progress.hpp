// feint/io/progress.hpp - a progress line on stderr for long runs, only when stderr is a terminal.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

namespace feint::io {

class ProgressLine {
 public:
  /// `what` prefixes the line (e.g. "feint score"). Active only when stderr is a terminal.
  explicit ProgressLine(std::string what);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// Redraws at most every 0.5 s, and not before 1 s has passed (short runs stay quiet).
  void update(std::uint64_t rows, std::uint64_t bytes, std::uint64_t trials,
              std::uint64_t rejected);
  /// The same for a run that counts units of work: "WHAT: done/total UNIT (P %, about S s left)".
  void update_count(std::uint64_t done, std::uint64_t total, std::string_view unit);
  /// Erases the line (before the summary is printed).
  void finish();
  bool active() const noexcept { return active_; }

 private:
  bool due();  // active, past the first second and 0.5 s since the last redraw

  std::string what_;
  bool active_ = false;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace feint::io

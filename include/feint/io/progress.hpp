// feint/io/progress.hpp - a progress line on stderr for long runs, only when stderr is a terminal.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

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
  /// Erases the line (before the summary is printed).
  void finish();
  bool active() const noexcept { return active_; }

 private:
  std::string what_;
  bool active_ = false;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace feint::io

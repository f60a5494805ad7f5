#include "feint/io/progress.hpp"

#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

namespace feint::io {

ProgressLine::ProgressLine(std::string what)
    : what_(std::move(what)),
      active_(::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

ProgressLine::~ProgressLine() { finish(); }

bool ProgressLine::due() {
  if (!active_) return false;
  const auto now = std::chrono::steady_clock::now();
  if (now - start_ < std::chrono::seconds(1) || now - last_ < std::chrono::milliseconds(500)) {
    return false;
  }
  last_ = now;
  return true;
}

void ProgressLine::update_count(std::uint64_t done, std::uint64_t total, std::string_view unit) {
  if (total == 0 || !due()) return;
  const double secs = std::chrono::duration<double>(last_ - start_).count();
  const double share = static_cast<double>(done) / static_cast<double>(total);
  const double left = share > 0 ? secs * (1 - share) / share : 0;
  fmt::print(stderr, "\r{}: {}/{} {} ({:.0f} %, about {:.0f} s left)\x1b[K", what_, done, total, unit,
             100 * share, left);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressLine::update(std::uint64_t rows, std::uint64_t bytes, std::uint64_t trials,
                          std::uint64_t rejected) {
  if (!due()) return;
  const double secs = std::chrono::duration<double>(last_ - start_).count();
  fmt::print(stderr, "\r{}: {:.1f} M rows ({:.1f} M rows/s, {:.0f} MB/s), {} trials scored, {} "
                     "rejected\x1b[K",
             what_, static_cast<double>(rows) / 1e6, static_cast<double>(rows) / 1e6 / secs,
             static_cast<double>(bytes) / 1e6 / secs, trials, rejected);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressLine::finish() {
  if (drawn_) {
    fmt::print(stderr, "\r\x1b[K");
    std::fflush(stderr);
    drawn_ = false;
  }
}

}  // namespace feint::io

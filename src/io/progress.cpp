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

void ProgressLine::update(std::uint64_t rows, std::uint64_t bytes, std::uint64_t trials,
                          std::uint64_t rejected) {
  if (!active_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - start_ < std::chrono::seconds(1) || now - last_ < std::chrono::milliseconds(500)) {
    return;
  }
  last_ = now;
  const double secs = std::chrono::duration<double>(now - start_).count();
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

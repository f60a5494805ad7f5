// feint/io/output.hpp - atomic output files.
//
// formats.md: a failed or interrupted run never leaves a half-written table. Output goes to a
// hidden temporary file beside the target, renamed into place by commit(); destruction without
// commit (an exception) removes the temporary, and so does SIGINT/SIGTERM. A device or FIFO
// (/dev/null, a named pipe) is written in place, never replaced.
#pragma once

#include <memory>
#include <ostream>
#include <string>

namespace feint::io {

class AtomicOutput {
 public:
  /// `path` = `-` writes to standard output (commit() then only flushes).
  /// Throws IoError when the temporary file cannot be created.
  explicit AtomicOutput(std::string path);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  std::ostream& stream() noexcept;
  /// Flushes, checks for write errors, and renames the temporary file to the target.
  /// Throws IoError on failure (the temporary is removed).
  void commit();
  const std::string& path() const noexcept;
  bool is_stdout() const noexcept;
  /// True when the target is an existing device or FIFO (e.g. /dev/null), written in place: such
  /// output cannot be rolled back, so callers that must not emit half a table buffer it first.
  bool in_place() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes `content` to `path` atomically (convenience for small files such as sidecars).
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace feint::io

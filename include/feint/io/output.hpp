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
#include <vector>

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
  /// The file that commit() replaces (the path, or the file a symbolic link names).
  const std::string& target() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Commits several outputs as one unit: each is fully written first, then, holding an exclusive
/// flock(2) on the folder of each target (taken in a fixed order), all are renamed into place in
/// the order given. Two processes committing to the same targets at once therefore never leave
/// one's file beside the other's (e.g. a scores table with another run's sidecar). Readers that
/// must be sure also check the sidecar's record of the table (io::read_scores_provenance does).
void commit_together(const std::vector<AtomicOutput*>& outputs);

/// Writes `content` to `path` atomically (convenience for small files such as sidecars).
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace feint::io

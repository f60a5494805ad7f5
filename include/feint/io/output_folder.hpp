// feint/io/output_folder.hpp - an output folder written as one unit: a command's run never writes
// into the user's folder directly and never mixes two runs.
//
// A run writes everything into a fresh hidden staging folder beside the target
// (`.OUT.feint-staging-XXXXXX`); commit() lists what was written in a manifest (OUT/MANIFEST) and
// swaps the staging folder in (one atomic rename on Linux, renameat2 RENAME_EXCHANGE), then deletes
// the previous run's folder. So:
//   - a run that fails (an exception before commit) leaves OUT exactly as it was;
//   - OUT never mixes two runs: files of an earlier run that this run does not write are gone;
//   - only files an earlier run of the same command wrote are ever deleted: an existing OUT must be
//     empty, or hold only the files its manifest lists (or, from feint versions before the manifest,
//     only files named like that command's outputs); anything else is refused before any work;
//   - a command that asks before replacing (FolderWriter::ask_before_replacing, e.g. `feint simulate
//     study`) refuses a non-empty OUT unless it was told to replace it (FolderWriter::replace).
// Everything written under staging() is the run's output: a step adds files (or subfolders such as
// figures/) by writing to path("name"); nothing needs registering.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace feint::io {

/// The command that writes a folder, and when it may replace an existing one.
struct FolderWriter {
  std::string command;       ///< "feint analyze": named in messages and in the manifest
  std::string manifest;      ///< the manifest's file name, e.g. ".feint-analyze.json"
  std::string option = "-o"; ///< the option that names the folder, for messages
  /// The names (files, and folders with a trailing '/') this command wrote before it wrote a
  /// manifest; nullptr when it always wrote one.
  bool (*legacy_output)(std::string_view name) = nullptr;
  /// true: a non-empty folder is refused unless `replace` is set (then replaced whole, under the
  /// same rule of never deleting a file the command did not write); false: a folder of an earlier
  /// run of the command is replaced without asking.
  bool ask_before_replacing = false;
  bool replace = false;
  std::string replace_option;  ///< the flag that sets `replace`, e.g. "--replace"
};

class OutputFolder {
 public:
  /// Checks `target` against the run's inputs (files or folders) and its current contents, then
  /// creates the staging folder. Throws UsageError (exit 64) when `target` is or lies inside an
  /// input folder, contains an input, is a file, or holds files the writer did not write (or is
  /// not empty, for a writer that asks before replacing and was not told to); IoError (74) when
  /// the staging folder cannot be created.
  OutputFolder(std::string target, const std::vector<std::string>& inputs, FolderWriter writer);
  ~OutputFolder();  ///< without commit(): removes the staging folder, OUT untouched
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  /// Where this run writes `name` (a path relative to the output folder).
  std::string path(std::string_view name) const;
  const std::filesystem::path& staging() const noexcept { return staging_; }
  /// The folder as the user named it.
  const std::string& target() const noexcept { return target_; }

  /// Writes the manifest and puts the staged folder in place of the target. Returns the files
  /// written (relative paths, sorted; the manifest not included). Throws IoError on failure (the
  /// target is then as it was).
  std::vector<std::string> commit(std::string_view tool_version);

 private:
  std::string target_;              // as given
  FolderWriter writer_;
  std::filesystem::path resolved_;  // the folder actually replaced (a symbolic link followed)
  std::filesystem::path staging_;
  bool committed_ = false;
};

namespace detail {
/// The file list of a manifest's text (its "files" array); throws InvalidData when malformed.
std::vector<std::string> parse_manifest_files(const std::string& json);
}  // namespace detail

}  // namespace feint::io

// feint/publish/output_folder.hpp - the output folder of `feint analyze`, replaced as one unit.
//
// A run never writes into the user's folder directly. It writes everything into a fresh hidden
// staging folder beside it (`.OUT.feint-staging-XXXXXX`); commit() lists what was written in a
// manifest (OUT/.feint-analyze.json) and swaps the staging folder in (one atomic rename on Linux,
// renameat2 RENAME_EXCHANGE), then deletes the previous run's folder. So:
//   - a run that fails (an exception before commit) leaves OUT exactly as it was;
//   - OUT never mixes two runs: files of an earlier run that this run does not write are gone;
//   - only files a previous feint analyze wrote are ever deleted: an existing OUT must be empty,
//     or hold only the files its manifest lists (or, from feint versions before the manifest, only
//     files named like feint analyze's outputs); anything else is refused before any work.
// Everything written under staging() is the run's output: a step adds files (or subfolders such as
// figures/) by writing to path("name"); nothing needs registering.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace feint::publish {

/// Name of the manifest a run writes into its output folder.
inline constexpr std::string_view kAnalyzeManifest = ".feint-analyze.json";

class OutputFolder {
 public:
  /// Checks `target` against the run's inputs (files or folders) and its current contents, then
  /// creates the staging folder. Throws UsageError (exit 64) when `target` is or lies inside an
  /// input folder, contains an input, is a file, or holds files feint analyze did not write;
  /// IoError (74) when the staging folder cannot be created.
  OutputFolder(std::string target, const std::vector<std::string>& inputs);
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
  std::filesystem::path resolved_;  // the folder actually replaced (a symbolic link followed)
  std::filesystem::path staging_;
  bool committed_ = false;
};

namespace detail {
/// The file list of a manifest's text (its "files" array); throws InvalidData when malformed.
std::vector<std::string> parse_manifest_files(const std::string& json);
/// True for the names feint analyze wrote before it wrote a manifest (scores.csv and its sidecar
/// and rejects, table1*.{txt,md,tex,csv,json}, likert*.{...}, likert_summary.csv).
bool is_legacy_analyze_output(std::string_view name);
}  // namespace detail

}  // namespace feint::publish

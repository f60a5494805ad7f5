// feint/publish/output_folder.hpp - the output folder of `feint analyze`, replaced as one unit
// (feint/io/output_folder.hpp): an earlier analyze run's folder is replaced without asking, and a
// folder holding anything that run did not write is refused before any work.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "feint/io/output_folder.hpp"

namespace feint::publish {

/// Name of the manifest a run writes into its output folder.
inline constexpr std::string_view kAnalyzeManifest = ".feint-analyze.json";

namespace detail {
using io::detail::parse_manifest_files;
/// True for the names feint analyze wrote before it wrote a manifest (scores.csv and its sidecar
/// and rejects, table1*.{txt,md,tex,csv,json}, likert*.{...}, likert_summary.csv).
bool is_legacy_analyze_output(std::string_view name);
}  // namespace detail

/// feint analyze as the writer of its output folder.
io::FolderWriter analyze_folder_writer();

class OutputFolder : public io::OutputFolder {
 public:
  OutputFolder(std::string target, const std::vector<std::string>& inputs)
      : io::OutputFolder(std::move(target), inputs, analyze_folder_writer()) {}
};

}  // namespace feint::publish

// feint analyze as the writer of its output folder (see feint/publish/output_folder.hpp).
#include "feint/publish/output_folder.hpp"

namespace feint::publish {

namespace detail {

bool is_legacy_analyze_output(std::string_view name) {
  if (name == "scores.csv" || name == "scores.csv.meta.json" || name == "scores.csv.rejects.csv" ||
      name == "likert_summary.csv") {
    return true;
  }
  for (const std::string_view stem : {"table1", "table1_compare", "likert", "likert_compare"}) {
    for (const std::string_view ext : {".txt", ".md", ".tex", ".csv", ".json"}) {
      if (name.size() == stem.size() + ext.size() && name.substr(0, stem.size()) == stem &&
          name.substr(stem.size()) == ext) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace detail

io::FolderWriter analyze_folder_writer() {
  io::FolderWriter w;
  w.command = "feint analyze";
  w.manifest = std::string(kAnalyzeManifest);
  w.option = "-o";
  w.legacy_output = &detail::is_legacy_analyze_output;
  return w;
}

}  // namespace feint::publish

// A private temporary folder, removed however the scope ends (analyze's scores, the calibration's
// simulated studies). Internal to src/analysis.
#pragma once

#include <stdlib.h>

#include <filesystem>
#include <string>
#include <system_error>

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::analysis::detail {

class ScratchFolder {
 public:
  /// Creates TMPDIR/<prefix>-XXXXXX; throws IoError when it cannot.
  explicit ScratchFolder(const std::string& prefix) {
    namespace fs = std::filesystem;
    std::string tmpl = (fs::temp_directory_path() / (prefix + "-XXXXXX")).string();
    if (mkdtemp(tmpl.data()) == nullptr) {
      throw IoError(fmt::format("cannot create a temporary folder in '{}'", fs::temp_directory_path().string()));
    }
    path_ = tmpl;
  }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace feint::analysis::detail

#include "feint/analysis/command_line.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "feint/analysis/study.hpp"

namespace feint::analysis {

namespace fs = std::filesystem;

std::string command_line() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  const std::string raw{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::string out;
  std::size_t start = 0;
  while (start < raw.size()) {
    std::size_t end = raw.find('\0', start);
    if (end == std::string::npos) end = raw.size();
    std::string arg = raw.substr(start, end - start);
    if (start == 0) {
      arg = fs::path(arg).filename().string();
    } else if (fs::path(arg).is_absolute()) {
      arg = display_path(arg, ".");
    }
    const bool plain =
        !arg.empty() && arg.find_first_of(" \t\"'$\\;&|<>*?()[]{}`") == std::string::npos;
    if (!out.empty()) out += ' ';
    out += plain ? arg : "'" + arg + "'";
    start = end + 1;
  }
  return out;
}

std::string run_summary(const Study& study, const StudyResults& results, std::size_t files,
                        const std::string& folder, bool default_folder) {
  const auto& d = results.diagnostics.scoring;
  std::string out = fmt::format(
      "feint analyze: {} rows read, {} trials scored, {} rejected; {} files written to {}{}\n",
      d.rows_read, d.trials_scored, d.trials_rejected, files, folder,
      default_folder ? " (the default; choose another with -o)" : "");
  if (!study.settings.no_report) {
    out += fmt::format("feint analyze: open {}\n", (fs::path(folder) / "report.html").string());
  }
  return out;
}

}  // namespace feint::analysis

#include "feint/commands/analyze_command.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "feint/analysis/study.hpp"

namespace feint::commands {

namespace fs = std::filesystem;

std::string quoted_command_line(const std::vector<std::string>& arguments) {
  std::string out;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    std::string arg = arguments[i];
    if (i == 0) {
      arg = fs::path(arg).filename().string();
    } else if (fs::path(arg).is_absolute()) {
      arg = analysis::display_path(arg, ".");
    }
    const bool plain =
        !arg.empty() && arg.find_first_of(" \t\"'$\\;&|<>*?()[]{}`") == std::string::npos;
    if (!out.empty()) out += ' ';
    out += plain ? arg : "'" + arg + "'";
  }
  return out;
}

std::string run_summary(const analysis::Study& study, const analysis::StudyResults& results,
                        std::size_t files, const std::string& folder, bool default_folder) {
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

}  // namespace feint::commands

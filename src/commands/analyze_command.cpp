#include "feint/commands/analyze_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "feint/analysis/study.hpp"

namespace feint::commands {

namespace fs = std::filesystem;

namespace {

// One argument as the Reproduce line shows it, run from the folder `out_arg` (empty: as given, an
// absolute path shown relative to the current folder).
std::string shown_argument(const std::string& arg, const std::string& out_arg) {
  if (out_arg.empty()) return fs::path(arg).is_absolute() ? analysis::display_path(arg, ".") : arg;
  std::string prefix, value = arg;
  if (arg.rfind("--", 0) == 0) {
    const auto eq = arg.find('=');
    if (eq == std::string::npos) return arg;
    prefix = arg.substr(0, eq + 1);
    value = arg.substr(eq + 1);
  } else if (!arg.empty() && arg[0] == '-') {
    return arg;
  }
  std::error_code ec;
  if (value.empty() || (value != out_arg && !fs::exists(value, ec))) return arg;
  return prefix + analysis::path_from(value, out_arg);
}

}  // namespace

std::vector<std::string> process_arguments() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  const std::string raw{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::vector<std::string> args;
  for (std::size_t start = 0, end = 0; start < raw.size(); start = end + 1) {
    end = std::min(raw.find('\0', start), raw.size());
    args.push_back(raw.substr(start, end - start));
  }
  return args;
}

std::string quoted_command_line(const std::vector<std::string>& arguments,
                                const std::string& output_folder) {
  std::string out_text;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    std::string arg = arguments[i];
    if (i == 0) {
      arg = fs::path(arg).filename().string();
    } else if (i > 1 || output_folder.empty()) {
      arg = shown_argument(arg, output_folder);
    }
    const bool plain =
        !arg.empty() && arg.find_first_of(" \t\"'$\\;&|<>*?()[]{}`") == std::string::npos;
    if (!out_text.empty()) out_text += ' ';
    out_text += plain ? arg : "'" + arg + "'";
  }
  return out_text;
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

// feint/commands/analyze_command.hpp - what `feint analyze` shows besides the study's files: the
// command line as the study report prints it, and the summary on standard error when it is done.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "feint/analysis/results.hpp"
#include "feint/analysis/study.hpp"

namespace feint::commands {

/// A command line as the study report shows it, to be run from the report's folder: the program
/// by its file name; every argument that names a file or folder (that exists, or is
/// `output_folder`), alone or after `--option=`, rewritten relative to `output_folder` (the output
/// folder itself as ../NAME); a path that shares no folder but the root with the output folder
/// shown as PATH_TO/NAME (analysis::path_from), so that a shared report carries no one's folder
/// layout; arguments with spaces or shell characters in single quotes. `arguments` are the
/// process's arguments as the caller captured them (the program first, then the command's name,
/// which is never rewritten); empty gives "". With `output_folder` empty, paths are shown relative
/// to the current folder (analysis::display_path) as before.
/// This process's arguments as the kernel recorded them (Linux: /proc/self/cmdline; none without
/// /proc), for the report's Reproduce line: the caller captures them, quoted_command_line quotes
/// them.
std::vector<std::string> process_arguments();

std::string quoted_command_line(const std::vector<std::string>& arguments,
                                const std::string& output_folder = "");

/// "feint analyze: R rows read, T trials scored, X rejected; N files written to FOLDER" (noting
/// when FOLDER is the default), then "feint analyze: open FOLDER/report.html" unless --no-report.
std::string run_summary(const analysis::Study& study, const analysis::StudyResults& results,
                        std::size_t files, const std::string& folder, bool default_folder);

}  // namespace feint::commands

// feint/commands/analyze_command.hpp - what `feint analyze` shows besides the study's files: the
// command line as the study report prints it, and the summary on standard error when it is done.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "feint/analysis/results.hpp"
#include "feint/analysis/study.hpp"

namespace feint::commands {

/// A command line as the study report shows it: the program by its file name, absolute paths
/// shown relative to the current folder (analysis::display_path), arguments with spaces or shell
/// characters in single quotes; so that the report names no absolute path. `arguments` are the
/// process's arguments as the caller captured them (the program first); empty gives "".
std::string quoted_command_line(const std::vector<std::string>& arguments);

/// "feint analyze: R rows read, T trials scored, X rejected; N files written to FOLDER" (noting
/// when FOLDER is the default), then "feint analyze: open FOLDER/report.html" unless --no-report.
std::string run_summary(const analysis::Study& study, const analysis::StudyResults& results,
                        std::size_t files, const std::string& folder, bool default_folder);

}  // namespace feint::commands

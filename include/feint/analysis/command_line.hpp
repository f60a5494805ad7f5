// feint/analysis/command_line.hpp - the command line that ran, as the study report shows it, and
// what `feint analyze` says on standard error when it is done.
#pragma once

#include <cstddef>
#include <string>

#include "feint/analysis/results.hpp"
#include "feint/analysis/study.hpp"

namespace feint::analysis {

/// The running process's command line (Linux: /proc/self/cmdline, as the kernel recorded it):
/// the program by its file name, absolute paths shown relative to the current folder
/// (display_path), arguments with spaces or shell characters in single quotes; so that the report
/// names no absolute path. Empty when /proc is not there.
std::string command_line();

/// "feint analyze: R rows read, T trials scored, X rejected; N files written to FOLDER" (noting
/// when FOLDER is the default), then "feint analyze: open FOLDER/report.html" unless --no-report.
std::string run_summary(const Study& study, const StudyResults& results, std::size_t files,
                        const std::string& folder, bool default_folder);

}  // namespace feint::analysis

// src/cli/report_options.hpp - command-line options shared by the report commands (`feint table`,
// `feint likert`, `feint describe`) and the atomic write of their rendered output.
//
// Usage in a command:
//   auto opts = std::make_shared<ReportOptions>();
//   add_report_options(*cmd, *opts);              // --format -o --apa --alpha --alternative ...
//   cmd->callback([opts] {
//     const ResolvedReportOptions r = resolve_report_options(*opts);  // UsageError (exit 64)
//     ... render with r.format ...
//     write_report(r.output, text);                                     // atomic; `-` = stdout
//   });
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "feint/analysis/options.hpp"
#include "feint/io/scores.hpp"
#include "feint/report/table1.hpp"
#include "feint/report/writers.hpp"
#include "feint/stats/htest.hpp"
#include "feint/stats/p_adjust.hpp"

namespace feint::cli {

/// The option values and their checks live in the library (feint/analysis/options.hpp).
using analysis::parse_compare;
using analysis::parse_metric_specs;
using analysis::parse_p_adjust_option;
using analysis::ReportOptions;
using analysis::resolve_report_options;
using analysis::ResolvedReportOptions;

/// Which of the shared options a command offers (describe has no tests: only format and output).
struct ReportOptionSet {
  bool tests = true;  ///< --apa --alpha --alternative --conf-level --p-adjust
  bool presentation = false;  ///< --label --caption --latex-wide
};

/// Registers `--format`, `-o/--output` and (unless `set.tests` is false) `--apa`, `--alpha`,
/// `--alternative`, `--conf-level`, `--p-adjust` on `cmd`, bound to `options` (which must outlive
/// the parse).
void add_report_options(CLI::App& cmd, ReportOptions& options, ReportOptionSet set = {});

/// Registers `--participant-column`, `--iteration-column`, `--condition-column`, bound to the
/// column names of `columns` (the scores loader's options; must outlive the parse). `role` starts
/// each description, e.g. "Pilot: " for a pilot file.
void add_scores_column_options(CLI::App& cmd, io::ScoresOptions& columns,
                               std::string_view role = "");

/// Registers `--label`, `--caption`, `--latex-wide` (in CLI11 group `group` when not empty).
void add_presentation_options(CLI::App& cmd, ReportOptions& options, const std::string& group = "");

/// Registers the questionnaire options (analysis::LikertOptions): --layout, --scale, --labels,
/// --items, the column names, --reverse, --composite, --reference, --alpha-missing,
/// --keep-unfinished, --keep-previews; `in_analyze` names the scale and the reference
/// --likert-scale and --likert-reference (feint analyze's tables have a reference of their own).
void add_questionnaire_options(CLI::App& cmd, analysis::LikertOptions& options, bool in_analyze,
                               const std::string& group = "");

/// Writes `content` to `path` atomically (temporary file + rename; `-` = standard output).
void write_report(const std::string& path, std::string_view content);

}  // namespace feint::cli

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

#include "feint/io/scores.hpp"
#include "feint/report/table1.hpp"
#include "feint/report/writers.hpp"
#include "feint/stats/htest.hpp"
#include "feint/stats/p_adjust.hpp"

namespace feint::cli {

/// The raw option values as CLI11 parses them.
struct ReportOptions {
  std::string format = "text";
  std::string output = "-";
  bool apa = false;
  double alpha = 0.05;
  std::string alternative = "two.sided";
  double conf_level = 0.95;
  std::string p_adjust = "none";
  std::string label;
  std::string caption;
  bool latex_wide = false;
};

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

/// The validated options.
struct ResolvedReportOptions {
  report::OutputFormat format = report::OutputFormat::text;
  std::string output = "-";
  bool apa = false;
  double alpha = 0.05;
  stats::TestOptions test;
  stats::PAdjustMethod p_adjust = stats::PAdjustMethod::none;
  report::TablePresentation presentation;
};

/// Validates: format name, alpha and conf-level in (0, 1), alternative, p-adjust method. Throws
/// UsageError (exit 64) naming the option and the accepted values.
ResolvedReportOptions resolve_report_options(const ReportOptions& options);

/// Parses a `--p-adjust` value: R's method names in any case, and R's alias "fdr" for BH.
/// Throws UsageError naming the accepted values.
stats::PAdjustMethod parse_p_adjust_option(std::string_view text);

/// Parses `--compare A,B` (the two conditions, trimmed). Throws UsageError otherwise.
std::pair<std::string, std::string> parse_compare(const std::string& text);

/// Parses repeated `--metric NAME[=REF]`; empty input gives the paper's defaults. Throws
/// UsageError for a malformed spec or a metric named twice.
std::vector<report::MetricSpec> parse_metric_specs(const std::vector<std::string>& texts);

/// Writes `content` to `path` atomically (temporary file + rename; `-` = standard output).
void write_report(const std::string& path, std::string_view content);

}  // namespace feint::cli

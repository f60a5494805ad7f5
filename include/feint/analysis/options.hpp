// feint/analysis/options.hpp - the settings of the scoring and of the statistical tests as the
// command line and feint.toml spell them (text), and their conversion into the library's typed
// settings. Shared by every command, so that `--alpha 2` or `--map pad` is refused with the same
// message by `feint analyze`, `feint table` and `feint likert`.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "feint/metrics/score.hpp"
#include "feint/report/table1.hpp"
#include "feint/report/writers.hpp"
#include "feint/stats/htest.hpp"
#include "feint/stats/p_adjust.hpp"

namespace feint::analysis {

/// The scoring options of `feint score` and `feint analyze` (docs/metrics.md).
struct ScoreOptions {
  std::optional<double> trim, trim_start, trim_end;
  double deadband = 1e-9;
  std::string norm = "speed";
  std::optional<double> pad_speed;
  std::vector<std::string> maps;  ///< NAME=COLUMN
  std::string delimiter;          ///< "" = detect
  std::string on_error = "strict";
  std::string time_unit = "s";
};

/// Typed scoring settings; throws UsageError naming the option for a value it cannot take.
metrics::ScoreSettings score_settings(const ScoreOptions& options);

/// The test and output options shared by the table commands.
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

struct ResolvedReportOptions {
  report::OutputFormat format = report::OutputFormat::text;
  std::string output = "-";
  bool apa = false;
  double alpha = 0.05;
  stats::TestOptions test;
  stats::PAdjustMethod p_adjust = stats::PAdjustMethod::none;
  report::TablePresentation presentation;
};

/// Checks and converts; UsageError names the option (--alpha, --conf-level, ...).
ResolvedReportOptions resolve_report_options(const ReportOptions& options);

/// none, bonferroni, holm, hochberg, hommel, BH (alias fdr), BY; any case. Throws UsageError.
stats::PAdjustMethod parse_p_adjust_option(std::string_view text);

/// "A,B" -> (A, B). Throws UsageError.
std::pair<std::string, std::string> parse_compare(const std::string& text);

/// --metric NAME=REF list (default: the paper's error=0.5 confusion=0.95). Throws UsageError.
std::vector<report::MetricSpec> parse_metric_specs(const std::vector<std::string>& texts);

}  // namespace feint::analysis

// feint/analysis/settings.hpp - every setting of a study run (`feint analyze`), named as the
// options of `feint analyze --help` and the keys of feint.toml: the option groups as the command
// line and feint.toml spell them (text) with their conversion into the library's typed settings,
// and the feint.toml text that reproduces a run (settings_toml): the report prints it and feint
// reads it back unchanged. The option groups are shared by every command, so that `--alpha 2` or
// `--map pad` is refused with the same message by `feint analyze`, `feint table` and
// `feint likert`; a Study is made from them (study.hpp), so they live here, upstream of the
// commands that bind them.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "feint/metrics/score.hpp"
#include "feint/stats/htest.hpp"
#include "feint/stats/p_adjust.hpp"
#include "feint/tables/likert.hpp"
#include "feint/tables/table1.hpp"
#include "feint/tables/writers.hpp"

namespace feint::analysis {

/// The scoring options of `feint score` and `feint analyze` (docs/metrics.md).
struct ScoreOptions {
  std::optional<double> trim, trim_start, trim_end;
  double deadband = 1e-9;
  double belief_deadband = 0.05;
  std::string norm = "raw";
  std::optional<double> pad_speed;
  std::vector<std::string> maps;  ///< NAME=COLUMN
  std::string delimiter;          ///< "" = detect
  std::string on_error = "strict";
  std::string time_unit = "s";
  // Other labs' exports (docs/formats.md "Files from other labs").
  std::string decimal;
  bool no_header = false;
  std::string columns;
  std::string iteration_base;
  std::string participant_from_path;
  std::string samples_column;
  bool single_condition = false;
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
  /// Scale r of the JZS Bayes factors' Cauchy prior (docs/bayes-factors.md): a number > 0 or
  /// BayesFactor's names medium (sqrt(2)/2), wide (1), ultrawide (sqrt(2)).
  std::string bf_prior_scale = "medium";
};

struct ResolvedReportOptions {
  tables::OutputFormat format = tables::OutputFormat::text;
  std::string output = "-";
  bool apa = false;
  double alpha = 0.05;
  stats::TestOptions test;
  stats::PAdjustMethod p_adjust = stats::PAdjustMethod::none;
  tables::TablePresentation presentation;
  double bf_prior_r = 0.7071067811865476;  ///< sqrt(2)/2, BayesFactor's "medium"
};

/// Checks and converts; UsageError names the option (--alpha, --conf-level, ...).
ResolvedReportOptions resolve_report_options(const ReportOptions& options);

inline constexpr const char* kDesignHelp =
    "between (each participant saw one condition) or within (each saw every condition: paired "
    "tests, condition within participants); default: read off the data";

inline constexpr const char* kBfPriorScaleHelp =
    "Scale r of the JZS Bayes factors' Cauchy prior: a number > 0, or medium (sqrt(2)/2, the "
    "default), wide (1), ultrawide (sqrt(2))";
/// --bf-prior-scale: a finite number > 0, or medium (sqrt(2)/2), wide (1), ultrawide (sqrt(2)), any
/// case. Throws UsageError naming the option.
double parse_bf_prior_scale(std::string_view text);

/// none, bonferroni, holm, hochberg, hommel, BH (alias fdr), BY; any case. Throws UsageError.
stats::PAdjustMethod parse_p_adjust_option(std::string_view text);

/// "A,B" -> (A, B). Throws UsageError.
std::pair<std::string, std::string> parse_compare(const std::string& text);

/// --metric NAME=REF list (default: the paper's error=0.5 confusion=0.95). Throws UsageError.
std::vector<tables::MetricSpec> parse_metric_specs(const std::vector<std::string>& texts);

/// The questionnaire options of `feint likert` and `feint analyze` (docs/likert.md). Lists may
/// hold comma-separated names ("a,b"); they are split and trimmed.
struct LikertOptions {
  std::string layout = "auto";
  std::string scale = "1-7";
  std::string labels;              ///< "Strongly disagree=1,Disagree=2,..." ("" = built-in)
  std::vector<std::string> items;  ///< NAME or NAME=COLUMN
  std::string id_column = "participant";
  std::string condition_column = "condition";
  std::string item_column = "item";
  std::string response_column = "response";
  std::vector<std::string> reverse;
  std::vector<std::string> composites;  ///< NAME=ITEM,ITEM,...
  std::optional<double> reference;      ///< default: the scale midpoint
  std::string alpha_missing = "pairwise";
  bool keep_unfinished = false;
  bool keep_previews = false;
};

/// The Likert analysis settings (loading, composites, reference, tests); throws UsageError naming
/// the option for a value it cannot take.
tables::LikertSettings likert_settings(const LikertOptions& options,
                                       const ResolvedReportOptions& tests);

struct AnalysisSettings {
  // Scoring (feint score).
  std::vector<std::string> logs;  ///< files, folders or globs relative to the study; default logs/
  ScoreOptions scoring;
  // Tables (feint table).
  std::vector<std::string> metrics;  ///< NAME=REF; default error=0.5 confusion=0.95
  std::string compare;               ///< "A,B" or ""
  /// between, within, or "" (read off the data; models/condition_design.hpp).
  std::string design;
  bool var_equal = false;
  bool paired = false;
  std::optional<double> equivalence;
  /// ID:KEY=VALUE changes to the study's hypotheses (feint.toml [hypotheses.ID]); default the
  /// paper's H1 and H2 (analysis::parse_hypotheses).
  std::vector<std::string> hypotheses;
  // Questionnaire (feint likert).
  std::string questionnaire;  ///< relative to the study; default questionnaire.csv when present
  LikertOptions likert;  ///< --likert-scale, --likert-reference, --layout, --items, ...
  // Tests and output (format, output, label and caption are not used by a study run).
  ReportOptions report;
  std::vector<std::string> formats = {"text", "markdown", "latex", "csv", "json"};
  bool no_figures = false;
  bool no_report = false;
  std::vector<std::string> figure_formats = {"pdf", "svg"};
};

/// The settings as a feint.toml that `feint analyze --config FILE STUDY` accepts and that
/// reproduces the run: every setting, one `name = value` line, in the order of `feint analyze
/// --help`; a setting without a value (an unset optional) is a comment line.
std::string settings_toml(const AnalysisSettings& settings);

}  // namespace feint::analysis

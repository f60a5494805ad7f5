// feint/analysis/settings.hpp - every setting of a study run (`feint analyze`), named as the
// options of `feint analyze --help` and the keys of feint.toml, and the feint.toml text that
// reproduces a run (settings_toml): the report prints it and feint reads it back unchanged.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "feint/analysis/options.hpp"

namespace feint::analysis {

struct AnalysisSettings {
  // Scoring (feint score).
  std::vector<std::string> logs;  ///< files, folders or globs relative to the study; default logs/
  ScoreOptions scoring;
  // Tables (feint table).
  std::vector<std::string> metrics;  ///< NAME=REF; default error=0.5 confusion=0.95
  std::string compare;               ///< "A,B" or ""
  bool var_equal = false;
  bool paired = false;
  std::optional<double> equivalence;
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

// feint/analysis/study.hpp - a study: its pad-trace logs, its questionnaire and its settings,
// located and validated once (load_study), before any statistic is computed.
//
// A study folder holds `logs/` (pad-trace logs, any number of .csv/.csv.gz files), optionally
// `questionnaire.csv` (Likert), and optionally `feint.toml` (the settings, read by the command
// line; see settings.hpp). The logs are not held in memory: they are streamed when scored
// (analyze), so a study of millions of rows needs no more memory than one trial.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "feint/analysis/settings.hpp"
#include "feint/io/questionnaire.hpp"
#include "feint/models/condition_design.hpp"
#include "feint/tables/likert.hpp"

namespace feint::analysis {

struct Study {
  std::string folder;             ///< as given
  std::string name;               ///< the folder's last component ("demo")
  std::vector<std::string> log_inputs;  ///< the logs as named: files, folders, globs (in the study)
  std::vector<std::string> logs;        ///< the log files they expand to
  std::string questionnaire;      ///< path of the questionnaire, "" = the study has none
  std::string config;             ///< the settings file that was read ("" = none); not read here
  AnalysisSettings settings;
  /// The Likert settings (questionnaire loading options, composites, reference, tests).
  tables::LikertSettings likert;
  std::optional<io::Questionnaire> answers;  ///< loaded and validated; empty without one
  /// STUDY/questionnaire_yesno.csv (written by `feint collect`) when present: yes/no answers
  /// read with the questionnaire's column options (docs/yes-no.md).
  std::optional<io::Questionnaire> yes_no_answers;
  /// Typed settings, checked once.
  metrics::ScoreSettings scoring;
  ResolvedReportOptions tests;
  std::vector<tables::MetricSpec> metrics;
  std::optional<std::pair<std::string, std::string>> compare;
  std::optional<models::ConditionDesign> design;  ///< declared; empty = read off the data
  std::vector<tables::OutputFormat> formats;

  /// Every input (log folders and files, questionnaire, settings file): what an output folder
  /// must stay clear of.
  std::vector<std::string> inputs() const;
};

/// Locates the inputs of `folder` under `settings` (logs relative to the study, default logs/;
/// the questionnaire, default questionnaire.csv when present), checks every setting (UsageError,
/// naming the option) and loads the questionnaire (InvalidData naming file, row and column).
/// Throws IoError when the folder does not exist, InvalidData when it has no logs.
/// `config` is recorded only (the command line reads the settings file).
Study load_study(const std::string& folder, const AnalysisSettings& settings,
                 const std::string& config = "");

/// A path as the report shows it: relative to `base` when it lies inside it (or relative to
/// the current folder otherwise), never absolute unless it has no relative form; '/' separators.
std::string display_path(const std::string& path, const std::string& base);

/// What a path outside every folder a report shares with its study is shown as: PATH_TO/NAME.
inline constexpr const char* kPathPlaceholder = "PATH_TO";

/// `path` as seen from `folder` (a report's folder), so that a command run from there finds it:
/// relative to `folder` ('/' separators; `folder` itself as ../NAME), or PATH_TO/NAME when the two
/// share no folder but the root (a shared report then carries no one's folder layout). Neither
/// needs to exist.
std::string path_from(const std::string& path, const std::string& folder);

}  // namespace feint::analysis

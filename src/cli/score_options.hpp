// src/cli/score_options.hpp - the scoring options shared by `feint score` and `feint analyze`.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "feint/metrics/score.hpp"

namespace feint::cli {

/// The raw values of the scoring options as CLI11 parses them.
struct ScoreOptions {
  std::optional<double> trim, trim_start, trim_end;
  double deadband = 1e-9;
  double belief_deadband = 0.05;
  std::string norm = "speed";
  std::optional<double> pad_speed;
  std::vector<std::string> maps;
  std::string delimiter;
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

/// Registers --trim, --trim-start, --trim-end, --deadband, --confusion-norm, --pad-speed, --map,
/// --delimiter, --on-error, --time-unit, --decimal, --no-header, --columns, --iteration-base,
/// --participant-from-path, --samples-column and --single-condition on `cmd` (in help group `group`, if not empty), bound to `options`.
void add_score_options(CLI::App& cmd, ScoreOptions& options, const std::string& group = "");

/// The settings they stand for (trims, dead band, normalisation, pad speed, column map,
/// delimiter, error mode). Throws UsageError naming the option for a malformed value.
metrics::ScoreSettings score_settings(const ScoreOptions& options);

}  // namespace feint::cli

// src/cli/score_options.hpp - the scoring options shared by `feint score` and `feint analyze`.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "feint/analysis/options.hpp"

namespace feint::cli {

/// The option values and their checks live in the library (feint/analysis/options.hpp).
using analysis::score_settings;
using analysis::ScoreOptions;

/// Registers --trim, --trim-start, --trim-end, --deadband, --confusion-norm, --pad-speed, --map,
/// --delimiter, --on-error, --time-unit, --decimal, --no-header, --columns, --iteration-base,
/// --participant-from-path, --samples-column and --single-condition on `cmd` (in help group `group`, if not empty), bound to `options`.
void add_score_options(CLI::App& cmd, ScoreOptions& options, const std::string& group = "");
}  // namespace feint::cli

// feint/commands/score_command.hpp - `feint score`: pad-trace logs -> one row of metrics per trial
// (feint/metrics/score.hpp; docs/scoring.md).
#pragma once

#include <string>
#include <vector>

#include "feint/analysis/settings.hpp"

namespace feint::commands {

struct ScoreCommandOptions {
  std::vector<std::string> inputs;  ///< files, folders, globs; "-" = standard input
  std::string output;               ///< the scores CSV; "-" = standard output
  analysis::ScoreOptions scoring;   ///< the loader and scoring options every log reader shares
  std::string rejects;              ///< "" = OUTPUT.rejects.csv
  std::string sidecar;              ///< "" = OUTPUT.meta.json
  bool unsorted = false;
  std::string tool_version = "unknown";
};

/// Scores the logs into `output` (a progress line on standard error while it runs, when that is a
/// terminal) and returns the summary that `feint score` prints on standard error. Throws
/// UsageError naming a bad option, InvalidData naming file, row and column.
std::string score_command(const ScoreCommandOptions& options);

}  // namespace feint::commands

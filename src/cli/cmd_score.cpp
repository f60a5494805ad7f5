// `feint score`: pad-trace logs -> one row of metrics per trial (a thin layer over
// feint/metrics/score.hpp; see docs/scoring.md).
#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "feint/commands/score_command.hpp"
#include "options.hpp"

namespace feint::cli {

namespace {

void run(const commands::ScoreCommandOptions& a) {
  const std::string summary = commands::score_command(a);
  std::fflush(stdout);
  fmt::print(stderr, "{}", summary);
}

}  // namespace

void add_score_command(CLI::App& app) {
  auto args = std::make_shared<commands::ScoreCommandOptions>();
  args->tool_version = FEINT_VERSION;
  auto* cmd = app.add_subcommand(
      "score",
      "Score pad-trace logs: one row per trial with error and confusion (seed paper sec. VI, "
      "docs/metrics.md).");
  cmd->footer(
      "Input: long CSV, one row per pad sample, columns participant, [condition], iteration, "
      "[strategy], [variant], target (left/right/0/1/number in [0,1]), t (seconds), pad ([0,1]), "
      "[pad_speed] (pad units/s). A trial = (participant, condition, iteration); its rows must "
      "be contiguous.\n"
      "Output columns: participant, condition, iteration, strategy, variant, target, n_samples, "
      "duration, error, confusion, reversal_time, reversals, final_pad, overspeed_segments, "
      "signed_area, max_deviation, flips, time_deceived, final_belief_time (belief-trace "
      "measures, docs/metrics.md); the "
      "settings are recorded in OUTPUT.meta.json.\n"
      "Exit status: 0 ok, 64 bad command line, 65 invalid data, 74 cannot read/write a file.");
  cmd->add_option("inputs", args->inputs,
                  "Log files (.csv, .tsv, optionally .gz), directories (all data files below "
                  "them) or quoted globs; - = stdin")
      ->required();
  cmd->add_option("-o,--output", args->output, "Scores CSV to write (atomically); - = stdout")
      ->required();
  add_score_options(*cmd, args->scoring);
  cmd->add_option("--rejects", args->rejects,
                  "With --on-error skip: CSV listing each skipped trial (file, line, key, rows, "
                  "reason); default OUTPUT.rejects.csv");
  cmd->add_option("--sidecar", args->sidecar,
                  "Where to record the settings and counts (JSON); default OUTPUT.meta.json, none "
                  "for -o - unless given");
  cmd->add_flag("--unsorted", args->unsorted,
                "Trials' rows may be scattered (across files too): buffer all rows and group them "
                "(memory grows with the input)");
  cmd->callback([args] { run(*args); });
}

}  // namespace feint::cli

// `feint score`: pad-trace logs -> one row of metrics per trial (a thin layer over
// feint/metrics/score.hpp; see docs/scoring.md).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/metrics/score.hpp"
#include "progress.hpp"
#include "score_options.hpp"

#ifndef FEINT_VERSION
#define FEINT_VERSION "dev"
#endif

namespace feint::cli {

namespace {

struct ScoreArgs {
  std::vector<std::string> inputs;
  std::string output;
  ScoreOptions scoring;
  std::string rejects;
  std::string sidecar;
  bool unsorted = false;
};

void run(const ScoreArgs& a) {
  metrics::ScoreSettings s = score_settings(a.scoring);
  s.rejects_path = a.rejects;
  s.sidecar_path = a.sidecar;
  s.unsorted = a.unsorted;
  s.tool_version = FEINT_VERSION;

  auto progress = std::make_shared<ProgressLine>("feint score");
  if (progress->active()) {
    s.on_progress = [progress](const metrics::ScoreProgress& p) {
      progress->update(p.rows_read, p.bytes_read, p.trials_scored, p.trials_rejected);
    };
  }
  const auto summary = metrics::score_to_file(a.inputs, s, a.output);
  progress->finish();

  std::string line = fmt::format("feint score: {} rows read from {} file(s), {} trials scored, {} "
                                 "rejected",
                                 summary.rows_read, summary.files, summary.trials_scored,
                                 summary.trials_rejected);
  if (!summary.rejects_path.empty()) line += fmt::format(" (list in {})", summary.rejects_path);
  line += fmt::format(" -> {}", summary.output_path == "-" ? "stdout" : summary.output_path);
  if (!summary.sidecar_path.empty()) line += fmt::format(" (settings in {})", summary.sidecar_path);
  std::fflush(stdout);
  fmt::print(stderr, "{}\n", line);
  if (summary.overspeed_trials > 0) {
    fmt::print(stderr, "feint score: warning: {} trial(s) move faster than the pad speed (see "
                       "the overspeed_segments column)\n", summary.overspeed_trials);
  }
}

}  // namespace

void add_score_command(CLI::App& app) {
  auto args = std::make_shared<ScoreArgs>();
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

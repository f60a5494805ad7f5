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

#ifndef FEINT_VERSION
#define FEINT_VERSION "dev"
#endif

namespace feint::cli {

namespace {

struct ScoreArgs {
  std::vector<std::string> inputs;
  std::string output;
  std::optional<double> trim, trim_start, trim_end;
  double deadband = 1e-9;
  std::string norm = "speed";
  std::optional<double> pad_speed;
  std::vector<std::string> maps;
  std::string delimiter;
  std::string on_error = "strict";
  std::string rejects;
  std::string sidecar;
  bool unsorted = false;
};

char parse_delimiter(const std::string& text) {
  const std::string d = io::to_lower(text);
  if (d.empty() || d == "auto") return 0;
  if (d == "," || d == "comma") return ',';
  if (d == ";" || d == "semicolon") return ';';
  if (d == "\t" || d == "\\t" || d == "tab") return '\t';
  if (d == "|" || d == "pipe") return '|';
  throw UsageError(fmt::format("--delimiter '{}': expected , ; tab | or auto", text));
}

void run(const ScoreArgs& a) {
  metrics::ScoreSettings s;
  if (a.trim) s.metrics.trim_start = s.metrics.trim_end = *a.trim;
  if (a.trim_start) s.metrics.trim_start = *a.trim_start;
  if (a.trim_end) s.metrics.trim_end = *a.trim_end;
  s.metrics.deadband = a.deadband;
  s.metrics.norm = *metrics::parse_confusion_norm(a.norm);  // CLI11 checked membership
  s.metrics.pad_speed = a.pad_speed;
  for (const auto& m : a.maps) {
    const auto eq = m.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == m.size()) {
      throw UsageError(fmt::format("--map '{}': expected NAME=COLUMN, e.g. --map pad=position", m));
    }
    const std::string name = io::to_lower(io::trim(m.substr(0, eq)));
    if (s.column_map.count(name) != 0) {
      throw UsageError(fmt::format("--map: '{}' is mapped twice", name));
    }
    s.column_map[name] = std::string(io::trim(m.substr(eq + 1)));
  }
  s.delimiter = parse_delimiter(a.delimiter);
  s.on_error = a.on_error == "skip" ? metrics::OnError::skip : metrics::OnError::strict;
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
      "shared/spec/metrics.md).");
  cmd->footer(
      "Input: long CSV, one row per pad sample, columns participant, [condition], iteration, "
      "[strategy], [variant], target (left/right/0/1/number in [0,1]), t (seconds), pad ([0,1]), "
      "[pad_speed] (pad units/s). A trial = (participant, condition, iteration); its rows must "
      "be contiguous.\n"
      "Output columns: participant, condition, iteration, strategy, variant, target, n_samples, "
      "duration, error, confusion, reversal_time, reversals, final_pad, overspeed_segments; the "
      "settings are recorded in OUTPUT.meta.json.\n"
      "Exit status: 0 ok, 64 bad command line, 65 invalid data, 74 cannot read/write a file.");
  cmd->add_option("inputs", args->inputs,
                  "Log files (.csv, .tsv, optionally .gz), directories (all data files below "
                  "them) or quoted globs; - = stdin")
      ->required();
  cmd->add_option("-o,--output", args->output, "Scores CSV to write (atomically); - = stdout")
      ->required();
  auto* trim = cmd->add_option("--trim", args->trim,
                               "Fraction of each trial's duration excluded at BOTH ends, in [0, 1) "
                               "(default 0.05)");
  cmd->add_option("--trim-start", args->trim_start,
                  "Fraction of the duration excluded at the start, in [0, 1) (default 0.05)")
      ->excludes(trim);
  cmd->add_option("--trim-end", args->trim_end,
                  "Fraction of the duration excluded at the end, in [0, 1) (default 0.05)")
      ->excludes(trim);
  cmd->add_option("--deadband", args->deadband,
                  "Dead band eps in pad units: a segment moving <= eps has no direction for the "
                  "reversal rule (default 1e-9)");
  cmd->add_option("--confusion-norm", args->norm,
                  "Confusion normalisation: 'speed' = moving fraction at the pad speed, in [0, 1] "
                  "(default); 'raw' = the paper's eq. 4 as printed (unbounded)")
      ->check(CLI::IsMember({"speed", "raw"}, CLI::ignore_case));
  cmd->add_option("--pad-speed", args->pad_speed,
                  "Pad speed v in pad units per second for every trial; replaces a pad_speed "
                  "column (needed by --confusion-norm speed when the logs have none)");
  cmd->add_option("--map", args->maps,
                  "NAME=COLUMN: read field NAME (participant, condition, iteration, strategy, "
                  "variant, target, t, pad, pad_speed) from the study's column COLUMN; repeatable")
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--delimiter", args->delimiter,
                  "Field separator: , ; tab | (default: detected per file from its header)");
  cmd->add_option("--on-error", args->on_error,
                  "strict = stop at the first invalid trial (default); skip = leave invalid trials "
                  "out and list them in the rejects file")
      ->check(CLI::IsMember({"strict", "skip"}));
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

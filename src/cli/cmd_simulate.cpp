// `feint simulate selection`: the strategy selection simulator and its entropy analysis
// (selection.md; docs/simulation.md). `feint simulate study`: a simulated user study.
// `feint simulate trajectories`: the observer's deceptiveness measures of each strategy
// (docs/observer.md).
#include <fmt/format.h>

#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "feint/tables/simulation_render.hpp"
#include "feint/tables/trajectory_render.hpp"
#include "feint/sim/options.hpp"
#include "options.hpp"

namespace feint::cli {

namespace {

void run_selection(const sim::SelectionOptions& o) {
  const std::string format = tables::output_format(o.format, o.output);
  const std::vector<sim::SimulationSettings> all = sim::selection_settings(o);
  std::vector<sim::SimulationSummary> rows;
  rows.reserve(all.size());
  for (const auto& s : all) rows.push_back(sim::simulate_selection(s));
  if (!o.sequences.empty()) tables::write_selection_sequences(o.sequences, all);
  if (!o.occurrence.empty()) tables::write_selection_occurrence(o.occurrence, rows);
  write_report(o.output, tables::render_selection(rows, format));
}

void add_selection_command(CLI::App& parent) {
  auto opts = std::make_shared<sim::SelectionOptions>();
  auto* cmd = parent.add_subcommand(
      "selection",
      "Simulate runs of a strategy selection algorithm and report entropy, repetition, conditional "
      "entropy and least-seen-guesser accuracy (docs/selection.md, docs/simulation.md).");
  cmd->option_defaults()->always_capture_default();  // each option shows its default
  cmd->add_option("--algorithm,-a", opts->algorithm,
                  "random, fixed-block, fixed-balanced or adaptive");
  cmd->add_option("--lambda,-l", opts->lambda, "adaptive: share of p_i moved away when S_i occurs")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--iterations,-n", opts->iterations, "iterations per run (N)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--runs,-r", opts->runs, "number of runs (R)")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 40));
  cmd->add_option("--seed,-s", opts->seed, "random seed (unsigned 64-bit)");
  cmd->add_option("--batch", opts->batch,
                  "runs per batch for the quantiles of the batch mean entropy (0 = none)");
  cmd->add_option("--threads", opts->threads, "worker threads (0 = all cores)")
      ->check(CLI::Range(0u, 1024u));
  cmd->add_option("--targets", opts->targets, "true targets: random (coin flips) or balanced");
  cmd->add_flag("--compare", opts->compare, "run all four algorithms on the same settings");
  cmd->add_option("--sweep-lambda", opts->sweep,
                  "FROM:TO:STEP: the adaptive algorithm over a grid of lambda, e.g. 0:1:0.05");
  cmd->add_option("--format,-f", opts->format,
                  "text, markdown, csv or json (default: from the -o extension, else text)");
  cmd->add_option("--output,-o", opts->output, "summary file (- = standard output)");
  cmd->add_option("--sequences", opts->sequences,
                  "write every run's iterations (tidy CSV: algorithm, lambda, run, iteration, "
                  "strategy, variant, target)");
  cmd->add_option("--occurrence", opts->occurrence,
                  "write per-iteration occurrence probabilities (tidy CSV: algorithm, lambda, "
                  "iteration, strategy, probability, cumulative_share, runs)");
  cmd->callback([opts] { run_selection(*opts); });
}

void run_study(const sim::StudyOptions& o) {
  const sim::StudySettings s = sim::study_settings(o);
  const auto people = sim::write_study(s, o.out, o.replace, FEINT_VERSION);
  // Where the files are, and the mean trial error by condition (first and last five iterations).
  fmt::print("{}", tables::study_summary_text(people, s, o.out));
}

void add_study_command(CLI::App& parent) {
  auto opts = std::make_shared<sim::StudyOptions>();
  auto* cmd = parent.add_subcommand(
      "study",
      "Simulate a user study (adaptive vs random selection) and write pad-trace logs "
      "(DIR/logs/P*.csv.gz) and a Likert questionnaire (DIR/questionnaire.csv); "
      "docs/simulation.md.");
  cmd->add_option("-o,--output,--out", opts->out,
                  "output directory (created if missing; a non-empty one is refused)")
      ->required();
  cmd->add_flag("--replace", opts->replace,
                "replace the folder of an earlier feint simulate study whole (never a folder "
                "holding other files)");
  cmd->add_option("--design", opts->design, "between or within participants")->capture_default_str();
  cmd->add_option("--conditions", opts->conditions, "two or more of adaptive, random, fixed-block, fixed-balanced, "
                  "each ALGORITHM or NAME=ALGORITHM (e.g. a=random,b=random)")->capture_default_str();
  cmd->add_option("--participants,-p", opts->participants, "participants per condition (within: in all)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--iterations,-n", opts->iterations, "iterations per participant")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--lambda,-l", opts->lambda, "lambda of the adaptive condition")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--seed,-s", opts->seed, "random seed (unsigned 64-bit)")->capture_default_str();
  cmd->add_option("--sample-rate", opts->sample_rate, "pad samples per second (Hz)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 1000.0));
  cmd->add_option("--pad-speed", opts->pad_speed, "pad speed (pad units per second)")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 100.0));
  cmd->add_option("--participant-model", opts->participant_model,
                  "how simulated people infer the goal: heuristic (tanh of the robot's x) or "
                  "goal-inference (Bayesian observer; docs/simulation.md)")
      ->capture_default_str();
  cmd->add_option(
      "--observer", opts->observer,
      "NAME=VALUE: set a parameter of the simulated observer (repeatable), e.g. beta=1.5 "
      "noise_sd=0.1; the names and defaults are in docs/simulation.md");
  cmd->add_option("--targets", opts->targets, "K >= 2 targets (K > 2: people point)")->capture_default_str();
  cmd->add_option("--layout", opts->layout, "fixed (a row) or random (per round)")->capture_default_str();
  cmd->callback([opts] { run_study(*opts); });
}

void run_trajectories(const sim::TrajectoriesOptions& o) {
  const std::string format = tables::output_format(o.format, o.output);
  const sim::TrajectoryMeasures m = sim::trajectory_measures(o);
  write_report(o.output, tables::render_trajectories(m.rows, m.settings, format));
}

void add_trajectories_command(CLI::App& parent) {
  auto opts = std::make_shared<sim::TrajectoriesOptions>();
  auto* cmd = parent.add_subcommand(
      "trajectories",
      "Deceptiveness of every strategy and version of the paper (both targets) under the "
      "goal-inference "
      "observer: legibility, time deceived, last deceptive point, cost overhead, and the error and "
      "confusion of the observer's belief as if it were a pad (docs/observer.md).");
  cmd->option_defaults()->always_capture_default();  // each option shows its default
  cmd->add_option("--beta", opts->beta, "observer rationality beta (1/m, >= 0)");
  cmd->add_option("--tau", opts->tau, "observer response delay tau (s, >= 0)");
  cmd->add_option("--prior", opts->prior, "prior P(right), in (0, 1)");
  cmd->add_option("--pad-speed", opts->pad_speed,
                  "pad speed v (pad units/s) normalising the belief's confusion");
  cmd->add_option(
      "--path", opts->path,
      "measure this path instead (CSV with columns t, x, y in the default geometry: start "
      "(0, 0), targets (-2, 4) and (2, 4))");
  cmd->add_option("--target", opts->target, "with --path: the true target, left or right");
  cmd->add_option("--format,-f", opts->format,
                  "text, markdown, csv or json (default: from the -o extension, else text)");
  cmd->add_option("--output,-o", opts->output, "output file (- = standard output)");
  cmd->callback([opts] { run_trajectories(*opts); });
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("simulate",
                                 "Simulate strategy selection (entropy analysis), a whole user "
                                 "study, or the observer's view of "
                                 "the strategies' trajectories.");
  cmd->require_subcommand(1);
  add_selection_command(*cmd);
  add_study_command(*cmd);
  add_trajectories_command(*cmd);
}

}  // namespace feint::cli

// `feint simulate selection`: the strategy selection simulator and its entropy analysis
// (selection.md; docs/simulation.md). `feint simulate study`: a simulated user study.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/io/output.hpp"
#include "feint/report/simulation_render.hpp"
#include "feint/sim/simulation.hpp"
#include "feint/sim/study.hpp"
#include "feint/sim/sweep.hpp"

namespace feint::cli {

namespace {

using sim::Algorithm;

struct SelectionOptions {
  std::string algorithm = "adaptive";
  double lambda = 0.5;
  int iterations = 20;
  std::uint64_t runs = 10;
  std::uint64_t seed = 1;
  std::uint64_t batch = 10;
  unsigned threads = 0;
  std::string targets = "random";
  bool compare = false;
  std::string sweep;
  std::string format;
  std::string output = "-";
  std::string sequences;
  std::string occurrence;
};

/// `a:b:step` -> a, a + step, ..., up to b (inclusive, with a tolerance of step/1e6); each value
/// rounded to 12 significant digits so that 0:1:0.05 gives 0.15, not 0.15000000000000002.
std::string infer_format(const std::string& format, const std::string& output) {
  if (!format.empty()) {
    const std::string f = io::to_lower(format);
    if (f == "text" || f == "markdown" || f == "csv" || f == "json") return f;
    throw UsageError(fmt::format("--format '{}': expected text, markdown, csv or json", format));
  }
  auto ends = [&](const char* ext) {
    const std::string e = ext;
    return output.size() > e.size() && io::to_lower(output.substr(output.size() - e.size())) == e;
  };
  if (ends(".csv")) return "csv";
  if (ends(".json")) return "json";
  if (ends(".md")) return "markdown";
  return "text";
}

// --- summary rendering -----------------------------------------------------------------------
void run_selection(const SelectionOptions& o) {
  const std::string format = infer_format(o.format, o.output);
  sim::SimulationSettings base;
  base.run.algorithm = sim::parse_algorithm(o.algorithm);
  base.run.lambda = o.lambda;
  base.run.iterations = o.iterations;
  base.run.targets = sim::parse_target_order(o.targets);
  base.runs = o.runs;
  base.seed = o.seed;
  base.batch = o.batch;
  base.threads = o.threads;

  const std::vector<sim::SimulationSettings> all =
      sim::selection_grid(base, o.compare, o.sweep.empty() ? std::vector<double>{} : sim::parse_lambda_sweep(o.sweep));
  std::vector<sim::SimulationSummary> rows;
  rows.reserve(all.size());
  for (const auto& s : all) rows.push_back(sim::simulate_selection(s));

  if (!o.sequences.empty()) report::write_selection_sequences(o.sequences, all);
  if (!o.occurrence.empty()) report::write_selection_occurrence(o.occurrence, rows);

  const std::string text = report::render_selection(rows, format);
  io::AtomicOutput out(o.output);
  out.stream() << text;
  out.commit();
}

void add_selection_command(CLI::App& parent) {
  auto opts = std::make_shared<SelectionOptions>();
  auto* cmd = parent.add_subcommand(
      "selection",
      "Simulate runs of a strategy selection algorithm and report entropy, repetition, conditional "
      "entropy and least-seen-guesser accuracy (docs/selection.md, docs/simulation.md).");
  cmd->add_option("--algorithm,-a", opts->algorithm,
                  "random, fixed-block, fixed-balanced or adaptive")
      ->capture_default_str();
  cmd->add_option("--lambda,-l", opts->lambda, "adaptive: share of p_i moved away when S_i occurs")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--iterations,-n", opts->iterations, "iterations per run (N)")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--runs,-r", opts->runs, "number of runs (R)")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 40))
      ->capture_default_str();
  cmd->add_option("--seed,-s", opts->seed, "random seed (unsigned 64-bit)")->capture_default_str();
  cmd->add_option("--batch", opts->batch,
                  "runs per batch for the quantiles of the batch mean entropy (0 = none)")
      ->capture_default_str();
  cmd->add_option("--threads", opts->threads, "worker threads (0 = all cores)")
      ->check(CLI::Range(0u, 1024u))
      ->capture_default_str();
  cmd->add_option("--targets", opts->targets, "true targets: random (coin flips) or balanced")
      ->capture_default_str();
  cmd->add_flag("--compare", opts->compare, "run all four algorithms on the same settings");
  cmd->add_option("--sweep-lambda", opts->sweep,
                  "FROM:TO:STEP: the adaptive algorithm over a grid of lambda, e.g. 0:1:0.05");
  cmd->add_option("--format,-f", opts->format,
                  "text, markdown, csv or json (default: from the -o extension, else text)");
  cmd->add_option("--output,-o", opts->output, "summary file (- = standard output)")
      ->capture_default_str();
  cmd->add_option("--sequences", opts->sequences,
                  "write every run's iterations (tidy CSV: algorithm, lambda, run, iteration, "
                  "strategy, variant, target)");
  cmd->add_option("--occurrence", opts->occurrence,
                  "write per-iteration occurrence probabilities (tidy CSV: algorithm, lambda, "
                  "iteration, strategy, probability, cumulative_share, runs)");
  cmd->callback([opts] { run_selection(*opts); });
}

struct StudyOptions {
  std::string out;
  int participants = 20;
  int iterations = 20;
  double lambda = 0.5;
  std::uint64_t seed = 1;
  double sample_rate = 25.0;
  double pad_speed = 0.8;
};

void run_study(const StudyOptions& o) {
  sim::StudySettings s;
  s.participants = o.participants;
  s.iterations = o.iterations;
  s.lambda = o.lambda;
  s.seed = o.seed;
  s.geometry.sample_rate = o.sample_rate;
  s.observer.pad_speed = o.pad_speed;
  sim::validate(s.geometry);
  sim::validate(s.observer);
  const auto people = sim::write_study(s, o.out);
  // A short account: where the files are, and the mean trial error by condition (first and last
  // five iterations), computed on the written traces with the simple trapezoid error.
  fmt::print("{}", report::study_summary_text(people, s, o.out));
}

void add_study_command(CLI::App& parent) {
  auto opts = std::make_shared<StudyOptions>();
  auto* cmd = parent.add_subcommand(
      "study",
      "Simulate a user study (adaptive vs random selection) and write pad-trace logs "
      "(DIR/logs/P*.csv.gz) and a Likert questionnaire (DIR/questionnaire.csv); docs/simulation.md.");
  cmd->add_option("-o,--output,--out", opts->out, "output directory (created if missing)")
      ->required();
  cmd->add_option("--participants,-p", opts->participants, "participants per condition")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--iterations,-n", opts->iterations, "iterations per participant")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  cmd->add_option("--lambda,-l", opts->lambda, "lambda of the adaptive condition")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--seed,-s", opts->seed, "random seed (unsigned 64-bit)")->capture_default_str();
  cmd->add_option("--sample-rate", opts->sample_rate, "pad samples per second (Hz)")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  cmd->add_option("--pad-speed", opts->pad_speed, "pad speed (pad units per second)")
      ->check(CLI::Range(0.01, 100.0))
      ->capture_default_str();
  cmd->callback([opts] { run_study(*opts); });
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "simulate", "Simulate strategy selection (entropy analysis) or a whole user study.");
  cmd->require_subcommand(1);
  add_selection_command(*cmd);
  add_study_command(*cmd);
}

}  // namespace feint::cli

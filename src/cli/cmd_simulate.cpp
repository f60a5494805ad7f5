// `feint simulate selection`: the strategy selection simulator and its entropy analysis
// (selection.md; docs/simulation.md). `feint simulate study`: a simulated user study.
// `feint simulate trajectories`: the observer's deceptiveness measures of each strategy (docs/observer.md).
#include <cmath>
#include <fstream>
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
#include "feint/sim/trajectory_measures.hpp"

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
  std::string participant_model = "goal-inference";
  std::vector<std::string> observer;  // KEY=VALUE
};

void run_study(const StudyOptions& o) {
  sim::StudySettings s;
  s.participants = o.participants;
  s.iterations = o.iterations;
  s.lambda = o.lambda;
  s.seed = o.seed;
  s.geometry.sample_rate = o.sample_rate;
  if (sim::parse_participant_model(o.participant_model) == sim::ParticipantModel::heuristic) {
    s.observer = sim::ObserverParams{};  // feint 0.1's participant, with its own defaults
  }
  s.observer.pad_speed = o.pad_speed;
  for (const auto& kv : o.observer) sim::set_parameter(s.observer, kv);
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
  cmd->add_option("--participant-model", opts->participant_model,
                  "how simulated people infer the goal: heuristic (tanh of the robot's x) or "
                  "goal-inference (Bayesian observer; docs/simulation.md)")
      ->capture_default_str();
  cmd->add_option("--observer", opts->observer,
                  "NAME=VALUE: set a parameter of the simulated observer (repeatable), e.g. beta=1.5 "
                  "noise_sd=0.1; the names and defaults are in docs/simulation.md");
  cmd->callback([opts] { run_study(*opts); });
}


// --- trajectories: the observer's deceptiveness measures (docs/observer.md) ---------------------
struct TrajectoriesOptions {
  double beta = 1.0;
  double tau = 0.0;
  double prior = 0.5;
  double pad_speed = 0.8;
  std::string path;          // a custom path CSV (t,x,y) instead of the paper's strategies
  std::string target = "right";
  std::string format;
  std::string output = "-";
};

/// A path file: a header naming t, x and y (any order, other columns ignored), one sample a row.
std::vector<models::PathSample> read_path_file(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw IoError(fmt::format("{}: cannot open the path file", file));
  std::string line;
  if (!std::getline(in, line)) throw InvalidData(fmt::format("{}:1: the path file is empty", file));
  const auto head = io::split_csv_line(line);
  int ct = -1, cx = -1, cy = -1;
  for (std::size_t i = 0; i < head.size(); ++i) {
    const std::string h = io::to_lower(std::string(io::trim(head[i])));
    if (h == "t") ct = static_cast<int>(i);
    if (h == "x" || h == "robot_x") cx = static_cast<int>(i);
    if (h == "y" || h == "robot_y") cy = static_cast<int>(i);
  }
  if (ct < 0 || cx < 0 || cy < 0) {
    throw InvalidData(fmt::format("{}:1: the header must name the columns t, x and y (got '{}')", file, line));
  }
  std::vector<models::PathSample> out;
  for (std::uint64_t ln = 2; std::getline(in, line); ++ln) {
    if (io::trim(line).empty()) continue;
    const auto cells = io::split_csv_line(line);
    auto get = [&](int c, const char* name) {
      const auto i = static_cast<std::size_t>(c);
      const auto v = i < cells.size() ? io::parse_double(io::trim(cells[i])) : std::nullopt;
      if (!v) {
        throw InvalidData(fmt::format("{}:{}: column '{}': '{}' is not a number", file, ln, name,
                                      i < cells.size() ? cells[i] : std::string()));
      }
      return *v;
    };
    out.push_back({get(ct, "t"), get(cx, "x"), get(cy, "y")});
  }
  return out;
}

struct Column {
  std::string name;
  bool text;  // a string (quoted in JSON) rather than a number
};

const std::vector<Column>& trajectory_columns() {
  static const std::vector<Column> cols = {
      {"strategy", true},         {"variant", true},          {"target", true},
      {"duration", false},        {"path_length", false},     {"cost_overhead", false},
      {"legibility", false},      {"time_deceived", false},   {"last_deceptive_point", false},
      {"final_belief", false},    {"belief_error", false},    {"belief_confusion", false},
      {"belief_overspeed_segments", false}, {"beta", false},  {"tau", false},
      {"prior_right", false},     {"pad_speed", false}};
  return cols;
}

std::vector<std::string> trajectory_cells(const sim::TrajectoryMeasuresRow& r, const TrajectoriesOptions& o) {
  const auto& m = r.measures;
  auto d = [](double x) { return io::format_double(x); };
  return {r.strategy, r.variant, r.target, d(m.duration), d(m.path_length), d(m.cost_overhead),
          d(m.legibility), d(m.time_deceived), d(m.last_deceptive_point), d(m.final_belief),
          d(m.belief_error), d(m.belief_confusion), std::to_string(m.belief_overspeed_segments),
          d(o.beta), d(o.tau), d(o.prior), d(o.pad_speed)};
}

std::string render_trajectories(const std::vector<sim::TrajectoryMeasuresRow>& rows,
                                const TrajectoriesOptions& o, const std::string& format) {
  const auto& cols = trajectory_columns();
  std::string out;
  if (format == "csv") {
    for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + cols[i].name;
    out += '\n';
    for (const auto& r : rows) {
      const auto cells = trajectory_cells(r, o);
      for (std::size_t i = 0; i < cells.size(); ++i) out += (i ? "," : "") + io::csv_escape(cells[i]);
      out += '\n';
    }
    return out;
  }
  if (format == "json") {
    out = "[\n";
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const auto cells = trajectory_cells(rows[k], o);
      out += "  {";
      for (std::size_t i = 0; i < cells.size(); ++i) {
        out += (i ? ", " : "") + io::json_quote(cols[i].name) + ": " +
               (cols[i].text ? io::json_quote(cells[i]) : (cells[i].empty() ? "null" : cells[i]));
      }
      out += k + 1 < rows.size() ? "},\n" : "}\n";
    }
    return out + "]\n";
  }
  const bool md = format == "markdown";
  const std::vector<std::string> head = {"strategy", "variant", "target", "T (s)", "overhead",
                                         "legibility", "deceived", "LDP", "error", "confusion", "overspeed"};
  std::vector<std::vector<std::string>> body;
  auto f = [](double x) { return std::isnan(x) ? std::string("-") : fmt::format("{:.4f}", x); };
  for (const auto& r : rows) {
    const auto& m = r.measures;
    body.push_back({r.strategy, r.variant, r.target, fmt::format("{:.2f}", m.duration), f(m.cost_overhead),
                    f(m.legibility), f(m.time_deceived), f(m.last_deceptive_point), f(m.belief_error),
                    f(m.belief_confusion), std::to_string(m.belief_overspeed_segments)});
  }
  std::vector<std::size_t> width(head.size());
  for (std::size_t i = 0; i < head.size(); ++i) {
    width[i] = head[i].size();
    for (const auto& b : body) width[i] = std::max(width[i], b[i].size());
  }
  auto line = [&](const std::vector<std::string>& cells) {
    std::string l = md ? "|" : "";
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const std::string cell = i < 3 ? fmt::format("{:<{}}", cells[i], width[i]) : fmt::format("{:>{}}", cells[i], width[i]);
      l += md ? " " + cell + " |" : (i ? "  " : "") + cell;
    }
    return l + "\n";
  };
  out += fmt::format("Observer: beta = {} 1/m, tau = {} s, P(right) = {}; confusion normalised by the pad "
                     "speed v = {} pad units/s.\n",
                     io::format_double(o.beta), io::format_double(o.tau), io::format_double(o.prior),
                     io::format_double(o.pad_speed));
  if (md) out += "\n";
  out += line(head);
  if (md) {
    std::string sep = "|";
    for (std::size_t i = 0; i < head.size(); ++i) sep += " " + std::string(width[i], '-') + " |";
    out += sep + "\n";
  }
  for (const auto& b : body) out += line(b);
  if (md) out += "\n";
  out += "overhead: path length / straight line - 1; legibility: Dragan's time-weighted P(true goal);\n"
         "deceived: share of time the true goal is the less probable one; LDP: last deceptive point\n"
         "(share of the path); error, confusion: the paper's metrics of the delayed belief b(t) as a pad;\n"
         "overspeed: segments where b(t) moved faster than v (counted as moving at v).\n";
  return out;
}

void run_trajectories(const TrajectoriesOptions& o) {
  const std::string format = infer_format(o.format, o.output);
  models::DeceptivenessSettings s;
  s.observer = {o.beta, o.tau, o.prior};
  models::validate(s.observer);
  s.pad_speed = o.pad_speed;
  const sim::Geometry g;
  std::vector<sim::TrajectoryMeasuresRow> rows;
  if (o.path.empty()) {
    rows = sim::strategy_measures(g, s);
  } else {
    const std::string t = io::to_lower(o.target);
    if (t != "left" && t != "right") throw UsageError(fmt::format("--target '{}': expected left or right", o.target));
    s.goals = sim::goals_of(g);
    const auto path = read_path_file(o.path);
    try {
      rows.push_back({"custom", "main", t,
                      models::deceptiveness(path, t == "right" ? models::GoalSide::right : models::GoalSide::left, s)});
    } catch (const InvalidData& e) {
      throw InvalidData(fmt::format("{}: {}", o.path, e.what()));
    }
  }
  io::AtomicOutput out(o.output);
  out.stream() << render_trajectories(rows, o, format);
  out.commit();
}

void add_trajectories_command(CLI::App& parent) {
  auto opts = std::make_shared<TrajectoriesOptions>();
  auto* cmd = parent.add_subcommand(
      "trajectories",
      "Deceptiveness of every strategy and version of the paper (both targets) under the goal-inference "
      "observer: legibility, time deceived, last deceptive point, cost overhead, and the error and "
      "confusion of the observer's belief as if it were a pad (docs/observer.md).");
  cmd->add_option("--beta", opts->beta, "observer rationality beta (1/m, >= 0)")->capture_default_str();
  cmd->add_option("--tau", opts->tau, "observer response delay tau (s, >= 0)")->capture_default_str();
  cmd->add_option("--prior", opts->prior, "prior P(right), in (0, 1)")->capture_default_str();
  cmd->add_option("--pad-speed", opts->pad_speed,
                  "pad speed v (pad units/s) normalising the belief's confusion")
      ->capture_default_str();
  cmd->add_option("--path", opts->path,
                  "measure this path instead (CSV with columns t, x, y in the default geometry: start "
                  "(0, 0), targets (-2, 4) and (2, 4))");
  cmd->add_option("--target", opts->target, "with --path: the true target, left or right")->capture_default_str();
  cmd->add_option("--format,-f", opts->format,
                  "text, markdown, csv or json (default: from the -o extension, else text)");
  cmd->add_option("--output,-o", opts->output, "output file (- = standard output)")->capture_default_str();
  cmd->callback([opts] { run_trajectories(*opts); });
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "simulate",
      "Simulate strategy selection (entropy analysis), a whole user study, or the observer's view of "
      "the strategies' trajectories.");
  cmd->require_subcommand(1);
  add_selection_command(*cmd);
  add_study_command(*cmd);
  add_trajectories_command(*cmd);
}

}  // namespace feint::cli

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
#include "feint/sim/simulation.hpp"
#include "feint/sim/study.hpp"

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
std::vector<double> parse_sweep(const std::string& text) {
  const auto parts = io::split_csv_line(text, ':');
  auto bad = [&](const std::string& why) {
    return UsageError(fmt::format("--sweep-lambda '{}': {} (expected FROM:TO:STEP, e.g. 0:1:0.05)",
                                  text, why));
  };
  if (parts.size() != 3) throw bad("three numbers are needed");
  std::array<double, 3> v{};
  for (std::size_t i = 0; i < 3; ++i) {
    const auto d = io::parse_double(parts[i]);
    if (!d) throw bad(fmt::format("'{}' is not a number", parts[i]));
    v[i] = *d;
  }
  const double from = v[0], to = v[1], step = v[2];
  if (!(from >= 0 && to <= 1 && from <= to)) throw bad("need 0 <= FROM <= TO <= 1");
  if (!(step > 0)) throw bad("STEP must be > 0");
  std::vector<double> out;
  for (long i = 0;; ++i) {
    const double x = from + static_cast<double>(i) * step;
    if (x > to + step * 1e-6) break;
    const double rounded = *io::parse_double(fmt::format("{:.12g}", x));
    out.push_back(std::min(rounded, 1.0));
    if (out.size() > 100000) throw bad("more than 100000 values");
  }
  return out;
}

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
struct Column {
  std::string name;
  bool text;  // a string (quoted in JSON) rather than a number
};

const std::vector<Column>& summary_columns() {
  static const std::vector<Column> cols = {
      {"algorithm", true},          {"lambda", false},
      {"states", false},            {"iterations", false},
      {"runs", false},              {"seed", false},
      {"entropy_mean", false},      {"entropy_sd", false},
      {"entropy_se", false},        {"entropy_min", false},
      {"entropy_max", false},       {"entropy_pooled", false},
      {"repetition_mean", false},   {"repetition_sd", false},
      {"conditional_entropy_mean", false}, {"conditional_entropy_sd", false},
      {"guess_accuracy_mean", false},      {"guess_accuracy_sd", false},
      {"batch", false},             {"batches", false},
      {"batch_entropy_mean_q025", false},  {"batch_entropy_mean_q975", false},
      {"batch_entropy_pooled_q025", false}, {"batch_entropy_pooled_q975", false},
  };
  return cols;
}

double lambda_of(const sim::SimulationSettings& s) {
  return s.run.algorithm == Algorithm::adaptive ? s.run.lambda : std::nan("");
}

/// Cells of one summary row, in summary_columns() order; NaN (not computable) -> "".
std::vector<std::string> summary_cells(const sim::SimulationSummary& r) {
  const auto& s = r.settings;
  auto d = [](double x) { return io::format_double(x); };
  return {std::string(sim::to_string(s.run.algorithm)),
          d(lambda_of(s)),
          std::to_string(s.run.states),
          std::to_string(s.run.iterations),
          std::to_string(s.runs),
          std::to_string(s.seed),
          d(r.entropy.mean), d(r.entropy.sd), d(r.entropy.se()), d(r.entropy.min), d(r.entropy.max),
          d(r.entropy_pooled),
          d(r.repetition.mean), d(r.repetition.sd),
          d(r.conditional_entropy.mean), d(r.conditional_entropy.sd),
          d(r.guess_accuracy.mean), d(r.guess_accuracy.sd),
          std::to_string(s.batch), std::to_string(r.batches),
          d(r.batch_entropy_mean_q025), d(r.batch_entropy_mean_q975),
          d(r.batch_entropy_pooled_q025), d(r.batch_entropy_pooled_q975)};
}

std::string render_csv(const std::vector<sim::SimulationSummary>& rows) {
  std::string out;
  const auto& cols = summary_columns();
  for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + cols[i].name;
  out += '\n';
  for (const auto& r : rows) {
    const auto cells = summary_cells(r);
    for (std::size_t i = 0; i < cells.size(); ++i) out += (i ? "," : "") + io::csv_escape(cells[i]);
    out += '\n';
  }
  return out;
}

std::string render_json(const std::vector<sim::SimulationSummary>& rows) {
  std::string out = "[\n";
  const auto& cols = summary_columns();
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto cells = summary_cells(rows[r]);
    out += "  {";
    for (std::size_t i = 0; i < cells.size(); ++i) {
      out += (i ? ", " : "") + io::json_quote(cols[i].name) + ": ";
      if (cols[i].text) {
        out += io::json_quote(cells[i]);
      } else {
        out += cells[i].empty() ? "null" : cells[i];
      }
    }
    out += r + 1 < rows.size() ? "},\n" : "}\n";
  }
  return out + "]\n";
}

/// Human-readable table (text: aligned columns; markdown: a pipe table). Numbers to 4 decimals.
std::string render_table(const std::vector<sim::SimulationSummary>& rows, bool markdown) {
  const std::vector<std::string> head = {"algorithm", "lambda", "H mean", "H sd", "H pooled",
                                         "repetition", "cond. H", "guess acc.",
                                         "mean H of B runs: 2.5%", "97.5%"};
  std::vector<std::vector<std::string>> body;
  auto f4 = [](double x) { return std::isnan(x) ? std::string("-") : fmt::format("{:.4f}", x); };
  for (const auto& r : rows) {
    const double lam = lambda_of(r.settings);
    body.push_back({std::string(sim::to_string(r.settings.run.algorithm)),
                    std::isnan(lam) ? "-" : io::format_double(lam), f4(r.entropy.mean),
                    f4(r.entropy.sd), f4(r.entropy_pooled), f4(r.repetition.mean),
                    f4(r.conditional_entropy.mean), f4(r.guess_accuracy.mean),
                    f4(r.batch_entropy_mean_q025), f4(r.batch_entropy_mean_q975)});
  }
  std::vector<std::size_t> width(head.size());
  for (std::size_t i = 0; i < head.size(); ++i) {
    width[i] = head[i].size();
    for (const auto& b : body) width[i] = std::max(width[i], b[i].size());
  }
  std::string out;
  const auto& s = rows.front().settings;
  const std::string intro = fmt::format(
      "Selection simulation: {} runs of {} iterations, {} states, seed {}; B = {} runs per batch.",
      s.runs, s.run.iterations, s.run.states, s.seed, s.batch);
  out += markdown ? intro + "\n\n" : intro + "\n";
  auto line = [&](const std::vector<std::string>& cells) {
    std::string l = markdown ? "|" : "";
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const bool left = i == 0;
      const std::string cell = left ? fmt::format("{:<{}}", cells[i], width[i])
                                    : fmt::format("{:>{}}", cells[i], width[i]);
      l += markdown ? " " + cell + " |" : (i ? "  " : "") + cell;
    }
    return l + "\n";
  };
  out += line(head);
  if (markdown) {
    std::string sep = "|";
    for (std::size_t i = 0; i < head.size(); ++i) {
      sep += (i == 0 ? " :" : " ") + std::string(width[i] - 1, '-') + (i == 0 ? " |" : ": |");
    }
    out += sep + "\n";
  }
  for (const auto& b : body) out += line(b);
  out += markdown ? "\n" : "";
  out += "H: per-run entropy in bits (max log2 K); H pooled: entropy of the counts pooled over all runs;\n"
         "repetition: share of consecutive repeats; cond. H: H(S_k given S_k-1); guess acc.:\n"
         "accuracy of the least-seen-state guesser; last columns: 2.5/97.5 % quantiles of the mean\n"
         "entropy of B consecutive runs (how far a study of B runs scatters).\n";
  return out;
}

void write_sequences(const std::string& path, const std::vector<sim::SimulationSettings>& settings) {
  io::AtomicOutput out(path);
  auto& os = out.stream();
  os << "algorithm,lambda,run,iteration,strategy,variant,target\n";
  for (const auto& s : settings) {
    const std::string alg(sim::to_string(s.run.algorithm));
    const std::string lam = io::format_double(lambda_of(s));
    sim::for_each_run(s, [&](std::uint64_t run, const std::vector<sim::Iteration>& its) {
      for (std::size_t i = 0; i < its.size(); ++i) {
        os << alg << ',' << lam << ',' << run + 1 << ',' << i + 1 << ','
           << sim::to_string(its[i].strategy) << ',' << sim::to_string(its[i].variant) << ','
           << sim::to_string(its[i].target) << '\n';
      }
    });
  }
  out.commit();
}

void write_occurrence(const std::string& path, const std::vector<sim::SimulationSummary>& rows) {
  io::AtomicOutput out(path);
  auto& os = out.stream();
  os << "algorithm,lambda,iteration,strategy,probability,cumulative_share,runs\n";
  for (const auto& r : rows) {
    const auto& s = r.settings;
    const int k = s.run.states;
    const std::string alg(sim::to_string(s.run.algorithm));
    const std::string lam = io::format_double(lambda_of(s));
    const double runs = static_cast<double>(s.runs);
    std::vector<std::uint64_t> cum(static_cast<std::size_t>(k), 0);
    for (int i = 0; i < s.run.iterations; ++i) {
      for (int st = 0; st < k; ++st) {
        const std::uint64_t c = r.occurrence[static_cast<std::size_t>(i * k + st)];
        cum[static_cast<std::size_t>(st)] += c;
        // probability: share of runs with this state at this iteration; cumulative_share: mean over
        // runs of the share of this state in iterations 1..i (the running frequency of Fig. 5/7).
        os << alg << ',' << lam << ',' << i + 1 << ','
           << sim::to_string(static_cast<sim::Strategy>(st)) << ','
           << io::format_double(static_cast<double>(c) / runs) << ','
           << io::format_double(static_cast<double>(cum[static_cast<std::size_t>(st)]) /
                                (runs * (i + 1)))
           << ',' << s.runs << '\n';
      }
    }
  }
  out.commit();
}

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

  std::vector<sim::SimulationSettings> all;
  auto with = [&](Algorithm a, double lambda) {
    sim::SimulationSettings s = base;
    s.run.algorithm = a;
    s.run.lambda = lambda;
    all.push_back(s);
  };
  if (o.compare) {
    for (auto a : {Algorithm::random, Algorithm::fixed_block, Algorithm::fixed_balanced}) {
      with(a, base.run.lambda);
    }
  }
  if (!o.sweep.empty()) {
    for (double l : parse_sweep(o.sweep)) with(Algorithm::adaptive, l);
  } else if (o.compare) {
    with(Algorithm::adaptive, base.run.lambda);
  } else {
    all.push_back(base);
  }

  std::vector<sim::SimulationSummary> rows;
  rows.reserve(all.size());
  for (const auto& s : all) rows.push_back(sim::simulate_selection(s));

  if (!o.sequences.empty()) write_sequences(o.sequences, all);
  if (!o.occurrence.empty()) write_occurrence(o.occurrence, rows);

  std::string text;
  if (format == "csv") text = render_csv(rows);
  else if (format == "json") text = render_json(rows);
  else text = render_table(rows, format == "markdown");
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
  fmt::print("feint simulate study: {} participants ({} per condition: adaptive, random), {} iterations, "
             "seed {}\n  logs: {}/logs/P*.csv.gz\n  questionnaire: {}/questionnaire.csv\n",
             people.size(), o.participants, o.iterations, o.seed, o.out, o.out);
  for (auto cond : sim::kStudyConditions) {
    double first = 0, last = 0;
    int nf = 0, nl = 0;
    for (const auto& p : people) {
      if (p.condition != cond) continue;
      for (const auto& tr : p.trials) {
        if (tr.iteration <= 5) { first += tr.error; ++nf; }
        if (tr.iteration > o.iterations - 5) { last += tr.error; ++nl; }
      }
    }
    fmt::print("  {:<8} mean error: iterations 1-5 {:.3f}, last 5 {:.3f}\n", sim::to_string(cond),
               nf ? first / nf : std::nan(""), nl ? last / nl : std::nan(""));
  }
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

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "simulate", "Simulate strategy selection (entropy analysis) or a whole user study.");
  cmd->require_subcommand(1);
  add_selection_command(*cmd);
  add_study_command(*cmd);
}

}  // namespace feint::cli

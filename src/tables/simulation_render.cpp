// Renderings of the selection simulation (see feint/tables/simulation_render.hpp); moved out of
// the command line so that the library can render what it simulates.
#include "feint/tables/simulation_render.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/io/output.hpp"

namespace feint::tables {

namespace {

using sim::Algorithm;

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

std::string render_csv_(const std::vector<sim::SimulationSummary>& rows) {
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

std::string render_json_(const std::vector<sim::SimulationSummary>& rows) {
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
std::string render_table_(const std::vector<sim::SimulationSummary>& rows, bool markdown) {
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

}  // namespace

void write_selection_sequences(const std::string& path, const std::vector<sim::SimulationSettings>& settings) {
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

void write_selection_occurrence(const std::string& path, const std::vector<sim::SimulationSummary>& rows) {
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


std::string render_selection(const std::vector<sim::SimulationSummary>& rows,
                             const std::string& format) {
  if (format == "csv") return render_csv_(rows);
  if (format == "json") return render_json_(rows);
  return render_table_(rows, format == "markdown");
}

std::string study_summary_text(const std::vector<sim::ParticipantRecord>& people,
                               const sim::StudySettings& s, const std::string& dir) {
  std::string names;
  for (std::size_t c = 0; c < s.conditions.size(); ++c)
    names += (names.empty() ? "" : ", ") + sim::condition_name(s, c);
  std::string o =
      s.within ? fmt::format("feint simulate study: {} participants, each in {} conditions ({}; "
                             "counterbalanced blocks of {} iterations), seed {}\n  logs: {}/logs/P*.csv.gz\n  "
                             "questionnaire: none (not simulated for within designs)\n",
                             s.participants, s.conditions.size() == 2 ? "both" : "all", names, s.iterations, s.seed, dir)
               : fmt::format("feint simulate study: {} participants ({} per condition: {}), {} "
                             "iterations, seed {}\n  logs: {}/logs/P*.csv.gz\n  questionnaire: {}/questionnaire.csv\n",
                             people.size(), s.participants, names, s.iterations, s.seed, dir, dir);
  std::size_t width = 8;
  for (std::size_t c = 0; c < s.conditions.size(); ++c) width = std::max(width, sim::condition_name(s, c).size());
  for (std::size_t c = 0; c < s.conditions.size(); ++c) {
    const std::string cond = sim::condition_name(s, c);
    double first = 0, last = 0;
    int nf = 0, nl = 0;
    for (const auto& p : people) {
      if (p.condition_name != cond) continue;
      for (const auto& tr : p.trials) {
        if (tr.iteration <= 5) {
          first += tr.error;
          ++nf;
        }
        if (tr.iteration > s.iterations - 5) {
          last += tr.error;
          ++nl;
        }
      }
    }
    o += fmt::format("  {:<{}} mean error: iterations 1-5 {:.3f}, last 5 {:.3f}\n",
                     cond, width, nf ? first / nf : std::nan(""),
                     nl ? last / nl : std::nan(""));
  }
  return o;
}

std::string output_format(const std::string& format, const std::string& output) {
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

}  // namespace feint::tables

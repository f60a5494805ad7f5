// feint power t-test | simulate: analytic t-test power and sample size, and simulation power of
// the 2 x k design (see docs/anova-power.md).
#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/io/scores.hpp"
#include "feint/models/power.hpp"
#include "feint/models/power_sim.hpp"
#include "feint/report/anova_render.hpp"
#include "feint/report/power_render.hpp"
#include "report_options.hpp"

namespace feint::cli {

namespace {

struct TTestArgs {
  std::string type = "two-sample";
  std::optional<double> n, delta, d, power, sd, sd2;
  double ratio = 1.0;
  bool welch = false;
  double alpha = 0.05;
  int tests = 1;
  std::string alternative = "two.sided";
  ReportOptions report;
};

void run_t_test(const TTestArgs& a) {
  const ResolvedReportOptions r = resolve_report_options(a.report);
  models::TTestPowerSpec s;
  s.design = models::parse_t_test_design(a.type);
  if (a.d && (a.delta || a.sd)) {
    throw UsageError("--d is Cohen's d (delta with sd = 1): give --d, or --delta with --sd");
  }
  s.n = a.n;
  s.delta = a.d ? a.d : a.delta;
  s.power = a.power;
  s.sd = a.sd.value_or(1.0);
  s.sd2 = a.sd2;
  s.ratio = a.ratio;
  s.welch = a.welch;
  s.alpha = a.alpha;
  s.tests = a.tests;
  try {
    s.alternative = stats::parse_alternative(a.alternative);
  } catch (const UsageError&) {
    throw UsageError(
        fmt::format("--alternative '{}': expected two.sided, greater or less", a.alternative));
  }
  const std::string solved = report::solved_for(s);
  const models::TTestPowerResult result = models::solve_t_test_power(s);
  write_report(r.output, report::render_t_test_power(result, solved, r.format, r.presentation));
}

struct SimulateArgs {
  std::string pilot;
  std::string metric = "error";
  std::string means_a, means_b;
  std::optional<double> sd_participant, sd_residual;
  std::optional<std::size_t> n_per_group;
  std::size_t studies = 10000;
  std::uint64_t seed = 1;
  unsigned threads = 2;
  double alpha = 0.05;
  std::string correction = "GG";
  std::string p_adjust = "holm";
  bool null = false;
  io::ScoresOptions columns;  // --participant-column, --iteration-column, --condition-column
  ReportOptions report;
};

std::vector<double> parse_means(const std::string& text, const char* option) {
  std::vector<double> out;
  for (const auto& f : io::split_csv_line(text)) {
    const auto v = io::parse_double(io::trim(f));
    if (!v)
      throw UsageError(fmt::format("{} '{}': expected comma-separated numbers, one per iteration",
                                   option, text));
    out.push_back(*v);
  }
  return out;
}

void run_simulate(const SimulateArgs& a) {
  const ResolvedReportOptions r = resolve_report_options(a.report);
  models::SimulationDesign d;
  if (!a.pilot.empty()) {
    if (!a.means_a.empty() || !a.means_b.empty()) {
      throw UsageError("--means-a/--means-b replace a pilot file: give one or the other");
    }
    io::ScoresOptions so = a.columns;
    so.metrics = {a.metric};
    const io::ScoresTable scores = io::load_scores(a.pilot, so);
    const auto obs = report::observations(scores, a.metric);
    d = models::design_from_pilot(models::make_wide_design(obs, a.metric, scores.path));
  } else {
    if (a.means_a.empty() || a.means_b.empty() || !a.sd_residual) {
      throw UsageError(
          "without a pilot file give --means-a, --means-b (one mean per iteration) and "
          "--sd-residual (and optionally --sd-participant, --n-per-group)");
    }
    d.means_a = parse_means(a.means_a, "--means-a");
    d.means_b = parse_means(a.means_b, "--means-b");
    d.n_a = d.n_b = 30;
  }
  if (a.sd_participant) d.sd_participant = *a.sd_participant;
  if (a.sd_residual) d.sd_residual = *a.sd_residual;
  if (a.n_per_group) d.n_a = d.n_b = *a.n_per_group;
  if (a.null) {
    // The null: both conditions follow the same (average) profile.
    for (std::size_t j = 0; j < d.means_a.size() && j < d.means_b.size(); ++j) {
      d.means_a[j] = d.means_b[j] = (d.means_a[j] + d.means_b[j]) / 2;
    }
  }
  models::SimulationOptions o;
  o.studies = a.studies;
  o.seed = a.seed;
  o.threads = a.threads;
  if (!(a.alpha > 0 && a.alpha < 1))
    throw UsageError(fmt::format("--alpha {}: expected a number in (0, 1)", a.alpha));
  o.alpha = a.alpha;
  o.correction = models::parse_sphericity_correction(a.correction);
  try {
    o.p_adjust = stats::parse_p_adjust(a.p_adjust);
  } catch (const UsageError&) {
    throw UsageError(
        fmt::format("--p-adjust '{}': expected none, bonferroni, holm, hochberg, hommel, BH or BY",
                    a.p_adjust));
  }
  const auto result = models::simulate_power(d, o);
  write_report(r.output,
               report::render_simulation_power(result, a.pilot, r.format, r.presentation));
}

}  // namespace

void add_power_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "power",
      "Power and sample size: `power t-test` (analytic, as R's power.t.test / pwr) and `power "
      "simulate` (the 2 x k design: ANOVA interaction and per-iteration contrasts, by simulation)");
  cmd->require_subcommand(1);

  auto t = std::make_shared<TTestArgs>();
  auto* tt = cmd->add_subcommand(
      "t-test",
      "Power, sample size or detectable difference of a one-sample, two-sample (Student or Welch) "
      "or paired t-test: give two of --n, --delta/--d, --power and the third is solved for");
  tt->add_option("--type", t->type, "one-sample, two-sample or paired")->capture_default_str();
  tt->add_option("--n", t->n, "Participants per group (two-sample: group A; pairs when paired)");
  tt->add_option("--delta", t->delta, "True difference of means, in metric units (with --sd)");
  tt->add_option("--d", t->d, "Cohen's d (delta in sd units; sd = 1)");
  tt->add_option("--power", t->power, "Power wanted, e.g. 0.8");
  tt->add_option("--sd", t->sd,
                 "Standard deviation (two-sample: common, or group A with --welch; "
                 "paired: of the differences); default 1");
  tt->add_option("--sd2", t->sd2, "Welch: standard deviation of group B (default --sd)");
  tt->add_option("--ratio", t->ratio, "Two-sample: n2 = ratio x n1 (unequal groups)")
      ->capture_default_str();
  tt->add_flag("--welch", t->welch, "Two-sample: Welch's test (unequal variances)");
  tt->add_option("--alpha", t->alpha, "Family-wise significance level")->capture_default_str();
  tt->add_option("--tests", t->tests,
                 "Number of tests sharing alpha (Bonferroni: alpha / m per test), e.g. 20 for the "
                 "paper's per-iteration tests")
      ->capture_default_str();
  tt->add_option("--alternative", t->alternative,
                 "two.sided, greater or less (one-sided in the direction of the effect)")
      ->capture_default_str();
  add_report_options(*tt, t->report, {.tests = false, .presentation = true});
  tt->callback([t] { run_t_test(*t); });

  auto s = std::make_shared<SimulateArgs>();
  auto* sim = cmd->add_subcommand(
      "simulate",
      "Simulation power of the 2-condition x k-iteration design: the condition x iteration "
      "interaction of the mixed ANOVA and the per-iteration Welch contrasts, with means and "
      "variance components from a pilot scores file or given");
  sim->add_option("PILOT", s->pilot, "Pilot scores CSV (two conditions); optional");
  sim->add_option("--metric", s->metric, "Metric of the pilot")->capture_default_str();
  sim->add_option("--means-a", s->means_a,
                  "Without a pilot: means of condition A per iteration, comma-separated");
  sim->add_option("--means-b", s->means_b, "Without a pilot: means of condition B per iteration");
  sim->add_option("--sd-participant", s->sd_participant,
                  "SD of the participant intercepts (overrides the pilot)");
  sim->add_option("--sd-residual", s->sd_residual, "Residual SD (overrides the pilot)");
  sim->add_option("--n-per-group", s->n_per_group,
                  "Participants per condition (default: the pilot's, or 30)");
  sim->add_option("--studies", s->studies, "Simulated studies")->capture_default_str();
  sim->add_option("--seed", s->seed, "Random seed (same seed, same result)")->capture_default_str();
  sim->add_option("--threads", s->threads, "Threads")->capture_default_str();
  sim->add_option("--alpha", s->alpha, "Significance level")->capture_default_str();
  sim->add_option("--correction", s->correction,
                  "Sphericity correction of the ANOVA: GG, HF or none")
      ->capture_default_str();
  sim->add_option("--p-adjust", s->p_adjust,
                  "Adjustment of the per-iteration p-values (R's p.adjust)")
      ->capture_default_str();
  sim->add_flag("--null", s->null, "Simulate the null: both conditions get the average profile");
  add_scores_column_options(*sim, s->columns, "Pilot: ");
  add_report_options(*sim, s->report, {.tests = false, .presentation = true});
  sim->callback([s] { run_simulate(*s); });

  add_power_observer_command(*cmd);
}

}  // namespace feint::cli

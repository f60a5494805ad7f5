// feint power t-test | simulate: analytic t-test power and sample size, and simulation power of
// the 2 x k design (see docs/anova-power.md).
#include <memory>
#include <string>

#include "commands.hpp"
#include "feint/commands/power_reports.hpp"
#include "options.hpp"

namespace feint::cli {

void add_power_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "power",
      "Power and sample size: `power t-test` (analytic, as R's power.t.test / pwr) and `power "
      "simulate` (the 2 x k design: ANOVA interaction and per-iteration contrasts, by simulation)");
  cmd->require_subcommand(1);

  auto t = std::make_shared<ReportCommand<commands::TTestPowerOptions>>();
  auto* tt = cmd->add_subcommand(
      "t-test",
      "Power, sample size or detectable difference of a one-sample, two-sample (Student or Welch) "
      "or paired t-test: give two of --n, --delta/--d, --power and the third is solved for");
  tt->option_defaults()->always_capture_default();  // each option shows its default
  tt->add_option("--type", t->o.type, "one-sample, two-sample or paired");
  tt->add_option("--n", t->o.n, "Participants per group (two-sample: group A; pairs when paired)");
  tt->add_option("--delta", t->o.delta, "True difference of means, in metric units (with --sd)");
  tt->add_option("--d", t->o.d, "Cohen's d (delta in sd units; sd = 1)");
  tt->add_option("--power", t->o.power, "Power wanted, e.g. 0.8");
  tt->add_option("--sd", t->o.sd,
                 "Standard deviation (two-sample: common, or group A with --welch; "
                 "paired: of the differences); default 1");
  tt->add_option("--sd2", t->o.sd2, "Welch: standard deviation of group B (default --sd)");
  tt->add_option("--ratio", t->o.ratio, "Two-sample: n2 = ratio x n1 (unequal groups)");
  tt->add_flag("--welch", t->o.welch, "Two-sample: Welch's test (unequal variances)");
  tt->add_option("--alpha", t->o.alpha, "Family-wise significance level");
  tt->add_option("--tests", t->o.tests,
                 "Number of tests sharing alpha (Bonferroni: alpha / m per test), e.g. 20 for the "
                 "paper's per-iteration tests");
  tt->add_option("--alternative", t->o.alternative,
                 "two.sided, greater or less (one-sided in the direction of the effect)");
  add_report_options(*tt, t->report, {.tests = false, .presentation = true});
  tt->callback([t] { run_report(*t, commands::t_test_power_report); });

  auto s = std::make_shared<ReportCommand<commands::PowerSimulationOptions>>();
  auto* sim = cmd->add_subcommand(
      "simulate",
      "Simulation power of the 2-condition x k-iteration design: the condition x iteration "
      "interaction of the mixed ANOVA and the per-iteration Welch contrasts, with means and "
      "variance components from a pilot scores file or given");
  sim->option_defaults()->always_capture_default();  // each option shows its default
  sim->add_option("PILOT", s->o.pilot, "Pilot scores CSV (two conditions); optional");
  sim->add_option("--metric", s->o.metric, "Metric of the pilot");
  sim->add_option("--means-a", s->o.means_a,
                  "Without a pilot: means of condition A per iteration, comma-separated");
  sim->add_option("--means-b", s->o.means_b, "Without a pilot: means of condition B per iteration");
  sim->add_option("--sd-participant", s->o.sd_participant,
                  "SD of the participant intercepts (overrides the pilot)");
  sim->add_option("--sd-residual", s->o.sd_residual, "Residual SD (overrides the pilot)");
  sim->add_option("--n-per-group", s->o.n_per_group,
                  "Participants per condition (default: the pilot's, or 30)");
  sim->add_option("--studies", s->o.studies, "Simulated studies");
  sim->add_option("--seed", s->o.seed, "Random seed (same seed, same result)");
  sim->add_option("--threads", s->o.threads, "Threads");
  sim->add_option("--alpha", s->o.alpha, "Significance level");
  sim->add_option("--correction", s->o.correction,
                  "Sphericity correction of the ANOVA: GG, HF or none");
  sim->add_option("--p-adjust", s->o.p_adjust,
                  "Adjustment of the per-iteration p-values (R's p.adjust)");
  sim->add_flag("--null", s->o.null, "Simulate the null: both conditions get the average profile");
  add_scores_column_options(*sim, s->o.columns, "Pilot: ");
  add_report_options(*sim, s->report, {.tests = false, .presentation = true});
  sim->callback([s] { run_report(*s, commands::power_simulation_report); });

  add_power_observer_command(*cmd);
}

}  // namespace feint::cli

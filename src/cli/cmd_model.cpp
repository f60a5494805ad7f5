// feint model SCORES.csv: the linear mixed model of each metric (see docs/mixed-model.md).
#include <memory>

#include "commands.hpp"
#include "feint/commands/table_commands.hpp"
#include "options.hpp"

namespace feint::cli {

void add_model_command(CLI::App& app) {
  auto args = std::make_shared<ReportCommand<commands::ModelCommandOptions>>();
  auto* cmd = app.add_subcommand(
      "model",
      "Linear mixed model per metric: metric ~ condition * iteration + (1 | participant) by REML, "
      "type-III F tests with Satterthwaite df (as lmerTest), variance components, and contrasts "
      "of two conditions per iteration (as emmeans).");
  cmd->add_option("SCORES", args->o.input,
                  "Scores CSV: participant, iteration, condition, numeric metric columns "
                  "(- = standard input)")
      ->required();
  cmd->add_option("--metric", args->o.metrics,
                  "Metric column (repeatable; default error and confusion)")
      ->allow_extra_args(false);
  cmd->add_option("--compare", args->o.compare,
                  "Contrast A - B of these two conditions, e.g. adaptive,random (default: the "
                  "first two conditions in sorted order)");
  cmd->add_flag("--trend", args->o.trend, "Iteration as a linear trend instead of a factor");
  cmd->add_flag("--random-slope", args->o.random_slope,
                "With --trend: a random slope per participant, (1 + iteration | participant)");
  cmd->add_flag("--random-condition-slope", args->o.random_condition_slope,
                "Conditions within participants: (1 + condition | participant)");
  cmd->add_option("--random", args->o.random,
                  "Random intercepts of the strategy beside (1 | participant) (repeatable): strategy "
                  "(crossed) or participant:strategy (nested); needs the strategy column");
  cmd->add_option("--design", args->o.design, analysis::kDesignHelp);
  cmd->add_flag("--exposure", args->o.exposure,
                "Fit metric ~ strategy * exposure + (1 | participant), exposure = earlier trials "
                "of the same strategy; report the slope per strategy");
  cmd->add_option("--ddf", args->o.ddf,
                  "Denominator df of the F tests and contrasts: satterthwaite (lmerTest's default) "
                  "or kenward-roger (pbkrtest: adjusted covariance and scaled F)")
      ->capture_default_str();
  cmd->add_flag("--emmeans", args->o.emmeans,
                "Estimated marginal means with intervals: condition x iteration cells, conditions, "
                "iterations (as emmeans)");
  cmd->add_option("--contrasts", args->o.contrasts,
                  "emmeans contrasts (repeatable): pairwise (all pairs of conditions, of "
                  "iterations), simple (condition at each iteration, iteration within each "
                  "condition), poly (polynomial trends over iterations, overall and per condition)")
      ->allow_extra_args(false);
  cmd->add_option("--adjust", args->o.adjust,
                  "Adjustment of the --contrasts within each family: tukey, holm (Bonferroni "
                  "intervals) or none (default: tukey for pairwise/simple, none for poly)");
  add_scores_column_options(*cmd, args->o.columns);
  cmd->add_option("--strategy-column", args->o.strategy_column,
                  "Name of the strategy column (--exposure, --random)")
      ->capture_default_str();
  add_report_options(*cmd, args->report, {.tests = true, .presentation = true});
  cmd->callback([args] { run_report(*args, commands::model_report); });
}

}  // namespace feint::cli

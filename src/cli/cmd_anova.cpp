// feint anova SCORES.csv: the mixed ANOVA (condition between x iteration within) of each metric,
// as afex::aov_ez (see docs/anova-power.md).
#include <memory>

#include "commands.hpp"
#include "feint/commands/table_commands.hpp"
#include "options.hpp"

namespace feint::cli {

void add_anova_command(CLI::App& app) {
  auto args = std::make_shared<ReportCommand<commands::AnovaCommandOptions>>();
  auto* cmd = app.add_subcommand(
      "anova",
      "Mixed ANOVA per metric: condition (between) x iteration (within), as afex::aov_ez - "
      "type-III "
      "F tests, Mauchly's test, Greenhouse-Geisser/Huynh-Feldt corrections, generalized eta "
      "squared. One condition: one-way repeated-measures ANOVA.");
  cmd->add_option("SCORES", args->o.input,
                  "Scores CSV: participant, iteration, optional condition, numeric metric columns "
                  "(- = standard input)")
      ->required();
  cmd->add_option("--metric", args->o.metrics,
                  "Metric column to analyse (repeatable; default error and confusion)")
      ->allow_extra_args(false);
  cmd->add_option("--correction", args->o.correction,
                  "Sphericity correction of the within-participant df: GG (default, as afex), HF "
                  "or none")
      ->capture_default_str();
  cmd->add_flag("--apa", args->o.apa,
                "Add an APA string per effect, e.g. 'F(1.93, 112.1) = 4.31, p = .017, ηG² = .031'");
  cmd->add_flag("--drop-empty-conditions", args->o.drop_empty_conditions,
                "When every participant of a condition has a missing value, analyse the other "
                "condition(s) (one left: the one-way repeated-measures ANOVA) instead of stopping");
  cmd->add_flag("--emmeans", args->o.emmeans,
                "Estimated marginal means (cells, conditions, iterations) as emmeans on the afex "
                "object (multivariate model, df = N - a)");
  cmd->add_option("--contrasts", args->o.contrasts,
                  "emmeans contrasts (repeatable): pairwise, simple (condition at each iteration, "
                  "iteration within each condition) or poly (polynomial trends over iterations)")
      ->allow_extra_args(false);
  cmd->add_option("--adjust", args->o.adjust,
                  "Adjustment of the --contrasts within each family: tukey, holm or none "
                  "(default: tukey for pairwise/simple, none for poly)");
  cmd->add_option("--design", args->o.design, analysis::kDesignHelp);
  add_scores_column_options(*cmd, args->o.columns);
  add_report_options(*cmd, args->report, {.tests = false, .presentation = true});
  cmd->callback([args] { run_report(*args, commands::anova_report); });
}

}  // namespace feint::cli

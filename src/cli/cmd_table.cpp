// feint table SCORES.csv: the paper's Table 1 (see docs/tables.md).
#include <memory>

#include "commands.hpp"
#include "feint/commands/table_commands.hpp"
#include "options.hpp"

namespace feint::cli {

void add_table_command(CLI::App& app) {
  auto args = std::make_shared<ReportCommand<commands::TableCommandOptions>>();
  auto* cmd = app.add_subcommand(
      "table",
      "The paper's Table 1: per iteration and metric, t-tests of the participants' scores against "
      "reference means (default) or between two conditions (--compare A,B).");
  cmd->add_option("SCORES", args->o.input,
                  "Scores CSV: participant, iteration, optional condition, numeric metric columns "
                  "(- = standard input)")
      ->required();
  cmd->add_option("--metric", args->o.metrics,
                  "Metric column and reference mean, NAME=REF (repeatable; default error=0.5 "
                  "confusion=0.95@raw)")
      ->allow_extra_args(false);  // one value per --metric, so SCORES may follow it
  cmd->add_option(
      "--condition", args->o.condition,
      "One-sample mode: only this condition (default: every condition, one block each)");
  cmd->add_option("--compare", args->o.compare,
                  "Two-sample mode: compare condition A with B, e.g. adaptive,random");
  cmd->add_flag("--var-equal", args->o.var_equal,
                "Two-sample: Student's t (pooled variance) instead of Welch");
  cmd->add_flag("--paired", args->o.paired,
                "Two-sample: paired t-test, pairs matched by participant");
  cmd->add_option("--design", args->o.design, analysis::kDesignHelp);
  auto* equivalence = cmd->add_option(
      "--equivalence", args->o.equivalence,
      "Equivalence margin delta (> 0, metric units): '≈' is earned by TOST within +-delta");
  add_scores_column_options(*cmd, args->o.columns);
  add_report_options(*cmd, args->report, {.tests = true, .presentation = true, .bayes = true});
  cmd->callback([args, equivalence] {
    args->o.equivalence_given = equivalence->count() > 0;  // TOST only when asked for
    run_report(*args, commands::table1_report);
  });
}

}  // namespace feint::cli

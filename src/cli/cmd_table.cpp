// feint table SCORES.csv: the paper's Table 1 (see docs/tables.md).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/file_identity.hpp"
#include "feint/io/number.hpp"
#include "feint/io/scores.hpp"
#include "feint/report/table1.hpp"
#include "report_options.hpp"

namespace feint::cli {

namespace {

struct TableArgs {
  std::string input;
  std::vector<std::string> metrics;
  std::string condition;
  std::string compare;
  bool var_equal = false;
  bool paired = false;
  double equivalence = 0.0;
  CLI::Option* equivalence_option = nullptr;
  io::ScoresOptions columns;  // --participant-column, --iteration-column, --condition-column
  ReportOptions report;
};

void run_table(const TableArgs& a) {
  const ResolvedReportOptions r = resolve_report_options(a.report);
  io::refuse_overwriting_inputs({a.input}, {r.output});
  report::Table1Options o;
  o.metrics = parse_metric_specs(a.metrics);
  o.condition = a.condition;
  if (!a.compare.empty()) {
    o.compare = parse_compare(a.compare);
    if (!a.condition.empty()) throw UsageError("--condition and --compare exclude each other");
  }
  o.var_equal = a.var_equal;
  o.paired = a.paired;
  if (a.equivalence_option != nullptr && a.equivalence_option->count() > 0) {
    o.equivalence = a.equivalence;
  }
  o.alpha = r.alpha;
  o.test = r.test;
  o.p_adjust = r.p_adjust;
  o.apa = r.apa;

  io::ScoresOptions so = a.columns;
  so.metrics.clear();
  for (const auto& m : o.metrics) so.metrics.push_back(m.column);
  const io::ScoresTable scores = io::load_scores(a.input, so);
  const report::Table1 table = report::build_table1(scores, o);
  // The scores' sidecar (read for the note) is an input too.
  io::refuse_overwriting_inputs({table.provenance.sidecar_path}, {r.output});
  write_report(r.output, report::render_table1(table, r.format, r.presentation));
}

}  // namespace

void add_table_command(CLI::App& app) {
  auto args = std::make_shared<TableArgs>();
  auto* cmd = app.add_subcommand(
      "table",
      "The paper's Table 1: per iteration and metric, t-tests of the participants' scores against "
      "reference means (default) or between two conditions (--compare A,B).");
  cmd->add_option("SCORES", args->input,
                  "Scores CSV: participant, iteration, optional condition, numeric metric columns "
                  "(- = standard input)")
      ->required();
  cmd->add_option("--metric", args->metrics,
                  "Metric column and reference mean, NAME=REF (repeatable; default error=0.5 "
                  "confusion=0.95)")
      ->allow_extra_args(false);  // one value per --metric, so SCORES may follow it
  cmd->add_option("--condition", args->condition,
                  "One-sample mode: only this condition (default: every condition, one block each)");
  cmd->add_option("--compare", args->compare,
                  "Two-sample mode: compare condition A with B, e.g. adaptive,random");
  cmd->add_flag("--var-equal", args->var_equal, "Two-sample: Student's t (pooled variance) instead of Welch");
  cmd->add_flag("--paired", args->paired,
                "Two-sample: paired t-test, pairs matched by participant");
  args->equivalence_option = cmd->add_option(
      "--equivalence", args->equivalence,
      "Equivalence margin delta (> 0, metric units): '≈' is earned by TOST within +-delta");
  add_scores_column_options(*cmd, args->columns);
  add_report_options(*cmd, args->report, {.tests = true, .presentation = true});
  cmd->callback([args] { run_table(*args); });
}

}  // namespace feint::cli

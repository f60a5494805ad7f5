// `feint likert FILE`: Likert questionnaire analyses (docs/likert.md). Thin: the options go to
// commands::likert_report, which checks them, analyses the file and renders; this file writes.
#include <memory>

#include "commands.hpp"
#include "feint/commands/table_commands.hpp"
#include "options.hpp"

namespace feint::cli {

namespace {

void run(const ReportCommand<commands::LikertCommandOptions>& a) {
  const ResolvedReportOptions r = resolve_report_options(a.report);
  const commands::LikertReport out = commands::likert_report(a.o, r);
  if (!a.o.summary.empty()) write_report(a.o.summary, out.summary_csv);
  write_report(r.output, out.text);
}

}  // namespace

void add_likert_command(CLI::App& app) {
  auto args = std::make_shared<ReportCommand<commands::LikertCommandOptions>>();
  auto* cmd = app.add_subcommand(
      "likert",
      "Likert questionnaire analyses: per item and composite scale, descriptives, the Wilcoxon "
      "signed-rank test against a reference (primary) and the one-sample t-test (the paper's), or "
      "Mann-Whitney and Welch between two conditions; Cronbach's alpha of composites.");
  cmd->add_option("file", args->o.file,
                  "Questionnaire CSV (long or wide; Qualtrics exports; .gz; - = stdin)")
      ->required();
  add_questionnaire_options(*cmd, args->o.likert, false);
  cmd->add_option("--condition", args->o.condition,
                  "Only this condition (default: each condition)");
  cmd->add_option("--compare", args->o.compare,
                  "Two conditions A,B: Mann-Whitney U (primary) and Welch's t-test");
  cmd->add_flag("--paper", args->o.paper,
                "The paper's analysis: items entertainment, deception, intelligence, trust against "
                "3.5 (t-test column; Wilcoxon primary)");
  cmd->add_option(
      "--summary", args->o.summary,
      "Also write per-item descriptives and counts per scale point as CSV to this file");
  add_report_options(*cmd, args->report, {.tests = true, .presentation = true, .bayes = true});
  cmd->callback([args] { run(*args); });
}

}  // namespace feint::cli

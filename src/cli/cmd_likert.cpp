// `feint likert FILE`: Likert questionnaire analyses (issue #4). Thin: options -> LikertSettings
// -> report::analyze_likert_file -> render -> atomic write. See docs/likert.md.
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
#include "feint/io/questionnaire.hpp"
#include "feint/report/likert.hpp"
#include "report_options.hpp"

namespace feint::cli {

namespace {

struct LikertArgs {
  std::string file;
  analysis::LikertOptions o;
  std::string condition;
  std::string compare;
  bool paper = false;
  std::string summary;
  ReportOptions report;
};

/// Comma-separated list values (CSV quoting allowed), from one or more occurrences of an option.
void run(const LikertArgs& args) {
  const ResolvedReportOptions r = resolve_report_options(args.report);
  io::refuse_overwriting_inputs({args.file}, {r.output, args.summary});
  if (!args.summary.empty() && io::same_file(args.summary, r.output)) {
    throw UsageError(fmt::format("--summary '{}' is the output file itself", args.summary));
  }
  report::LikertSettings s = analysis::likert_settings(args.o, r);
  s.condition = args.condition;
  if (!args.compare.empty()) {
    s.compare = parse_compare(args.compare);
    if (!s.condition.empty()) {
      throw UsageError("--compare and --condition do not combine: --compare names both groups");
    }
  }
  s.paper = args.paper;
  if (s.paper && s.compare) {
    throw UsageError(
        "--paper is the paper's one-sample analysis; it does not combine with --compare");
  }

  const auto analysis = report::analyze_likert_file(args.file, s);
  const std::string text = report::render_likert(analysis, r.format, r.presentation);
  if (!args.summary.empty()) {
    if (args.summary == "-" && r.output == "-") {
      throw UsageError("--summary - and -o - would both write to standard output");
    }
    write_report(args.summary, report::likert_summary_csv(analysis));
  }
  write_report(r.output, text);
}

}  // namespace

void add_likert_command(CLI::App& app) {
  auto args = std::make_shared<LikertArgs>();
  auto* cmd = app.add_subcommand(
      "likert",
      "Likert questionnaire analyses: per item and composite scale, descriptives, the Wilcoxon "
      "signed-rank test against a reference (primary) and the one-sample t-test (the paper's), or "
      "Mann-Whitney and Welch between two conditions; Cronbach's alpha of composites.");
  cmd->add_option("file", args->file,
                  "Questionnaire CSV (long or wide; Qualtrics exports; .gz; - = stdin)")
      ->required();
  add_questionnaire_options(*cmd, args->o, false);
  cmd->add_option("--condition", args->condition, "Only this condition (default: each condition)");
  cmd->add_option("--compare", args->compare,
                  "Two conditions A,B: Mann-Whitney U (primary) and Welch's t-test");
  cmd->add_flag("--paper", args->paper,
                "The paper's analysis: items entertainment, deception, intelligence, trust against "
                "3.5 (t-test column; Wilcoxon primary)");
  cmd->add_option(
      "--summary", args->summary,
      "Also write per-item descriptives and counts per scale point as CSV to this file");
  add_report_options(*cmd, args->report, {.tests = true, .presentation = true});
  cmd->callback([args] { run(*args); });
}

}  // namespace feint::cli

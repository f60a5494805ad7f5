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
  std::string layout = "auto";
  std::string scale = "1-7";
  std::string labels;
  std::vector<std::string> items;
  std::string id_column = "participant";
  std::string condition_column = "condition";
  std::string item_column = "item";
  std::string response_column = "response";
  std::vector<std::string> reverse;
  std::vector<std::string> composites;
  std::optional<double> reference;
  std::string condition;
  std::string compare;
  bool paper = false;
  std::string alpha_missing = "pairwise";
  bool keep_unfinished = false;
  bool keep_previews = false;
  std::string summary;
  ReportOptions report;
};

/// Comma-separated list values (CSV quoting allowed), from one or more occurrences of an option.
std::vector<std::string> split_lists(const std::vector<std::string>& values) {
  std::vector<std::string> out;
  for (const auto& v : values) {
    for (const auto& part : io::split_csv_line(v, ',')) {
      const auto t = io::trim(part);
      if (!t.empty()) out.emplace_back(t);
    }
  }
  return out;
}

void run(const LikertArgs& args) {
  const ResolvedReportOptions r = resolve_report_options(args.report);
  io::refuse_overwriting_inputs({args.file}, {r.output, args.summary});
  if (!args.summary.empty() && io::same_file(args.summary, r.output)) {
    throw UsageError(fmt::format("--summary '{}' is the output file itself", args.summary));
  }
  report::LikertSettings s;
  s.load.layout = io::parse_questionnaire_layout(args.layout);
  const auto [lo, hi] = io::parse_scale(args.scale);
  s.load.scale_min = lo;
  s.load.scale_max = hi;
  if (!args.labels.empty()) s.load.labels = io::parse_label_map(args.labels);
  s.load.items = split_lists(args.items);
  s.load.id_column = args.id_column;
  s.load.condition_column = args.condition_column;
  s.load.item_column = args.item_column;
  s.load.response_column = args.response_column;
  s.load.reverse = split_lists(args.reverse);
  s.load.keep_unfinished = args.keep_unfinished;
  s.alpha_missing = stats::parse_alpha_missing(args.alpha_missing);
  s.load.keep_previews = args.keep_previews;
  for (const auto& c : args.composites) s.composites.push_back(report::parse_composite(c));
  s.reference = args.reference;
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
  s.test = r.test;
  s.alpha = r.alpha;
  s.p_adjust = r.p_adjust;
  s.apa = r.apa;

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
  cmd->add_option("--layout", args->layout,
                  "long, wide or auto (long when the header has the item "
                  "and response columns)")
      ->capture_default_str();
  cmd->add_option("--scale", args->scale, "Scale bounds MIN-MAX (whole numbers)")
      ->capture_default_str();
  cmd->add_option("--labels", args->labels,
                  "Map text answers to scale points: \"Strongly disagree=1,Disagree=2,...\" "
                  "(default: built-in agree/disagree map for 5- and 7-point scales)");
  cmd->add_option("--items", args->items,
                  "Items to analyse, in order (wide: columns; long: item names); NAME=COLUMN "
                  "renames (trust=Q5_1); comma-separated, repeatable")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false);
  cmd->add_option("--id-column", args->id_column, "Respondent id column")->capture_default_str();
  cmd->add_option("--condition-column", args->condition_column,
                  "Condition column (optional in the file)")
      ->capture_default_str();
  cmd->add_option("--item-column", args->item_column, "Long layout: item column")
      ->capture_default_str();
  cmd->add_option("--response-column", args->response_column, "Long layout: response column")
      ->capture_default_str();
  cmd->add_option("--reverse", args->reverse,
                  "Reverse-coded items (comma-separated, repeatable), recoded x -> min + max - x "
                  "before anything else")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false);
  cmd->add_option("--composite", args->composites,
                  "Multi-item scale NAME=ITEM,ITEM,... (repeatable): mean of its items, Cronbach's "
                  "alpha")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false);
  cmd->add_option(
      "--reference", args->reference,
      "Reference value of the one-sample tests (default: the scale midpoint; --paper: 3.5)");
  cmd->add_option("--condition", args->condition, "Only this condition (default: each condition)");
  cmd->add_option("--compare", args->compare,
                  "Two conditions A,B: Mann-Whitney U (primary) and Welch's t-test");
  cmd->add_option("--alpha-missing", args->alpha_missing,
                  "Cronbach's alpha with missing answers: pairwise (psych::alpha's default) or "
                  "complete (complete cases)")
      ->capture_default_str();
  cmd->add_flag("--keep-unfinished", args->keep_unfinished,
                "Survey exports: keep responses with Finished = False or Progress < 100 "
                "(excluded by default, and named in the note)");
  cmd->add_flag("--keep-previews", args->keep_previews,
                "Survey exports: keep Status = Survey Preview, Survey Test, Spam (excluded by "
                "default, and named in the note)");
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

#include "report_options.hpp"

#include <fmt/format.h>

#include <cmath>
#include <set>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/io/output.hpp"

namespace feint::cli {

void add_scores_column_options(CLI::App& cmd, io::ScoresOptions& columns, std::string_view role) {
  cmd.add_option("--participant-column", columns.participant_column,
                 fmt::format("{}Name of the participant column", role))
      ->capture_default_str();
  cmd.add_option("--iteration-column", columns.iteration_column,
                 fmt::format("{}Name of the iteration column", role))
      ->capture_default_str();
  cmd.add_option("--condition-column", columns.condition_column,
                 fmt::format("{}Name of the (optional) condition column", role))
      ->capture_default_str();
}

void add_presentation_options(CLI::App& cmd, ReportOptions& options, const std::string& group) {
  auto* label = cmd.add_option("--label", options.label,
                               "LaTeX \\label of the table (default: unique per table, e.g. "
                               "tab:feint-table1-adaptive-vs-random)");
  auto* caption =
      cmd.add_option("--caption", options.caption, "Caption of the table (default: describes it)");
  auto* wide = cmd.add_flag("--latex-wide", options.latex_wide,
                            "LaTeX table* (spans both columns of a two-column paper)");
  if (!group.empty()) {
    label->group(group);
    caption->group(group);
    wide->group(group);
  }
}

void add_report_options(CLI::App& cmd, ReportOptions& options, ReportOptionSet set) {
  cmd.add_option("--format", options.format,
                 "Output format: text (aligned table), markdown, latex (booktabs fragment), csv or "
                 "json (tidy: one row per test)")
      ->capture_default_str();
  cmd.add_option("-o,--output", options.output,
                 "Output file, written atomically (temporary file + rename); - = standard output")
      ->capture_default_str();
  if (set.presentation) add_presentation_options(cmd, options);
  if (!set.tests) return;
  cmd.add_flag("--apa", options.apa,
               "Add an APA-style string per test, e.g. 't(29) = 2.93, p = .007, d = 0.53' "
               "(column 'apa' in csv/json)");
  cmd.add_option("--alpha", options.alpha, "Significance level for the labels, in (0, 1)")
      ->capture_default_str();
  cmd.add_option("--alternative", options.alternative,
                 "Alternative hypothesis: two.sided, greater or less (as R's t.test)")
      ->capture_default_str();
  cmd.add_option("--conf-level", options.conf_level,
                 "Confidence level of the intervals (conf_low, conf_high), in (0, 1)")
      ->capture_default_str();
  cmd.add_option("--p-adjust", options.p_adjust,
                 "Multiple-comparison adjustment within a family (R's p.adjust): none, bonferroni, "
                 "holm, hochberg, hommel, BH (alias fdr), BY; any case")
      ->capture_default_str();
}

void add_questionnaire_options(CLI::App& cmd, analysis::LikertOptions& o, bool in_analyze,
                               const std::string& group) {
  // feint analyze names the scale and the reference after the questionnaire (the tables have a
  // reference of their own); feint likert has only the questionnaire.
  const std::string p = in_analyze ? "--likert-" : "--";
  const char* q = in_analyze ? "Questionnaire: " : "";
  auto take_all = [](CLI::Option* opt) {
    return opt->expected(1)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->allow_extra_args(false);
  };
  std::vector<CLI::Option*> added = {
      cmd.add_option("--layout", o.layout,
                     fmt::format("{}long, wide or auto (long when the header has the item and "
                                 "response columns)", q))->capture_default_str(),
      cmd.add_option(p + "scale", o.scale, "Scale bounds MIN-MAX (whole numbers)")
          ->capture_default_str(),
      cmd.add_option("--labels", o.labels,
                     "Map text answers to scale points: \"Strongly disagree=1,Disagree=2,...\" "
                     "(default: built-in agree/disagree map for 5- and 7-point scales)"),
      take_all(cmd.add_option("--items", o.items,
                              "Items to analyse, in order (wide: columns; long: item names); "
                              "NAME=COLUMN renames (trust=Q5_1); comma-separated, repeatable")),
      cmd.add_option("--id-column", o.id_column, fmt::format("{}Respondent id column", q))
          ->capture_default_str(),
      cmd.add_option("--condition-column", o.condition_column,
                     fmt::format("{}Condition column (optional in the file)", q))
          ->capture_default_str(),
      cmd.add_option("--item-column", o.item_column, fmt::format("{}Long layout: item column", q))
          ->capture_default_str(),
      cmd.add_option("--response-column", o.response_column,
                     fmt::format("{}Long layout: response column", q))
          ->capture_default_str(),
      take_all(cmd.add_option("--reverse", o.reverse,
                              "Reverse-coded items (comma-separated, repeatable), recoded x -> "
                              "min + max - x before anything else")),
      take_all(cmd.add_option("--composite", o.composites,
                              "Multi-item scale NAME=ITEM,ITEM,... (repeatable): mean of its "
                              "items, Cronbach's alpha")),
      cmd.add_option(p + "reference", o.reference,
                     "Reference value of the one-sample tests (default: the scale midpoint; "
                     "the paper used 3.5)"),
      cmd.add_option("--alpha-missing", o.alpha_missing,
                     "Cronbach's alpha with missing answers: pairwise (psych::alpha's default) "
                     "or complete (complete cases)")
          ->capture_default_str(),
      cmd.add_flag("--keep-unfinished", o.keep_unfinished,
                   "Survey exports: keep responses with Finished = False or Progress < 100 "
                   "(excluded by default, and named in the note)"),
      cmd.add_flag("--keep-previews", o.keep_previews,
                   "Survey exports: keep Status = Survey Preview, Survey Test, Spam (excluded by "
                   "default, and named in the note)"),
  };
  if (!group.empty()) {
    for (auto* opt : added) opt->group(group);
  }
}

void write_report(const std::string& path, std::string_view content) {
  io::AtomicOutput out(path);
  out.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  out.commit();
}

}  // namespace feint::cli

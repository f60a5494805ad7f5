#include "options.hpp"

#include <fmt/format.h>

#include "feint/error.hpp"
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
  const std::string previous = cmd.option_defaults()->get_group();
  if (!group.empty()) cmd.option_defaults()->group(group);
  cmd.add_option("--label", options.label,
                 "LaTeX \\label of the table (default: unique per table, e.g. "
                 "tab:feint-table1-adaptive-vs-random)");
  cmd.add_option("--caption", options.caption, "Caption of the table (default: describes it)");
  cmd.add_flag("--latex-wide", options.latex_wide,
               "LaTeX table* (spans both columns of a two-column paper)");
  cmd.option_defaults()->group(previous);
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
               "Add an APA-style string per test, e.g. 't(29) = 2.93, p = .007, d = 0.53' (column "
               "'apa' in csv/json)");
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
  if (set.bayes)
    cmd.add_option("--bf-prior-scale", options.bf_prior_scale, analysis::kBfPriorScaleHelp)
        ->capture_default_str();
}

void add_questionnaire_options(CLI::App& cmd, analysis::LikertOptions& o, bool in_analyze,
                               const std::string& group) {
  // feint analyze names the scale and the reference after the questionnaire (the tables have a
  // reference of their own); feint likert has only the questionnaire.
  const std::string p = in_analyze ? "--likert-" : "--";
  const char* q = in_analyze ? "Questionnaire: " : "";
  const std::string previous = cmd.option_defaults()->get_group();
  if (!group.empty()) cmd.option_defaults()->group(group);
  cmd.add_option("--layout", o.layout,
                 fmt::format("{}long, wide or auto (long when the header has the item and "
                             "response columns)",
                             q))
      ->capture_default_str();
  cmd.add_option(p + "scale", o.scale, "Scale bounds MIN-MAX (whole numbers)")
      ->capture_default_str();
  cmd.add_option("--labels", o.labels,
                 "Map text answers to scale points: \"Strongly disagree=1,Disagree=2,...\" "
                 "(default: built-in agree/disagree map for 5- and 7-point scales)");
  one_per_use(cmd.add_option("--items", o.items,
                             "Items to analyse, in order (wide: columns; long: item names); "
                             "NAME=COLUMN renames (trust=Q5_1); comma-separated, repeatable"));
  cmd.add_option("--id-column", o.id_column, fmt::format("{}Respondent id column", q))
      ->capture_default_str();
  cmd.add_option("--condition-column", o.condition_column,
                 fmt::format("{}Condition column (optional in the file)", q))
      ->capture_default_str();
  cmd.add_option("--item-column", o.item_column, fmt::format("{}Long layout: item column", q))
      ->capture_default_str();
  cmd.add_option("--response-column", o.response_column,
                 fmt::format("{}Long layout: response column", q))
      ->capture_default_str();
  one_per_use(cmd.add_option("--reverse", o.reverse,
                             "Reverse-coded items (comma-separated, repeatable), recoded x -> min "
                             "+ max - x before anything else"));
  one_per_use(cmd.add_option("--composite", o.composites,
                             "Multi-item scale NAME=ITEM,ITEM,... (repeatable): mean of its items, "
                             "Cronbach's alpha"));
  cmd.add_option(p + "reference", o.reference,
                 "Reference value of the one-sample tests (default: the scale midpoint; the paper "
                 "used 3.5)");
  cmd.add_option("--alpha-missing", o.alpha_missing,
                 "Cronbach's alpha with missing answers: pairwise (psych::alpha's default) or "
                 "complete (complete cases)")
      ->capture_default_str();
  cmd.add_flag("--keep-unfinished", o.keep_unfinished,
               "Survey exports: keep responses with Finished = False or Progress < 100 (excluded "
               "by default, and named in the note)");
  cmd.add_flag("--keep-previews", o.keep_previews,
               "Survey exports: keep Status = Survey Preview, Survey Test, Spam (excluded by "
               "default, and named in the note)");
  cmd.option_defaults()->group(previous);
}

CLI::Option* one_per_use(CLI::Option* opt) {
  return opt->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false);
}

void write_report(const std::string& path, std::string_view content) {
  io::AtomicOutput out(path);
  out.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  out.commit();
}

void add_score_options(CLI::App& cmd, ScoreOptions& o, const std::string& group) {
  // In `group` (if given), then back to the group the command had.
  const std::string previous = cmd.option_defaults()->get_group();
  if (!group.empty()) cmd.option_defaults()->group(group);
  auto* trim = cmd.add_option("--trim", o.trim,
                              "Fraction of each trial's duration excluded at BOTH ends, in [0, 1) "
                              "(default 0.05)");
  cmd.add_option("--trim-start", o.trim_start,
                 "Fraction of the duration excluded at the start, in [0, 1) (default 0.05)")
      ->excludes(trim);
  cmd.add_option("--trim-end", o.trim_end,
                 "Fraction of the duration excluded at the end, in [0, 1) (default 0.05)")
      ->excludes(trim);
  cmd.add_option("--deadband", o.deadband,
                 "Dead band eps in pad units: a segment moving <= eps has no direction for the "
                 "reversal rule (default 1e-9)");
  cmd.add_option("--belief-deadband", o.belief_deadband,
                 "Dead band delta in pad units of the belief-trace measures: flips smaller than "
                 "delta are ignored, and the pad is on a side of 0.5 only beyond delta (default "
                 "0.05)");
  cmd.add_option("--confusion-norm", o.norm,
                 "Confusion normalisation: 'raw' = the paper's eq. 4 as printed, the scale of its "
                 "reference 0.95 (default); 'speed' = moving fraction at the pad speed, in [0, 1]")
      ->check(CLI::IsMember({"speed", "raw"}, CLI::ignore_case));
  cmd.add_option("--pad-speed", o.pad_speed,
                 "Pad speed v in pad units per second for every trial; replaces a pad_speed column "
                 "(needed by --confusion-norm speed when the logs have none)");
  add_loader_options(cmd, o);
  cmd.option_defaults()->group(previous);
}

void add_loader_options(CLI::App& cmd, ScoreOptions& o, const std::string& group) {
  const std::string previous = cmd.option_defaults()->get_group();
  if (!group.empty()) cmd.option_defaults()->group(group);
  // One value per use: CLI11 2.1 would otherwise let a list option swallow a positional argument.
  cmd.add_option("--map", o.maps,
                 "NAME=COLUMN: read field NAME (participant, condition, iteration, strategy, "
                 "variant, target, t, pad, pad_speed) from the study's column COLUMN; repeatable")
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd.add_option("--delimiter", o.delimiter,
                 "Field separator: , ; tab | (default: detected per file from its header)");
  cmd.add_option("--on-error", o.on_error,
                 "strict = stop at the first invalid trial (default); skip = leave invalid trials "
                 "out and list them in the rejects file")
      ->check(CLI::IsMember({"strict", "skip"}));
  cmd.add_option("--time-unit", o.time_unit,
                 "Unit of the logs' t column: s (default) or ms (converted to seconds; jsPsych and "
                 "many loggers write ms)")
      ->check(CLI::IsMember({"s", "ms"}, CLI::ignore_case));
  cmd.add_option("--decimal", o.decimal,
                 "Decimal mark of the logs' numbers: . or , (default: '.' in a comma-separated "
                 "file; otherwise detected from the first number holding one)");
  cmd.add_flag("--no-header", o.no_header,
               "The logs have no header row (MATLAB): name the columns with --columns, or by "
               "number with --map FIELD=N (N from 1)");
  cmd.add_option("--columns", o.columns,
                 "With --no-header: the columns' names in order, comma-separated, e.g. "
                 "participant,iteration,target,t,pad (a column not named is called by its number)");
  cmd.add_option("--iteration-base", o.iteration_base,
                 "0 = the logs number iterations from 0 (PsychoPy; 1 is added, so 0..19 become "
                 "1..20); 1 = from 1 (an iteration 0 is invalid). Default: as written, with a "
                 "warning when they start at 0")
      ->check(CLI::IsMember({"0", "1"}));
  cmd.add_option("--participant-from-path", o.participant_from_path,
                 "Take the participant id from each log's path instead of a column: filename (name "
                 "without extensions), dirname (folder name), or a regular expression whose first "
                 "group is the id, e.g. 'sub-([0-9]+)'");
  cmd.add_option("--samples-column", o.samples_column,
                 "A column holding each trial's samples as JSON (jsPsych): "
                 "[{\"t\":0,\"pad\":0.5},...] or {\"t\":[...],\"pad\":[...]}; keys follow --map "
                 "t=KEY / pad=KEY");
  cmd.add_flag("--single-condition", o.single_condition,
               "Read every trial as one condition although a column looks like a condition (group, "
               "cond..., arm, treatment)");
  cmd.option_defaults()->group(previous);
}

}  // namespace feint::cli

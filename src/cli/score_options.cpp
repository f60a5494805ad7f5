#include "score_options.hpp"

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

namespace feint::cli {

namespace {

}  // namespace

void add_score_options(CLI::App& cmd, ScoreOptions& o, const std::string& group) {
  std::vector<CLI::Option*> added;
  auto* trim = cmd.add_option("--trim", o.trim,
                              "Fraction of each trial's duration excluded at BOTH ends, in [0, 1) "
                              "(default 0.05)");
  added.push_back(trim);
  added.push_back(
      cmd.add_option("--trim-start", o.trim_start,
                     "Fraction of the duration excluded at the start, in [0, 1) (default 0.05)")
          ->excludes(trim));
  added.push_back(
      cmd.add_option("--trim-end", o.trim_end,
                     "Fraction of the duration excluded at the end, in [0, 1) (default 0.05)")
          ->excludes(trim));
  added.push_back(cmd.add_option("--deadband", o.deadband,
                                 "Dead band eps in pad units: a segment moving <= eps has no "
                                 "direction for the reversal rule (default 1e-9)"));
  added.push_back(cmd.add_option("--belief-deadband", o.belief_deadband,
                                 "Dead band delta in pad units of the belief-trace measures: flips "
                                 "smaller than delta are ignored, and the pad is on a side of 0.5 "
                                 "only beyond delta (default 0.05)"));
  added.push_back(cmd.add_option("--confusion-norm", o.norm,
                                 "Confusion normalisation: 'speed' = moving fraction at the pad "
                                 "speed, in [0, 1] (default); 'raw' = the paper's eq. 4 as printed "
                                 "(unbounded)")
                      ->check(CLI::IsMember({"speed", "raw"}, CLI::ignore_case)));
  added.push_back(cmd.add_option("--pad-speed", o.pad_speed,
                                 "Pad speed v in pad units per second for every trial; replaces a "
                                 "pad_speed column (needed by --confusion-norm speed when the logs "
                                 "have none)"));
  // One value per use: CLI11 2.1 would otherwise let a list option swallow a positional argument.
  added.push_back(cmd.add_option("--map", o.maps,
                                 "NAME=COLUMN: read field NAME (participant, condition, iteration, "
                                 "strategy, variant, target, t, pad, pad_speed) from the study's "
                                 "column COLUMN; repeatable")
                      ->allow_extra_args(false)
                      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll));
  added.push_back(cmd.add_option("--delimiter", o.delimiter,
                                 "Field separator: , ; tab | (default: detected per file from its "
                                 "header)"));
  added.push_back(cmd.add_option("--on-error", o.on_error,
                                 "strict = stop at the first invalid trial (default); skip = leave "
                                 "invalid trials out and list them in the rejects file")
                      ->check(CLI::IsMember({"strict", "skip"})));
  added.push_back(cmd.add_option("--time-unit", o.time_unit,
                                 "Unit of the logs' t column: s (default) or ms (converted to "
                                 "seconds; jsPsych and many loggers write ms)")
                      ->check(CLI::IsMember({"s", "ms"}, CLI::ignore_case)));
  added.push_back(cmd.add_option("--decimal", o.decimal,
                                 "Decimal mark of the logs' numbers: . or , (default: '.' in a "
                                 "comma-separated file; otherwise detected from the first number "
                                 "holding one)"));
  added.push_back(cmd.add_flag("--no-header", o.no_header,
                               "The logs have no header row (MATLAB): name the columns with "
                               "--columns, or by number with --map FIELD=N (N from 1)"));
  added.push_back(cmd.add_option("--columns", o.columns,
                                 "With --no-header: the columns' names in order, comma-separated, "
                                 "e.g. participant,iteration,target,t,pad (a column not named is "
                                 "called by its number)"));
  added.push_back(cmd.add_option("--iteration-base", o.iteration_base,
                                 "0 = the logs number iterations from 0 (PsychoPy; 1 is added, so "
                                 "0..19 become 1..20); 1 = from 1 (an iteration 0 is invalid). "
                                 "Default: as written, with a warning when they start at 0")
                      ->check(CLI::IsMember({"0", "1"})));
  added.push_back(cmd.add_option("--participant-from-path", o.participant_from_path,
                                 "Take the participant id from each log's path instead of a "
                                 "column: filename (name without extensions), dirname (folder "
                                 "name), or a regular expression whose first group is the id, "
                                 "e.g. 'sub-([0-9]+)'"));
  added.push_back(cmd.add_option("--samples-column", o.samples_column,
                                 "A column holding each trial's samples as JSON (jsPsych): "
                                 "[{\"t\":0,\"pad\":0.5},...] or {\"t\":[...],\"pad\":[...]}; "
                                 "keys follow --map t=KEY / pad=KEY"));
  added.push_back(cmd.add_flag("--single-condition", o.single_condition,
                               "Read every trial as one condition although a column looks like "
                               "a condition (group, cond..., arm, treatment)"));
  if (!group.empty()) {
    for (auto* opt : added) opt->group(group);
  }
}

}  // namespace feint::cli

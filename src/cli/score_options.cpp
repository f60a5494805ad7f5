#include "score_options.hpp"

#include <fmt/format.h>

#include "feint/error.hpp"
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
  if (!group.empty()) {
    for (auto* opt : added) opt->group(group);
  }
}

}  // namespace feint::cli

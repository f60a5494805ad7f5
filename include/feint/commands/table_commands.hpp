// feint/commands/table_commands.hpp - the one-table commands (`feint table`, `anova`, `model`,
// `likert`) with their options as the command line spells them: checked (UsageError names the
// option), the input read, the table built and rendered. The command line only binds the options
// and writes the text (docs/tables.md, docs/anova-power.md, docs/mixed-model.md, docs/likert.md).
#pragma once

#include <string>
#include <vector>

#include "feint/analysis/settings.hpp"
#include "feint/io/scores.hpp"

namespace feint::commands {

struct TableCommandOptions {
  std::string input;
  std::vector<std::string> metrics;  // NAME=REF
  std::string condition;
  std::string compare;  // A,B
  bool var_equal = false;
  bool paired = false;
  std::string design;  // --design between|within ("" = read off the data)
  double equivalence = 0.0;
  bool equivalence_given = false;  // --equivalence was given (TOST)
  io::ScoresOptions columns;       // --participant-column, --iteration-column, --condition-column
};

/// Table 1 (tables::build_table1) rendered in `r.format`. Refuses to overwrite the scores file or
/// its sidecar with `r.output`.
std::string table1_report(const TableCommandOptions& options, const analysis::ResolvedReportOptions& r);

struct AnovaCommandOptions {
  std::string input;
  std::vector<std::string> metrics;
  std::string correction = "GG";
  bool apa = false;
  bool drop_empty_conditions = false;
  bool emmeans = false;
  std::vector<std::string> contrasts;
  std::string adjust;
  std::string design;  // --design between|within ("" = read off the data)
  io::ScoresOptions columns;
};

/// The mixed ANOVA of every metric (tables::build_anova_report) rendered in `r.format`.
std::string anova_report(const AnovaCommandOptions& options, const analysis::ResolvedReportOptions& r);

struct ModelCommandOptions {
  std::string input;
  std::vector<std::string> metrics;
  std::string compare;
  bool trend = false;
  bool random_slope = false;
  bool random_condition_slope = false;  // (1 + condition | participant); conditions within
  std::string design;                   // --design between|within ("" = read off the data)
  bool exposure = false;
  io::ScoresOptions columns;
  std::string strategy_column = "strategy";
  std::vector<std::string> random;  ///< --random strategy / participant:strategy
  std::string ddf = "satterthwaite";
  bool emmeans = false;
  std::vector<std::string> contrasts;
  std::string adjust;
};

/// The linear mixed model of every metric (tables::build_model_analysis) rendered in `r.format`.
/// Contrasts are two-sided: another --alternative is refused.
std::string model_report(const ModelCommandOptions& options, const analysis::ResolvedReportOptions& r);

struct LikertCommandOptions {
  std::string file;
  analysis::LikertOptions likert;
  std::string condition;
  std::string compare;
  bool paper = false;
  std::string summary;  // also write the per-item summary CSV here
};

/// The questionnaire analysis rendered in `r.format`, and (with --summary) its summary CSV.
struct LikertReport {
  std::string text;
  std::string summary_csv;
};

/// Refuses to overwrite the questionnaire; checks the options before reading it.
LikertReport likert_report(const LikertCommandOptions& options, const analysis::ResolvedReportOptions& r);

}  // namespace feint::commands

#include "feint/commands/table_commands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "feint/error.hpp"
#include "feint/io/file_identity.hpp"
#include "feint/models/condition_design.hpp"
#include "feint/models/emmeans.hpp"
#include "feint/tables/anova.hpp"
#include "feint/tables/likert.hpp"
#include "feint/tables/model.hpp"
#include "feint/tables/table1.hpp"

namespace feint::commands {

namespace {

// The conditions' design of a scores table: --design, else read off the data; a contradiction is
// InvalidData naming the participant and what to set (models/condition_design.hpp).
models::DesignCheck design_of(const io::ScoresTable& scores, std::optional<models::ConditionDesign> declared,
                              const std::string& metric) {
  return models::check_condition_design(tables::observations(scores, metric), declared, scores.path);
}

}  // namespace

std::string table1_report(const TableCommandOptions& a, const analysis::ResolvedReportOptions& r) {
  io::refuse_overwriting_inputs({a.input}, {r.output});
  tables::Table1Options o;
  o.metrics = analysis::parse_metric_specs(a.metrics);
  o.condition = a.condition;
  if (!a.compare.empty()) {
    o.compare = analysis::parse_compare(a.compare);
    if (!a.condition.empty()) throw UsageError("--condition and --compare exclude each other");
  }
  const auto declared = models::parse_condition_design(a.design);
  o.design = declared;  // the omnibus table of three or more conditions reads it (else off the data)
  o.var_equal = a.var_equal;
  o.paired = a.paired;
  if (a.equivalence_given) o.equivalence = a.equivalence;
  o.alpha = r.alpha;
  o.test = r.test;
  o.p_adjust = r.p_adjust;
  o.apa = r.apa;
  o.bf_prior_r = r.bf_prior_r;

  io::ScoresOptions so = a.columns;
  so.metrics.clear();
  for (const auto& m : o.metrics) so.metrics.push_back(m.column);
  const io::ScoresTable scores = io::load_scores(a.input, so);
  // Conditions within participants are compared pair by pair.
  if (o.compare && design_of(scores, declared, o.metrics.front().column).design == models::ConditionDesign::within) {
    if (o.var_equal) throw UsageError("--var-equal: the conditions are within participants (paired t-tests)");
    o.paired = true;
  }
  const tables::Table1 table = tables::build_table1(scores, o);
  // The scores' sidecar (read for the note) is an input too.
  io::refuse_overwriting_inputs({table.provenance.sidecar_path}, {r.output});
  return tables::render_table1(table, r.format, r.presentation);
}

std::string anova_report(const AnovaCommandOptions& a, const analysis::ResolvedReportOptions& r) {
  const auto correction = models::parse_sphericity_correction(a.correction);
  io::ScoresOptions so = a.columns;
  if (!a.metrics.empty()) {
    so.metrics.clear();
    for (const auto& m : a.metrics) {
      if (m.empty() || m.find('=') != std::string::npos) {
        throw UsageError("--metric '" + m + "': expected a metric column name, e.g. error");
      }
      if (std::find(so.metrics.begin(), so.metrics.end(), m) != so.metrics.end()) {
        throw UsageError("--metric '" + m + "' given twice");
      }
      so.metrics.push_back(m);
    }
  }
  tables::AnovaEmmOptions emm;
  emm.emmeans = a.emmeans;
  emm.conf_level = r.test.conf_level;
  auto contrasts = models::parse_emm_contrasts(a.contrasts, a.adjust);
  emm.families = std::move(contrasts.families);
  emm.adjust = contrasts.adjust;
  const auto declared = models::parse_condition_design(a.design);
  const io::ScoresTable scores = io::load_scores(a.input, so);
  const bool within = !scores.metrics.empty() &&
                      design_of(scores, declared, scores.metrics.front()).design == models::ConditionDesign::within;
  const tables::AnovaReport report =
      tables::build_anova_report(scores, correction, a.drop_empty_conditions, emm, within);
  return tables::render_anova(report, r.format, a.apa, r.presentation);
}

std::string model_report(const ModelCommandOptions& a, const analysis::ResolvedReportOptions& r) {
  if (r.test.alternative != stats::Alternative::two_sided)
    throw UsageError("feint model: contrasts are two-sided (--alternative two.sided)");
  tables::ModelOptions o;
  if (!a.metrics.empty()) {
    o.metrics.clear();
    for (const auto& m : a.metrics) {
      if (m.find('=') != std::string::npos)
        throw UsageError("--metric " + m + ": feint model takes a metric name only (no reference)");
      if (std::find(o.metrics.begin(), o.metrics.end(), m) != o.metrics.end())
        throw UsageError("--metric " + m + " given twice");
      o.metrics.push_back(m);
    }
  }
  if (!a.compare.empty()) o.compare = analysis::parse_compare(a.compare);
  o.trend = a.trend;
  o.random_slope = a.random_slope;
  o.random_condition_slope = a.random_condition_slope;
  const auto declared = models::parse_condition_design(a.design);
  o.exposure = a.exposure;
  o.random_strategy = tables::parse_random_terms(a.random);
  o.alpha = r.alpha;
  o.conf_level = r.test.conf_level;
  o.p_adjust = r.p_adjust;
  o.apa = r.apa;
  o.ddf = models::parse_ddf_method(a.ddf);
  o.emmeans = a.emmeans;
  auto contrasts = models::parse_emm_contrasts(a.contrasts, a.adjust);
  o.contrast_families = std::move(contrasts.families);
  o.adjust = contrasts.adjust;
  // The options' other combinations are checked before the file is read; whether the conditions
  // are within participants, only after.
  o.condition_within = o.random_condition_slope;
  tables::validate(o);

  io::ScoresOptions so = a.columns;
  so.metrics = o.metrics;
  const bool strategy = o.exposure || !o.random_strategy.empty();
  if (strategy && a.input == "-")
    throw UsageError(fmt::format("{} reads the file twice: give a file, not standard input",
                                 o.exposure ? "--exposure" : "--random"));
  const io::ScoresTable scores = io::load_scores(a.input, so);
  // Strategies are within participants whatever the conditions are; the conditions' design is
  // checked (and read off the data) only for the models of conditions.
  if (!o.exposure && !o.metrics.empty())
    o.condition_within = design_of(scores, declared, o.metrics.front()).design == models::ConditionDesign::within;
  if (o.random_condition_slope && !o.condition_within)
    throw UsageError("--random-condition-slope: the conditions are between participants (a random slope of the "
                     "condition needs each participant in several conditions: --design within)");
  std::vector<std::string> strategies;
  if (strategy) strategies = tables::load_strategies(scores, so, a.strategy_column);
  const tables::ModelAnalysis analysis =
      tables::build_model_analysis(scores, o, strategy ? &strategies : nullptr);
  return tables::render_model(analysis, r.format, r.presentation);
}

LikertReport likert_report(const LikertCommandOptions& args, const analysis::ResolvedReportOptions& r) {
  io::refuse_overwriting_inputs({args.file}, {r.output, args.summary});
  if (!args.summary.empty() && io::same_file(args.summary, r.output)) {
    throw UsageError(fmt::format("--summary '{}' is the output file itself", args.summary));
  }
  tables::LikertSettings s = analysis::likert_settings(args.likert, r);
  s.condition = args.condition;
  if (!args.compare.empty()) {
    s.compare = analysis::parse_compare(args.compare);
    if (!s.condition.empty()) {
      throw UsageError("--compare and --condition do not combine: --compare names both groups");
    }
  }
  s.paper = args.paper;
  if (s.paper && s.compare) {
    throw UsageError(
        "--paper is the paper's one-sample analysis; it does not combine with --compare");
  }

  const auto analysis = tables::analyze_likert_file(args.file, s);
  LikertReport out;
  out.text = tables::render_likert(analysis, r.format, r.presentation);
  if (!args.summary.empty()) {
    if (args.summary == "-" && r.output == "-") {
      throw UsageError("--summary - and -o - would both write to standard output");
    }
    out.summary_csv = tables::likert_summary_csv(analysis);
  }
  return out;
}

}  // namespace feint::commands

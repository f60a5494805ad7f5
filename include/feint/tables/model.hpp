// feint/tables/model.hpp - `feint model`: the linear mixed model of each metric from a
// scores file, and its renderings (text, Markdown, booktabs LaTeX, tidy CSV and JSON).
//
// Per metric: the type-III ANOVA with Satterthwaite df (lmerTest::anova), the variance components
// and ICC (lme4::VarCorr), and either the per-iteration contrasts of condition A against B
// (emmeans(m, pairwise ~ condition | iteration), a Table 1-shaped table) or, with --exposure, the
// slope of exposure per strategy. docs/mixed-model.md.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "feint/io/scores.hpp"
#include "feint/models/crossed_model.hpp"
#include "feint/models/emmeans.hpp"
#include "feint/models/mixed_model.hpp"
#include "feint/tables/writers.hpp"
#include "feint/stats/p_adjust.hpp"

namespace feint::tables {

struct ModelOptions {
  std::vector<std::string> metrics = {"error", "confusion"};
  bool trend = false;         ///< iteration as a linear trend instead of a factor
  bool random_slope = false;  ///< (1 + iteration | participant); needs `trend`
  /// Each participant may see several conditions: the model is fitted with the condition within
  /// participants (models::fit_mixed_model's group_between = false) and the missing trials are
  /// counted per participant x condition seen.
  bool condition_within = false;
  /// (1 + condition | participant): a random deviation per participant and condition
  /// (models::ModelSpec::random_group_slope); needs `condition_within`, not with `random_slope`
  /// or `exposure`.
  bool random_condition_slope = false;
  bool exposure = false;      ///< metric ~ strategy * exposure + (1 | participant)
  /// --random strategy / participant:strategy: random intercepts of the strategy beside
  /// (1 | participant), crossed or nested (models::fit_crossed_model); needs the strategy of each
  /// trial, not with the random slopes, --exposure or Kenward-Roger.
  std::vector<models::RandomIntercept> random_strategy;
  /// The contrast A - B; default: the first two conditions in R's level order.
  std::optional<std::pair<std::string, std::string>> compare;
  double alpha = 0.05;
  double conf_level = 0.95;
  stats::PAdjustMethod p_adjust = stats::PAdjustMethod::none;  ///< over the iterations (strategies)
  bool apa = false;
  /// Denominator df of the F tests and contrasts: Satterthwaite (default) or Kenward-Roger.
  models::DdfMethod ddf = models::DdfMethod::satterthwaite;
  /// --emmeans: the estimated marginal means (cells, conditions, iterations), as emmeans.
  bool emmeans = false;
  /// --contrasts pairwise|simple|poly: emmeans contrast families.
  std::vector<models::EmmFamily> contrast_families;
  /// --adjust; empty = emmeans' defaults (tukey for pairwise families, none for polynomials).
  std::optional<models::EmmAdjust> adjust;
};

/// `--random` values: "strategy" (crossed, (1 | strategy)) and "participant:strategy" (nested,
/// (1 | participant:strategy)), each at most once. Throws UsageError naming a bad value.
std::vector<models::RandomIntercept> parse_random_terms(const std::vector<std::string>& values);

/// Throws UsageError for options that do not go together: --emmeans or --contrasts with --trend or
/// --exposure, --compare with --exposure, --random-slope without --trend, --exposure with --trend
/// or --random-slope, --random-condition-slope without the condition within participants or with
/// --random-slope or --exposure.
void validate(const ModelOptions& o);

using models::EmmTable;

/// A contrast (or slope) row: what it compares and its test.
struct ModelContrast {
  std::optional<double> iteration;  ///< contrasts: the iteration
  std::string level;                ///< slopes: the strategy
  models::Contrast contrast;
  std::string label;  ///< A>B, A<B, A≈B (contrasts only)
  std::string apa;
};

struct MetricModel {
  std::string metric;
  models::MixedModelFit fit;
  /// The trials the model was fitted to (the findings relabel them: models::relabel_condition_tests).
  models::LongData data;
  std::string formula;  ///< lme4 syntax, e.g. "error ~ condition * iteration + (1 | participant)"
  /// Participant x iteration trials without a value (empty, or no row), over the participants
  /// with at least one value and the iterations of the file.
  std::size_t trials_missing = 0;
  std::size_t participants_with_missing = 0;  ///< kept in the model
  std::vector<std::pair<std::string, std::size_t>> participants_per_group;
  std::vector<ModelContrast>
      contrasts;               ///< per iteration (A - B), or per strategy (exposure slope)
  std::string group1, group2;  ///< A and B of the contrasts
  /// --random strategy: the fit with the strategy's random intercepts (fit holds its fixed effects,
  /// type-III table and Satterthwaite machinery; this its variance components and ranova tests).
  std::optional<models::CrossedModelFit> crossed;
  std::vector<EmmTable> emmeans;        ///< --emmeans
  std::vector<EmmTable> emm_contrasts;  ///< --contrasts
};

struct ModelAnalysis {
  ModelOptions options;
  std::string source;
  std::vector<MetricModel> models;
};

/// Fits the model of every metric. `strategy` (one per scores record, needed with `exposure`) is
/// the strategy of each trial. Throws InvalidData for: a participant in two conditions (unless
/// `condition_within`), an
/// iteration present in the file but without a value of the metric for any participant, a metric
/// without variance, an empty condition x iteration cell, a --compare condition not in the data;
/// UsageError for impossible options (random slope without trend, exposure with trend).
ModelAnalysis build_model_analysis(const io::ScoresTable& scores, const ModelOptions& options,
                                   const std::vector<std::string>* strategy = nullptr);

/// Reads the `strategy_column` of the scores file for each record of `scores` (matched by
/// participant, condition and iteration). InvalidData when the column is absent or a trial has an
/// empty strategy.
std::vector<std::string> load_strategies(const io::ScoresTable& scores,
                                         const io::ScoresOptions& options,
                                         const std::string& strategy_column = "strategy");

/// A model test's df as every APA string prints it (docs/findings.md "Degrees of freedom"): one
/// decimal, none when it rounds to a whole number: 58 (also a Satterthwaite df of 57.99999), 1157.8.
std::string apa_model_df(double df);

/// `F(1, 58) = 4.31, p = .042`: both df by apa_model_df.
std::string anova_apa(const models::AnovaTerm& term);

/// The notes under the tables of one metric (model, REML, Satterthwaite, counts, missing trials).
std::vector<std::string> model_notes(const ModelAnalysis& analysis, const MetricModel& model);

/// Text / Markdown / LaTeX: per metric the ANOVA, the random effects and the contrast (or slope)
/// table with the notes. CSV / JSON: one tidy record per ANOVA term, variance parameter, fixed
/// effect and contrast, with a `table` column ("anova", "ran_pars", "fixef", "contrast", "slope")
/// and broom.mixed / lmerTest column names.
///
/// `presentation` (--label, --caption, --latex-wide): LaTeX labels are
/// tab:feint-model-anova-<metric>, -random-<metric> and -contrasts-<metric> (-slopes-<metric> with
/// exposure). A given label names the first metric's ANOVA table (which also gets the caption) and
/// replaces "tab:feint-model" in the others' labels (<label>-random-error, <label>-anova-confusion,
/// ...); --latex-wide makes every table wide.
std::string render_model(const ModelAnalysis& analysis, OutputFormat format,
                         const TablePresentation& presentation = {});

}  // namespace feint::tables

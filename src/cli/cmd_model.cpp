// feint model SCORES.csv: the linear mixed model of each metric (see docs/mixed-model.md).
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "feint/error.hpp"
#include "feint/io/scores.hpp"
#include "feint/report/model_render.hpp"
#include "report_options.hpp"

namespace feint::cli {

namespace {

struct ModelArgs {
  std::string input;
  std::vector<std::string> metrics;
  std::string compare;
  bool trend = false;
  bool random_slope = false;
  bool exposure = false;
  io::ScoresOptions columns;  // --participant-column, --iteration-column, --condition-column
  std::string strategy_column = "strategy";
  std::string ddf = "satterthwaite";
  bool emmeans = false;
  std::vector<std::string> contrasts;
  std::string adjust;
  ReportOptions report;
};

void run_model(const ModelArgs& a) {
  const ResolvedReportOptions r = resolve_report_options(a.report);
  if (r.test.alternative != stats::Alternative::two_sided)
    throw UsageError("feint model: contrasts are two-sided (--alternative two.sided)");
  report::ModelOptions o;
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
  if (!a.compare.empty()) o.compare = parse_compare(a.compare);
  o.trend = a.trend;
  o.random_slope = a.random_slope;
  o.exposure = a.exposure;
  o.alpha = r.alpha;
  o.conf_level = r.test.conf_level;
  o.p_adjust = r.p_adjust;
  o.apa = r.apa;
  if (a.ddf == "satterthwaite") {
    o.ddf = models::DdfMethod::satterthwaite;
  } else if (a.ddf == "kenward-roger") {
    o.ddf = models::DdfMethod::kenward_roger;
  } else {
    throw UsageError("--ddf " + a.ddf + ": expected satterthwaite or kenward-roger");
  }
  o.emmeans = a.emmeans;
  for (const auto& c : a.contrasts) {
    using F = models::EmmFamily;
    std::vector<F> add;
    if (c == "pairwise") {
      add = {F::pairwise_condition, F::pairwise_iteration};
    } else if (c == "simple") {
      add = {F::condition_at_iteration, F::iteration_in_condition};
    } else if (c == "poly") {
      add = {F::poly_iteration, F::poly_in_condition};
    } else {
      throw UsageError("--contrasts " + c + ": expected pairwise, simple or poly");
    }
    for (const F f : add)
      if (std::find(o.contrast_families.begin(), o.contrast_families.end(), f) ==
          o.contrast_families.end())
        o.contrast_families.push_back(f);
  }
  if (!a.adjust.empty()) {
    if (a.contrasts.empty()) throw UsageError("--adjust applies to --contrasts");
    o.adjust = models::parse_emm_adjust(a.adjust);
    if (*o.adjust == models::EmmAdjust::tukey &&
        std::find(a.contrasts.begin(), a.contrasts.end(), "poly") != a.contrasts.end())
      throw UsageError("--adjust tukey applies to pairwise and simple contrasts, not to poly");
  }
  if ((o.emmeans || !o.contrast_families.empty()) && (o.trend || o.exposure))
    throw UsageError("--emmeans and --contrasts need iteration as a factor (drop --trend/--exposure)");
  if (o.exposure && o.compare) throw UsageError("--compare does not apply to --exposure");
  if (o.random_slope && !o.trend)
    throw UsageError("--random-slope needs --trend (a random slope of the linear trend)");
  if (o.exposure && (o.trend || o.random_slope))
    throw UsageError(
        "--exposure fits its own model (strategy * exposure); drop --trend/--random-slope");

  io::ScoresOptions so = a.columns;
  so.metrics = o.metrics;
  if (o.exposure && a.input == "-")
    throw UsageError("--exposure reads the file twice: give a file, not standard input");
  const io::ScoresTable scores = io::load_scores(a.input, so);
  std::vector<std::string> strategies;
  if (o.exposure) strategies = report::load_strategies(scores, so, a.strategy_column);
  const report::ModelAnalysis analysis =
      report::build_model_analysis(scores, o, o.exposure ? &strategies : nullptr);
  write_report(r.output, report::render_model(analysis, r.format, r.presentation));
}

}  // namespace

void add_model_command(CLI::App& app) {
  auto args = std::make_shared<ModelArgs>();
  auto* cmd = app.add_subcommand(
      "model",
      "Linear mixed model per metric: metric ~ condition * iteration + (1 | participant) by REML, "
      "type-III F tests with Satterthwaite df (as lmerTest), variance components, and contrasts "
      "of two conditions per iteration (as emmeans).");
  cmd->add_option("SCORES", args->input,
                  "Scores CSV: participant, iteration, condition, numeric metric columns "
                  "(- = standard input)")
      ->required();
  cmd->add_option("--metric", args->metrics,
                  "Metric column (repeatable; default error and confusion)")
      ->allow_extra_args(false);
  cmd->add_option("--compare", args->compare,
                  "Contrast A - B of these two conditions, e.g. adaptive,random (default: the "
                  "first two conditions in sorted order)");
  cmd->add_flag("--trend", args->trend, "Iteration as a linear trend instead of a factor");
  cmd->add_flag("--random-slope", args->random_slope,
                "With --trend: a random slope per participant, (1 + iteration | participant)");
  cmd->add_flag("--exposure", args->exposure,
                "Fit metric ~ strategy * exposure + (1 | participant), exposure = earlier trials "
                "of the same strategy; report the slope per strategy");
  cmd->add_option("--ddf", args->ddf,
                  "Denominator df of the F tests and contrasts: satterthwaite (lmerTest's default) "
                  "or kenward-roger (pbkrtest: adjusted covariance and scaled F)")
      ->capture_default_str();
  cmd->add_flag("--emmeans", args->emmeans,
                "Estimated marginal means with intervals: condition x iteration cells, conditions, "
                "iterations (as emmeans)");
  cmd->add_option("--contrasts", args->contrasts,
                  "emmeans contrasts (repeatable): pairwise (all pairs of conditions, of "
                  "iterations), simple (condition at each iteration, iteration within each "
                  "condition), poly (polynomial trends over iterations, overall and per condition)")
      ->allow_extra_args(false);
  cmd->add_option("--adjust", args->adjust,
                  "Adjustment of the --contrasts within each family: tukey, holm (Bonferroni "
                  "intervals) or none (default: tukey for pairwise/simple, none for poly)");
  add_scores_column_options(*cmd, args->columns);
  cmd->add_option("--strategy-column", args->strategy_column,
                  "Name of the strategy column (--exposure)")
      ->capture_default_str();
  add_report_options(*cmd, args->report, {.tests = true, .presentation = true});
  cmd->callback([args] { run_model(*args); });
}

}  // namespace feint::cli

// feint anova SCORES.csv: the mixed ANOVA (condition between x iteration within) of each metric,
// as afex::aov_ez (see docs/anova-power.md).
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "feint/error.hpp"
#include "feint/io/scores.hpp"
#include "feint/report/anova_render.hpp"
#include "report_options.hpp"

namespace feint::cli {

namespace {

struct AnovaArgs {
  std::string input;
  std::vector<std::string> metrics;
  std::string correction = "GG";
  bool apa = false;
  bool drop_empty_conditions = false;
  bool emmeans = false;
  std::vector<std::string> contrasts;
  std::string adjust;
  io::ScoresOptions columns;  // --participant-column, --iteration-column, --condition-column
  ReportOptions report;
};

void run_anova(const AnovaArgs& a) {
  const ResolvedReportOptions r = resolve_report_options(a.report);
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
  report::AnovaEmmOptions emm;
  emm.emmeans = a.emmeans;
  emm.conf_level = r.test.conf_level;
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
      if (std::find(emm.families.begin(), emm.families.end(), f) == emm.families.end())
        emm.families.push_back(f);
  }
  if (!a.adjust.empty()) {
    if (a.contrasts.empty()) throw UsageError("--adjust applies to --contrasts");
    emm.adjust = models::parse_emm_adjust(a.adjust);
    if (*emm.adjust == models::EmmAdjust::tukey &&
        std::find(a.contrasts.begin(), a.contrasts.end(), "poly") != a.contrasts.end())
      throw UsageError("--adjust tukey applies to pairwise and simple contrasts, not to poly");
  }
  const io::ScoresTable scores = io::load_scores(a.input, so);
  const report::AnovaReport report =
      report::build_anova_report(scores, correction, a.drop_empty_conditions, emm);
  write_report(r.output, report::render_anova(report, r.format, a.apa, r.presentation));
}

}  // namespace

void add_anova_command(CLI::App& app) {
  auto args = std::make_shared<AnovaArgs>();
  auto* cmd = app.add_subcommand(
      "anova",
      "Mixed ANOVA per metric: condition (between) x iteration (within), as afex::aov_ez - "
      "type-III "
      "F tests, Mauchly's test, Greenhouse-Geisser/Huynh-Feldt corrections, generalized eta "
      "squared. One condition: one-way repeated-measures ANOVA.");
  cmd->add_option("SCORES", args->input,
                  "Scores CSV: participant, iteration, optional condition, numeric metric columns "
                  "(- = standard input)")
      ->required();
  cmd->add_option("--metric", args->metrics,
                  "Metric column to analyse (repeatable; default error and confusion)")
      ->allow_extra_args(false);
  cmd->add_option("--correction", args->correction,
                  "Sphericity correction of the within-participant df: GG (default, as afex), HF "
                  "or none")
      ->capture_default_str();
  cmd->add_flag("--apa", args->apa,
                "Add an APA string per effect, e.g. 'F(1.93, 112.1) = 4.31, p = .017, ηG² = .031'");
  cmd->add_flag("--drop-empty-conditions", args->drop_empty_conditions,
                "When every participant of a condition has a missing value, analyse the other "
                "condition(s) (one left: the one-way repeated-measures ANOVA) instead of stopping");
  cmd->add_flag("--emmeans", args->emmeans,
                "Estimated marginal means (cells, conditions, iterations) as emmeans on the afex "
                "object (multivariate model, df = N - a)");
  cmd->add_option("--contrasts", args->contrasts,
                  "emmeans contrasts (repeatable): pairwise, simple (condition at each iteration, "
                  "iteration within each condition) or poly (polynomial trends over iterations)")
      ->allow_extra_args(false);
  cmd->add_option("--adjust", args->adjust,
                  "Adjustment of the --contrasts within each family: tukey, holm or none "
                  "(default: tukey for pairwise/simple, none for poly)");
  add_scores_column_options(*cmd, args->columns);
  add_report_options(*cmd, args->report, {.tests = false, .presentation = true});
  cmd->callback([args] { run_anova(*args); });
}

}  // namespace feint::cli

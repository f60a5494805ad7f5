// feint plot INPUT --figure NAME -o FILE.pdf|.svg|.png: one of the study's figures from a scores
// file (or a questionnaire), for users who run `feint table` on its own (docs/figures.md).
#include <fmt/format.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "feint/error.hpp"
#include "feint/io/questionnaire.hpp"
#include "feint/io/scores.hpp"
#include "feint/plot/canvas.hpp"
#include "feint/plot/figures.hpp"
#include "feint/report/likert.hpp"
#include "feint/report/table1.hpp"
#include "report_options.hpp"

namespace feint::cli {

namespace {

struct PlotArgs {
  std::string input;
  std::string figure;
  std::string width = "one";
  // Scores figures (as feint table).
  std::vector<std::string> metrics;
  std::string compare;
  bool var_equal = false;
  bool paired = false;
  std::vector<std::string> logs;
  // Questionnaire figures (as feint likert).
  std::string scale = "1-7";
  std::optional<double> reference;
  std::vector<std::string> items;
  ReportOptions report;
};

constexpr std::string_view kFigures =
    "a metric column (error, confusion, ...), participants, strategies, traces, likert, "
    "likert-means";

plot::Figure build(const PlotArgs& a, const ResolvedReportOptions& r) {
  if (a.figure == "likert" || a.figure == "likert-means") {
    report::LikertSettings l;
    const auto [lo, hi] = io::parse_scale(a.scale);
    l.load.scale_min = lo;
    l.load.scale_max = hi;
    l.load.items = a.items;
    l.reference = a.reference;
    l.test = r.test;
    l.alpha = r.alpha;
    l.p_adjust = r.p_adjust;
    const report::LikertAnalysis analysis = report::analyze_likert_file(a.input, l);
    return a.figure == "likert" ? plot::likert_distribution_figure(analysis)
                                : plot::likert_means_figure(analysis);
  }
  if (a.figure == "strategies") {
    return plot::occurrence_figure(plot::strategy_occurrence(metrics::read_trial_labels(a.input)));
  }
  if (a.figure == "traces") {
    if (a.logs.empty()) {
      throw UsageError("--figure traces needs the pad-trace logs: --logs DIR (or files, globs)");
    }
    const auto curves = metrics::mean_traces(io::expand_inputs(a.logs), io::TraceOptions{},
                                          metrics::read_trial_labels(a.input), r.test.conf_level);
    if (curves.empty()) throw InvalidData("no trial of the logs appears in the scores file");
    return plot::traces_figure(curves, r.test.conf_level);
  }

  report::Table1Options t;
  t.metrics = parse_metric_specs(a.metrics);
  t.alpha = r.alpha;
  t.test = r.test;
  t.p_adjust = r.p_adjust;
  const std::string metric = a.figure == "participants" ? t.metrics.front().column : a.figure;
  bool known = false;
  for (const auto& m : t.metrics) known = known || m.column == metric;
  if (!known) {
    // `--figure confusion` without --metric: plot that metric with its default reference.
    if (!a.metrics.empty()) {
      throw UsageError(fmt::format("--figure '{}': not a metric given with --metric, nor one of {}",
                                   a.figure, kFigures));
    }
    t.metrics = {report::parse_metric_spec(metric)};
  }
  io::ScoresOptions so;
  so.metrics.clear();
  for (const auto& m : t.metrics) so.metrics.push_back(m.column);
  io::ScoresTable scores;
  try {
    scores = io::load_scores(a.input, so);
  } catch (const InvalidData& e) {
    if (known) throw;
    throw UsageError(
        fmt::format("--figure '{}': expected one of {} ({})", a.figure, kFigures, e.what()));
  }
  const report::Table1 one_sample = report::build_table1(scores, t);
  if (a.figure == "participants") return plot::participants_figure(scores, metric, &one_sample);
  std::optional<report::Table1> two_sample;
  if (!a.compare.empty()) {
    report::Table1Options c = t;
    c.compare = parse_compare(a.compare);
    c.var_equal = a.var_equal;
    c.paired = a.paired;
    two_sample = report::build_table1(scores, c);
  }
  return plot::metric_figure(
      plot::metric_figure_data(one_sample, two_sample ? &*two_sample : nullptr, metric));
}

void run(const PlotArgs& a) {
  const ResolvedReportOptions r = resolve_report_options(a.report);
  if (r.output == "-") throw UsageError("-o FILE.pdf|.svg|.png is required (the figure's file)");
  const plot::FileFormat format = plot::format_from_path(r.output);
  const plot::Width width = plot::parse_width(a.width);
  const plot::Figure figure = build(a, r);
  write_report(r.output, plot::render(figure, width, format));
}

}  // namespace

void add_plot_command(CLI::App& app) {
  auto args = std::make_shared<PlotArgs>();
  auto* cmd = app.add_subcommand(
      "plot",
      "Draw one of the study's figures from a scores file (feint score's output) or a "
      "questionnaire, as PDF, SVG or PNG (by the output's extension); see docs/figures.md.");
  cmd->add_option("INPUT", args->input,
                  "Scores CSV (metric, participants, strategies, traces) or questionnaire CSV "
                  "(likert, likert-means)")
      ->required();
  cmd->add_option("--figure", args->figure,
                  "Which figure: a metric column (the mean per iteration and condition with its "
                  "CI; error, confusion, ...), participants, strategies, traces, likert "
                  "(diverging bars), likert-means")
      ->required();
  cmd->add_option("--width", args->width,
                  "one (one-column paper, 3.5 in) or two (two-column, 7.16 in); text is 8 pt in "
                  "both")
      ->capture_default_str();
  auto* scores = "Scores figures (as feint table)";
  cmd->add_option("--metric", args->metrics,
                  "NAME=REF: metric column and reference mean (repeatable; default error=0.5 "
                  "confusion=0.95)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false)
      ->group(scores);
  cmd->add_option("--compare", args->compare,
                  "A,B: mark the iterations where condition A differs from B")
      ->group(scores);
  cmd->add_flag("--var-equal", args->var_equal, "Student's t instead of Welch's (--compare)")
      ->group(scores);
  cmd->add_flag("--paired", args->paired, "Paired t, pairs matched by participant (--compare)")
      ->group(scores);
  cmd->add_option("--logs", args->logs,
                  "Pad-trace logs (files, folders, globs) for --figure traces")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false)
      ->group(scores);
  auto* likert = "Questionnaire figures (as feint likert)";
  cmd->add_option("--scale", args->scale, "Scale bounds MIN-MAX")
      ->capture_default_str()
      ->group(likert);
  cmd->add_option("--reference", args->reference,
                  "Reference of the one-sample tests (default: the scale midpoint)")
      ->group(likert);
  cmd->add_option("--items", args->items, "Item columns (default: every other column)")
      ->delimiter(',')
      ->group(likert);
  add_report_options(*cmd, args->report);
  // The figure's format comes from the output's extension; --format is the tables' option.
  cmd->remove_option(cmd->get_option("--format"));
  cmd->get_option("--output")->description("Output figure: FILE.pdf, FILE.svg or FILE.png");
  cmd->callback([args] { run(*args); });
}

}  // namespace feint::cli

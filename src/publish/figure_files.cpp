// One figure from a scores file or a questionnaire (see feint/publish/figure_files.hpp).
#include "feint/publish/figure_files.hpp"

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/questionnaire.hpp"
#include "feint/io/scores.hpp"
#include "feint/io/trace.hpp"
#include "feint/plot/figures.hpp"
#include "feint/tables/likert.hpp"
#include "feint/tables/table1.hpp"

namespace feint::publish {

namespace {

constexpr std::string_view kFigures =
    "a metric column (error, confusion, ...), participants, strategies, traces, likert, "
    "likert-means";

}  // namespace

plot::Figure figure_from_files(const FigureRequest& a, const analysis::ResolvedReportOptions& r) {
  if (a.figure == "likert" || a.figure == "likert-means") {
    tables::LikertSettings l;
    const auto [lo, hi] = io::parse_scale(a.scale);
    l.load.scale_min = lo;
    l.load.scale_max = hi;
    l.load.items = a.items;
    l.reference = a.reference;
    l.test = r.test;
    l.alpha = r.alpha;
    l.p_adjust = r.p_adjust;
    const tables::LikertAnalysis analysis = tables::analyze_likert_file(a.input, l);
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

  tables::Table1Options t;
  t.metrics = analysis::parse_metric_specs(a.metrics);
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
    t.metrics = {tables::parse_metric_spec(metric)};
  }
  io::ScoresOptions so;
  so.metrics.clear();
  for (const auto& m : t.metrics) so.metrics.push_back(m.column);
  if (!a.compare.empty()) {
    // A comparison of two conditions never pools a scores file without its condition column.
    const auto ab = analysis::parse_compare(a.compare);
    so.expected_conditions = {ab.first, ab.second};
  }
  io::ScoresTable scores;
  try {
    scores = io::load_scores(a.input, so);
  } catch (const InvalidData& e) {
    if (known) throw;
    throw UsageError(
        fmt::format("--figure '{}': expected one of {} ({})", a.figure, kFigures, e.what()));
  }
  const tables::Table1 one_sample = tables::build_table1(scores, t);
  if (a.figure == "participants") return plot::participants_figure(scores, metric, &one_sample);
  std::optional<tables::Table1> two_sample;
  if (!a.compare.empty()) {
    tables::Table1Options c = t;
    c.compare = analysis::parse_compare(a.compare);
    c.var_equal = a.var_equal;
    c.paired = a.paired;
    two_sample = tables::build_table1(scores, c);
  }
  return plot::metric_figure(
      plot::metric_figure_data(one_sample, two_sample ? &*two_sample : nullptr, metric));
}

}  // namespace feint::publish

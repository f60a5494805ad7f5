// feint plot INPUT --figure NAME -o FILE.pdf|.svg|.png: one of the study's figures from a scores
// file (or a questionnaire), for users who run `feint table` on its own (docs/figures.md).

#include <memory>

#include "commands.hpp"
#include "feint/error.hpp"
#include "feint/plot/canvas.hpp"
#include "feint/plot/figures.hpp"
#include "feint/publish/figure_files.hpp"
#include "options.hpp"

namespace feint::cli {

namespace {

struct PlotArgs {
  publish::FigureRequest request;
  std::string width = "one";
  ReportOptions report;
};

void run(const PlotArgs& a) {
  if (a.report.apa) {
    throw UsageError(
        "--apa: a figure has no APA strings; use feint table --apa (or feint "
        "analyze --apa) for the numbers");
  }
  const ResolvedReportOptions r = resolve_report_options(a.report);
  if (r.output == "-") throw UsageError("-o FILE.pdf|.svg|.png is required (the figure's file)");
  const plot::FileFormat format = plot::format_from_path(r.output);
  const plot::Width width = plot::parse_width(a.width);
  const plot::Figure figure = publish::figure_from_files(a.request, r);
  write_report(r.output, plot::render(figure, width, format));
}

}  // namespace

void add_plot_command(CLI::App& app) {
  auto args = std::make_shared<PlotArgs>();
  auto* cmd = app.add_subcommand(
      "plot",
      "Draw one of the study's figures from a scores file (feint score's output) or a "
      "questionnaire, as PDF, SVG or PNG (by the output's extension); see docs/figures.md.");
  cmd->add_option("INPUT", args->request.input,
                  "Scores CSV (metric, participants, strategies, traces) or questionnaire CSV "
                  "(likert, likert-means)")
      ->required();
  cmd->add_option("--figure", args->request.figure,
                  "Which figure: a metric column (the mean per iteration and condition with its "
                  "CI; error, confusion, ...), participants, strategies, traces, likert "
                  "(diverging bars), likert-means")
      ->required();
  cmd->add_option("--width", args->width,
                  "one (one-column paper, 3.5 in) or two (two-column, 7.16 in); text is 8 pt in "
                  "both")
      ->capture_default_str();
  cmd->option_defaults()->group("Scores figures (as feint table)");
  one_per_use(cmd->add_option("--metric", args->request.metrics,
                              "NAME=REF: metric column and reference mean (repeatable; default "
                              "error=0.5 confusion=0.95@raw)"));
  cmd->add_option("--compare", args->request.compare,
                  "A,B: mark the iterations where condition A differs from B");
  cmd->add_flag("--var-equal", args->request.var_equal,
                "Student's t instead of Welch's (--compare)");
  cmd->add_flag("--paired", args->request.paired,
                "Paired t, pairs matched by participant (--compare)");
  one_per_use(cmd->add_option("--logs", args->request.logs,
                              "Pad-trace logs (files, folders, globs) for --figure traces"));
  cmd->option_defaults()->group("Questionnaire figures (as feint likert)");
  cmd->add_option("--scale", args->request.scale, "Scale bounds MIN-MAX")->capture_default_str();
  cmd->add_option("--reference", args->request.reference,
                  "Reference of the one-sample tests (default: the scale midpoint)");
  cmd->add_option("--items", args->request.items, "Item columns (default: every other column)")
      ->delimiter(',');
  cmd->option_defaults()->group("Options");
  add_report_options(*cmd, args->report);
  // The figure's format comes from the output's extension; --format is the tables' option.
  cmd->remove_option(cmd->get_option("--format"));
  // -o is required (there is no figure on standard output): its help shows no default.
  cmd->get_option("--output")
      ->description("Output figure: FILE.pdf, FILE.svg or FILE.png (required)")
      ->default_str("")
      ->required();
  // A figure has no APA string: --apa is refused rather than silently ignored.
  cmd->get_option("--apa")->description(
      "Not for figures (refused): APA strings are in feint table --apa and feint analyze --apa");
  cmd->callback([args] { run(*args); });
}

}  // namespace feint::cli

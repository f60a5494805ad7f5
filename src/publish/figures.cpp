// The study's figures, drawn from the results' data (see feint/publish/study_report.hpp).
#include <fmt/format.h>

#include <cctype>
#include <filesystem>

#include "feint/error.hpp"
#include "feint/io/output.hpp"
#include "feint/plot/canvas.hpp"
#include "feint/plot/figures.hpp"
#include "feint/publish/study_report.hpp"
#include "feint/stats/p_adjust.hpp"

namespace feint::publish {

namespace {

namespace fs = std::filesystem;

class FigureWriter {
 public:
  FigureWriter(const std::vector<std::string>& formats, const std::string& folder) {
    for (const auto& f : formats) formats_.push_back(plot::parse_file_format(f));
    dir_ = fs::path(folder) / "figures";
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec) throw IoError(fmt::format("cannot create folder '{}': {}", dir_.string(), ec.message()));
  }

  void add(const std::string& name, const std::string& title, const std::string& alt,
           const std::string& caption, const plot::Figure& figure) {
    RenderedFigure d{name, title, caption, alt, {}, {}};
    for (const auto width : {plot::Width::one_column, plot::Width::two_column}) {
      const char* suffix = width == plot::Width::one_column ? "-1col" : "-2col";
      std::string svg;
      for (const auto format : formats_) {
        std::string bytes = plot::render(figure, width, format);
        const std::string file = fmt::format("{}{}.{}", name, suffix, plot::extension(format));
        io::write_file_atomically((dir_ / file).string(), bytes);
        out.written.push_back((dir_ / file).string());
        d.files.push_back("figures/" + file);
        if (format == plot::FileFormat::svg) svg = std::move(bytes);
      }
      if (width == plot::Width::two_column) {
        d.svg = svg.empty() ? plot::render(figure, width, plot::FileFormat::svg) : svg;
      }
    }
    out.figures.push_back(std::move(d));
  }

  DrawnFigures out;

 private:
  std::vector<plot::FileFormat> formats_;
  fs::path dir_;
};

std::string capitalised(std::string s) {
  if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  return s;
}

std::string adjustment_words(stats::PAdjustMethod m) {
  return m == stats::PAdjustMethod::none
             ? "not adjusted for multiple comparisons"
             : fmt::format("adjusted with {} within each metric", stats::to_string(m));
}

}  // namespace

DrawnFigures draw_figures(const analysis::StudyResults& r, const std::vector<std::string>& formats,
                          const std::string& folder) {
  for (const auto& f : formats) plot::parse_file_format(f);  // UsageError before any work
  FigureWriter w(formats, folder);
  const report::Table1& t = r.table1;
  const report::Table1* comparison = r.comparison ? &*r.comparison : nullptr;
  const std::string level = fmt::format("{:g}%", t.options.test.conf_level * 100);
  for (const auto& m : t.options.metrics) {
    const plot::MetricFigureData d = plot::metric_figure_data(t, comparison, m.column);
    std::string caption = fmt::format(
        "Mean {} per iteration and condition with its {} confidence interval (the one-sample "
        "t-tests of Table 1), against the reference R = {:g} (dashed; an arrow at the edge when "
        "far from the data). Filled markers: the mean "
        "differs from R (p < {:g}, {}); hollow: no difference found.",
        m.column, level, m.reference, t.options.alpha, adjustment_words(t.options.p_adjust));
    if (comparison != nullptr) {
      caption += fmt::format(
          " *: the iterations where {} and {} differ (the comparison table, same alpha and "
          "adjustment): {}.",
          d.group1, d.group2,
          d.marked.empty() ? std::string("none") : fmt::format("{}", fmt::join(d.marked, ", ")));
    }
    w.add(m.column, fmt::format("Mean {} per iteration", m.column),
          fmt::format("Line chart: mean {} per iteration for each condition, with confidence "
                      "bands, against the reference {:g}.",
                      m.column, m.reference),
          caption, plot::metric_figure(d));
  }
  for (const auto& m : t.options.metrics) {
    w.add("participants-" + m.column, capitalised(m.column) + " of each participant",
          fmt::format("Line chart, one panel per condition: each participant's {} over the "
                      "iterations as faint lines, the condition mean with its band on top.",
                      m.column),
          fmt::format("Each participant's {} over the iterations (faint lines), one panel per "
                      "condition, with the condition's mean and its interval from Table 1 (thick "
                      "line and band). A participant who stopped playing or an outlier stands out.",
                      m.column),
          plot::participants_figure(r.scores, m.column, &t));
  }
  if (!r.figures.labels_note.empty()) {
    w.out.notes.push_back(fmt::format("No strategy figures: {}", r.figures.labels_note));
  }
  if (!r.figures.labels.empty()) {
    w.add("strategies", "Strategies shown",
          "Bar chart per condition: the share of participants who saw each strategy at each "
          "iteration.",
          "Share of participants who saw each strategy, per iteration and condition (the logs' "
          "strategy column, as scored). The paper's Fig. 5/7 show the selection algorithms' "
          "expectation; this is what the study's participants actually saw.",
          plot::occurrence_figure(plot::strategy_occurrence(r.figures.labels)));
    if (r.figures.traces.empty()) {
      w.out.notes.push_back("No trace figure: no scored trial was found again in the logs.");
    } else {
      w.add("traces", "Pad traces per strategy",
            "Line chart per strategy: the mean pad position over normalised time, first "
            "exposure against later exposures, with confidence bands.",
            fmt::format("Mean pad position over normalised time (0 = first sample, 1 = last) "
                        "per strategy and version, mirrored so that the true target is at 1 "
                        "(1 - |pad - target|), with {} t intervals; first exposure of a "
                        "participant to that strategy and version against later exposures (n = "
                        "trials, first / later). 0.5 is the undecided middle.",
                        level),
            plot::traces_figure(r.figures.traces, t.options.test.conf_level));
    }
  }
  if (r.likert) {
    const report::LikertAnalysis& l = *r.likert;
    w.add("likert", "Questionnaire answers",
          "Diverging stacked bar chart: the answers to each questionnaire item per condition, "
          "disagreement to the left and agreement to the right of the neutral point.",
          fmt::format("Answers per item and condition as diverging stacked bars centred on the "
                      "neutral point {:g}: disagreement to the left, agreement to the right; "
                      "bar lengths are percentages of the respondents (n).",
                      l.neutral),
          plot::likert_distribution_figure(l));
    w.add("likert-means", "Questionnaire means",
          fmt::format("Dot chart: the mean rating of each item per condition with its confidence "
                      "interval, against the reference {:g}.",
                      l.reference),
          fmt::format("Mean rating per item and condition with its {:g}% t interval, against "
                      "the reference R = {:g} (the paper's Fig. 11). Filled markers: the "
                      "one-sample t-test differs from R (p < {:g}, {}); the Wilcoxon "
                      "signed-rank test is the primary analysis (table below).",
                      l.settings.test.conf_level * 100, l.reference, l.settings.alpha,
                      adjustment_words(l.settings.p_adjust)),
          plot::likert_means_figure(l));
  }
  return std::move(w.out);
}

}  // namespace feint::publish

// The study's figures, drawn from the results' data (see feint/publish/study_report.hpp).
#include <fmt/format.h>

#include <cctype>
#include <filesystem>

#include "feint/error.hpp"
#include "feint/io/output.hpp"
#include "feint/plot/canvas.hpp"
#include "feint/plot/figures.hpp"
#include "feint/plot/map_figure.hpp"
#include "feint/publish/study_report.hpp"
#include "feint/stats/p_adjust.hpp"
#include "report_details.hpp"

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
      std::string& page = width == plot::Width::two_column ? d.svg : d.svg_narrow;
      page = svg.empty() ? plot::render(figure, width, plot::FileFormat::svg) : std::move(svg);
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

// The comparison's table (the iterations where the conditions differ), if the study has one.
const tables::Table1* comparison_of(const analysis::StudyResults& r) {
  return r.comparison ? &*r.comparison : nullptr;
}

// Per metric: the means per iteration against the reference (Table 1's tests).
void add_metric_figures(FigureWriter& w, const analysis::StudyResults& r,
                        const std::string& level) {
  const tables::Table1& t = r.table1;
  const tables::Table1* comparison = comparison_of(r);
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
    w.add(m.column, fmt::format("Mean {} per iteration", m.column), plot::alt_text(d), caption,
          plot::metric_figure(d));
  }
}

// Per metric: every participant's line under their condition's mean.
void add_participant_figures(FigureWriter& w, const analysis::StudyResults& r) {
  const tables::Table1& t = r.table1;
  for (const auto& m : t.options.metrics) {
    const plot::ParticipantsData pd = plot::participants_data(r.scores, m.column, &t);
    w.add("participants-" + m.column, capitalised(m.column) + " of each participant",
          plot::alt_text(pd),
          fmt::format("Each participant's {} over the iterations (faint lines), one panel per "
                      "condition, with the condition's mean and its interval from Table 1 (thick "
                      "line and band). A participant who stopped playing or an outlier stands out.",
                      m.column),
          plot::participants_figure(pd));
  }
}

// The mixed model's fitted trend over the per-iteration means (the trend F-test's line).
void add_model_trend_figures(FigureWriter& w, const analysis::StudyResults& r,
                             const std::string& level) {
  for (const auto& mt : r.figures.model_trends) {
    plot::ModelFitFigureData md{plot::metric_figure_data(r.table1, comparison_of(r), mt.metric),
                                mt.trend, mt.model};
    w.add("model-" + mt.metric, fmt::format("Mixed model's fitted trend of {}", mt.metric),
          plot::alt_text(md),
          fmt::format("The mixed model's fitted {} per condition and iteration (lines, {} "
                      "confidence band from Satterthwaite's df, as emmeans) over the observed "
                      "per-iteration means with their {} t intervals (markers; Table 1). Model: "
                      "{} ~ condition * iteration, {} (the table \"Mixed model (linear trend "
                      "over the iterations)\"). Where the means leave the band, a straight line "
                      "does not describe the iterations.",
                      mt.metric, level, level, mt.metric, mt.model),
          plot::model_fit_figure(md));
  }
}

// The exposure figure's caption, with the scored trials it left out for want of a label.
// The seed paper is cited only for a study of its design (detail::paper_design); another design is
// described as it is.
std::string exposure_caption(const metrics::ExposureTrend& e, const std::string& level, bool paper) {
  const std::string unmatched =
      e.unmatched > 0 ? fmt::format(" {} without a strategy label left out.",
                                    e.unmatched == 1 ? std::string("1 scored trial")
                                                     : fmt::format("{} scored trials", e.unmatched))
                      : std::string();
  return fmt::format(
      "Mean {} against the exposure (1 = the participant's first trial with that "
      "strategy, 2 = the second, ...), one panel per strategy, per condition, with "
      "{} t intervals (at exposures with at least 5 trials), and each condition's "
      "least-squares line with its {} band from participant-clustered (CR1) standard "
      "errors. A strategy that wears off rises (error) as it is seen again{}. "
      "Descriptive: the mixed model is the inference.{}",
      e.metric, level, level,
      paper ? "; the paper's claim is that it wears off under the random algorithm and not under the "
              "adaptive one"
            : "",
      unmatched);
}

// The figures of the trials' strategy labels: which strategies were shown, each metric against
// the exposure, and the pad traces (or a note why there are none).
void add_strategy_figures(FigureWriter& w, const analysis::StudyResults& r,
                          const std::string& level) {
  const double conf_level = r.table1.options.test.conf_level;
  const bool paper = detail::paper_design(r);
  const plot::Occurrence occurrence = plot::strategy_occurrence(r.figures.labels);
  w.add("strategies", "Strategies shown", plot::alt_text(occurrence),
        std::string("Share of participants who saw each strategy, per iteration and condition (the logs' "
                    "strategy column, as scored). ") +
            (paper ? "The paper's Fig. 5/7 show the selection algorithms' expectation; this is what the "
                     "study's participants actually saw."
                   : "This is what the study's participants actually saw, not what a selection "
                     "algorithm expects."),
        plot::occurrence_figure(occurrence));
  for (const auto& e : r.figures.exposure) {
    w.add("exposure-" + e.metric,
          fmt::format("{} by exposure to the strategy, per condition", capitalised(e.metric)),
          plot::alt_text(e), exposure_caption(e, level, paper), plot::exposure_figure(e));
  }
  if (r.figures.traces.empty()) {
    w.out.notes.push_back(r.figures.map ? "No pad-trace figure: the participants pointed on a map (no pad); the map "
                                          "figure shows their mean pointer."
                                        : "No trace figure: no scored trial was found again in the logs.");
    return;
  }
  w.add("traces", "Pad traces per strategy",
        plot::alt_text(plot::TracesFigureData{r.figures.traces, conf_level}),
        fmt::format("Mean pad position over normalised time (0 = first sample, 1 = last) "
                    "per strategy and version, mirrored so that the true target is at 1 "
                    "(1 - |pad - target|), with {} t intervals; first exposure of a "
                    "participant to that strategy and version against later exposures (n = "
                    "trials, first / later). 0.5 is the undecided middle.",
                    level),
        plot::traces_figure(r.figures.traces, conf_level));
}

// Logs of K targets and a pointer: the map (targets, mean robot paths and pointers per strategy),
// drawn from the analysis' data (FigureData::map). Pad logs have no map: nothing is said about them.
void add_map_figure(FigureWriter& w, const analysis::FigureData& f) {
  if (!f.map_note.empty()) w.out.notes.push_back(fmt::format("No map figure: {}", f.map_note));
  if (!f.map) return;
  w.add("map", "Robot paths and pointers on the map, per strategy", plot::alt_text(*f.map),
        plot::map_caption(*f.map), plot::map_figure(*f.map));
}

// The questionnaire: the answers' distribution and the means against the reference.
void add_likert_figures(FigureWriter& w, const tables::LikertAnalysis& l, bool paper) {
  const plot::LikertDistribution ld = plot::likert_distribution_data(l);
  w.add("likert", "Questionnaire answers", plot::alt_text(ld),
        fmt::format("Answers per item and condition as diverging stacked bars centred on the "
                    "neutral point {:g}: disagreement to the left, agreement to the right; "
                    "bar lengths are percentages of the respondents (n).",
                    l.neutral),
        plot::likert_distribution_figure(ld));
  const plot::LikertMeansData lm = plot::likert_means_data(l);
  w.add("likert-means", "Questionnaire means", plot::alt_text(lm),
        fmt::format("Mean rating per item and condition with its {:g}% t interval, against "
                    "the reference R = {:g}{}. Filled markers: the "
                    "one-sample t-test differs from R (p < {:g}, {}); the Wilcoxon "
                    "signed-rank test is the primary analysis (table below).",
                    l.settings.test.conf_level * 100, l.reference, paper ? " (the paper's Fig. 11)" : "",
                    l.settings.alpha,
                    adjustment_words(l.settings.p_adjust)),
        plot::likert_means_figure(lm));
}

}  // namespace

DrawnFigures draw_figures(const analysis::StudyResults& r, const std::vector<std::string>& formats,
                          const std::string& folder) {
  for (const auto& f : formats) plot::parse_file_format(f);  // UsageError before any work
  FigureWriter w(formats, folder);
  const std::string level = fmt::format("{:g}%", r.table1.options.test.conf_level * 100);
  add_metric_figures(w, r, level);
  add_participant_figures(w, r);
  add_model_trend_figures(w, r, level);
  if (!r.figures.labels_note.empty()) {
    w.out.notes.push_back(fmt::format("No strategy figures: {}", r.figures.labels_note));
  }
  if (!r.figures.labels.empty()) add_strategy_figures(w, r, level);
  add_map_figure(w, r.figures);
  if (r.likert) add_likert_figures(w, *r.likert, detail::paper_design(r));
  return std::move(w.out);
}

}  // namespace feint::publish

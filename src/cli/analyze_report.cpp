// The figures and report.html of `feint analyze` (see analyze_report.hpp, docs/figures.md).
#include "analyze_report.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "feint/error.hpp"
#include "feint/io/html_escape.hpp"
#include "feint/io/output.hpp"
#include "feint/plot/canvas.hpp"
#include "feint/plot/figures.hpp"
#include "feint/plot/html.hpp"
#include "feint/report/writers.hpp"

namespace feint::cli {

namespace {

namespace fs = std::filesystem;
using io::html_escape;

struct DrawnFigure {
  std::string name;                // file stem
  std::string title;               // heading in the report
  std::string caption;             // plain text
  std::string svg;                 // two-column SVG, for the page
  std::vector<std::string> files;  // relative to OUT
};

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The command line that ran, as the kernel recorded it (Linux).
std::string command_line() {
  const std::string raw = read_all("/proc/self/cmdline");
  std::string out;
  std::size_t start = 0;
  while (start < raw.size()) {
    std::size_t end = raw.find('\0', start);
    if (end == std::string::npos) end = raw.size();
    std::string arg = raw.substr(start, end - start);
    if (start == 0) arg = fs::path(arg).filename().string();
    const bool plain =
        !arg.empty() && arg.find_first_of(" \t\"'$\\;&|<>*?()[]{}`") == std::string::npos;
    if (!out.empty()) out += ' ';
    out += plain ? arg : "'" + arg + "'";
    start = end + 1;
  }
  return out;
}

std::string facts(const std::vector<std::pair<std::string, std::string>>& rows) {
  std::string o = "<dl class=\"facts\">\n";
  for (const auto& [k, v] : rows) {
    o += fmt::format("<dt>{}</dt><dd>{}</dd>\n", html_escape(k), html_escape(v));
  }
  return o + "</dl>\n";
}

class FigureWriter {
 public:
  FigureWriter(const AnalyzeContext& c, const FigureOptions& o) {
    for (const auto& f : o.formats) formats_.push_back(plot::parse_file_format(f));
    dir_ = fs::path(c.out) / "figures";
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec) {
      throw IoError(fmt::format("cannot create folder '{}': {}", dir_.string(), ec.message()));
    }
  }

  void add(const std::string& name, const std::string& title, const std::string& caption,
           const plot::Figure& figure) {
    DrawnFigure d{name, title, caption, {}, {}};
    for (const auto width : {plot::Width::one_column, plot::Width::two_column}) {
      const char* suffix = width == plot::Width::one_column ? "-1col" : "-2col";
      std::string svg;
      for (const auto format : formats_) {
        std::string bytes = plot::render(figure, width, format);
        const std::string file = fmt::format("{}{}.{}", name, suffix, plot::extension(format));
        io::write_file_atomically((dir_ / file).string(), bytes);
        written_.push_back((dir_ / file).string());
        d.files.push_back("figures/" + file);
        if (format == plot::FileFormat::svg) svg = std::move(bytes);
      }
      if (width == plot::Width::two_column) {
        d.svg = svg.empty() ? plot::render(figure, width, plot::FileFormat::svg) : svg;
      }
    }
    figures_.push_back(std::move(d));
  }

  std::vector<DrawnFigure>& figures() { return figures_; }
  std::vector<std::string>& written() { return written_; }

 private:
  std::vector<plot::FileFormat> formats_;
  fs::path dir_;
  std::vector<DrawnFigure> figures_;
  std::vector<std::string> written_;
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

void draw_figures(const AnalyzeContext& c, FigureWriter& w, std::vector<std::string>& notes) {
  const report::Table1& t = *c.one_sample;
  const std::string level = fmt::format("{:g}%", t.options.test.conf_level * 100);
  for (const auto& m : t.options.metrics) {
    const plot::MetricFigureData d = plot::metric_figure_data(t, c.comparison, m.column);
    std::string caption = fmt::format(
        "Mean {} per iteration and condition with its {} confidence interval (the one-sample "
        "t-tests of Table 1), against the reference R = {:g} (dashed; an arrow at the edge when "
        "far from the data). Filled markers: the mean "
        "differs from R (p < {:g}, {}); hollow: no difference found.",
        m.column, level, m.reference, t.options.alpha, adjustment_words(t.options.p_adjust));
    if (c.comparison != nullptr) {
      caption += fmt::format(
          " *: the iterations where {} and {} differ (the comparison table, same alpha and "
          "adjustment): {}.",
          d.group1, d.group2,
          d.marked.empty() ? std::string("none") : fmt::format("{}", fmt::join(d.marked, ", ")));
    }
    w.add(m.column, fmt::format("Mean {} per iteration", m.column), caption,
          plot::metric_figure(d));
  }
  for (const auto& m : t.options.metrics) {
    w.add("participants-" + m.column, capitalised(m.column) + " of each participant",
          fmt::format("Each participant's {} over the iterations (faint lines), one panel per "
                      "condition, with the condition's mean and its interval from Table 1 (thick "
                      "line and band). A participant who stopped playing or an outlier stands out.",
                      m.column),
          plot::participants_figure(*c.scores, m.column, &t));
  }
  std::optional<std::vector<plot::TrialLabel>> labels;
  try {
    labels = metrics::read_trial_labels(c.scores_path);
  } catch (const InvalidData& e) {
    notes.push_back(fmt::format("No strategy figures: {}", e.what()));
  }
  if (labels) {
    w.add("strategies", "Strategies shown",
          "Share of participants who saw each strategy, per iteration and condition (the logs' "
          "strategy column, as scored). The paper's Fig. 5/7 show the selection algorithms' "
          "expectation; this is what the study's participants actually saw.",
          plot::occurrence_figure(plot::strategy_occurrence(*labels)));
    io::TraceOptions topt;
    topt.column_map = c.scoring->column_map;
    topt.delimiter = c.scoring->delimiter;
    topt.unsorted = c.scoring->unsorted;
    const auto curves =
        metrics::mean_traces(io::expand_inputs(c.logs), topt, *labels, t.options.test.conf_level);
    if (curves.empty()) {
      notes.push_back("No trace figure: no scored trial was found again in the logs.");
    } else {
      w.add("traces", "Pad traces per strategy",
            fmt::format("Mean pad position over normalised time (0 = first sample, 1 = last) "
                        "per strategy and version, mirrored so that the true target is at 1 "
                        "(1 - |pad - target|), with {} t intervals; first exposure of a "
                        "participant to that strategy and version against later exposures (n = "
                        "trials, first / later). 0.5 is the undecided middle.",
                        level),
            plot::traces_figure(curves, t.options.test.conf_level));
    }
  }
  if (c.likert != nullptr) {
    const report::LikertAnalysis& l = *c.likert;
    w.add("likert", "Questionnaire answers",
          fmt::format("Answers per item and condition as diverging stacked bars centred on the "
                      "neutral point {:g}: disagreement to the left, agreement to the right; "
                      "bar lengths are percentages of the respondents (n).",
                      l.neutral),
          plot::likert_distribution_figure(l));
    w.add("likert-means", "Questionnaire means",
          fmt::format("Mean rating per item and condition with its {:g}% t interval, against "
                      "the reference R = {:g} (the paper's Fig. 11). Filled markers: the "
                      "one-sample t-test differs from R (p < {:g}, {}); the Wilcoxon "
                      "signed-rank test is the primary analysis (table below).",
                      l.settings.test.conf_level * 100, l.reference, l.settings.alpha,
                      adjustment_words(l.settings.p_adjust)),
          plot::likert_means_figure(l));
  }
}

std::string figure_html(const DrawnFigure& d, std::size_t index) {
  std::string links;
  for (const auto& f : d.files) {
    if (!links.empty()) links += ", ";
    links += fmt::format("<a href=\"{0}\">{1}</a>", html_escape(f),
                         html_escape(fs::path(f).filename().string()));
  }
  return fmt::format(
      "<figure id=\"fig-{0}\">\n{1}\n<figcaption><strong>Figure {2}. {3}.</strong> {4}{5}"
      "</figcaption>\n</figure>\n",
      html_escape(d.name), plot::inline_svg(d.svg, fmt::format("f{}-", index), d.title), index,
      html_escape(d.title), html_escape(d.caption),
      links.empty() ? "" : "<br><span class=\"files\">Files: " + links + "</span>");
}

std::string design_html(const AnalyzeContext& c) {
  const io::ScoresTable& s = *c.scores;
  std::map<std::string, std::set<std::string>> participants;
  for (const auto& r : s.records) participants[r.condition].insert(r.participant);
  std::vector<std::string> per_condition;
  for (const auto& cond : s.conditions()) {
    per_condition.push_back(fmt::format("{} ({} participants)", cond.empty() ? "(none)" : cond,
                                        participants[cond].size()));
  }
  const auto its = s.iterations();
  std::vector<std::pair<std::string, std::string>> rows = {
      {"Study folder", c.study},
      {"Conditions", fmt::format("{}", fmt::join(per_condition, ", "))},
      {"Iterations",
       its.empty() ? "none" : fmt::format("{} ({} to {})", its.size(), its.front(), its.back())},
      {"Metrics and references", ""},
      {"Comparison", c.comparison != nullptr
                         ? fmt::format("{} against {}", c.comparison->blocks.front().group1,
                                       c.comparison->blocks.front().group2)
                         : "none (set compare = \"A,B\")"},
      {"Questionnaire", c.questionnaire_path.empty() ? "none" : c.questionnaire_path},
      {"Settings file", c.config_path.empty() ? "none" : c.config_path},
  };
  std::vector<std::string> metrics;
  for (const auto& m : c.one_sample->options.metrics) {
    metrics.push_back(fmt::format("{} against {:g}", m.column, m.reference));
  }
  rows[3].second = fmt::format("{}", fmt::join(metrics, "; "));
  return facts(rows);
}

// Every setting: how the scores were made (the sidecar), the settings file, every option.
std::string settings_html(const AnalyzeContext& c) {
  std::string o;
  std::vector<std::pair<std::string, std::string>> scoring;
  for (const auto& [k, v] : c.one_sample->provenance.settings) {
    if (k.rfind("settings.", 0) == 0) scoring.emplace_back(k.substr(9), v);
  }
  if (!scoring.empty()) {
    o += "<h3>Scoring (from the scores' sidecar)</h3>\n" + facts(scoring);
  }
  if (!c.config_path.empty()) {
    o += fmt::format("<h3>{}</h3>\n<pre>{}</pre>\n", html_escape(c.config_path),
                     html_escape(read_all(c.config_path)));
  }
  if (c.command != nullptr) {
    o += "<h3>Every option of this run (feint.toml syntax)</h3>\n<pre>" +
         html_escape(c.command->config_to_str(true, false)) + "</pre>\n";
  }
  return o;
}

std::string accounting_html(const AnalyzeContext& c) {
  const metrics::ScoreSummary& s = *c.scored;
  std::vector<std::pair<std::string, std::string>> rows = {
      {"Log files read", std::to_string(s.files)},
      {"Rows read", std::to_string(s.rows_read)},
      {"Rows scored", std::to_string(s.rows_scored)},
      {"Rows rejected", std::to_string(s.rows_rejected)},
      {"Trials scored", std::to_string(s.trials_scored)},
      {"Trials rejected", std::to_string(s.trials_rejected)},
      {"Trials with an overspeed segment", std::to_string(s.overspeed_trials)},
      // Named relative to this page: the run writes into a staging folder that is renamed into
      // place, so an absolute path here would name a folder that no longer exists.
      {"Scores", fs::path(c.scores_path).filename().string() + " (beside this report)"},
  };
  if (!s.rejects_path.empty()) {
    rows.emplace_back("Rejected trials listed in",
                      fs::path(s.rejects_path).filename().string() + " (beside this report)");
  }
  std::string o = facts(rows);
  o += fmt::format("<p>rows read = rows scored + rows rejected: {} = {} + {}.</p>\n", s.rows_read,
                   s.rows_scored, s.rows_rejected);
  return o;
}

}  // namespace

void add_figure_options(CLI::App& cmd, FigureOptions& options, const std::string& group) {
  cmd.add_flag("--no-figures", options.no_figures,
               "Do not draw the figures (OUT/figures/); report.html then has tables only")
      ->group(group);
  cmd.add_flag("--no-report", options.no_report, "Do not write OUT/report.html")->group(group);
  cmd.add_option("--figure-formats", options.formats,
                 "Figure file formats: pdf (for LaTeX), svg (web), png (300 dpi)")
      ->delimiter(',')
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false)
      ->capture_default_str()
      ->group(group);
}

std::vector<std::string> write_figures_and_report(const AnalyzeContext& c, const FigureOptions& o) {
  for (const auto& f : o.formats) plot::parse_file_format(f);  // UsageError before any work
  std::vector<std::string> written;
  std::vector<DrawnFigure> figures;
  std::vector<std::string> notes;
  if (!o.no_figures) {
    FigureWriter w(c, o);
    draw_figures(c, w, notes);
    written = std::move(w.written());
    figures = std::move(w.figures());
  }
  if (o.no_report) return written;

  plot::HtmlReport r;
  r.title = fmt::format("Study report: {}", fs::path(c.study).lexically_normal().filename().empty()
                                                ? c.study
                                                : fs::path(c.study).filename().string());
  r.subtitle = fmt::format("feint {} analyze, {} trials of {} log files", c.version,
                           c.scored->trials_scored, c.scored->files);
  r.sections.push_back({"design", "Design", design_html(c)});
  r.sections.push_back({"accounting", "Accounting", accounting_html(c)});
  if (!figures.empty() || !notes.empty()) {
    std::string html;
    for (std::size_t i = 0; i < figures.size(); ++i) html += figure_html(figures[i], i + 1);
    for (const auto& n : notes) html += "<p>" + html_escape(n) + "</p>\n";
    r.sections.push_back({"figures", "Figures", html});
  }
  r.sections.push_back({"table1", "Table 1 per condition",
                        plot::markdown_to_html(
                            report::render_table1(*c.one_sample, report::OutputFormat::markdown))});
  if (c.comparison != nullptr) {
    r.sections.push_back({"comparison", "Comparison",
                          plot::markdown_to_html(report::render_table1(
                              *c.comparison, report::OutputFormat::markdown))});
  }
  if (c.anova != nullptr) {  // the tables of anova.* (same APA choice as Table 1)
    r.sections.push_back(
        {"anova", "Mixed ANOVA",
         plot::markdown_to_html(report::render_anova(*c.anova, report::OutputFormat::markdown,
                                                     c.one_sample->options.apa))});
  }
  if (c.likert != nullptr) {
    std::string html =
        plot::markdown_to_html(report::render_likert(*c.likert, report::OutputFormat::markdown));
    if (c.likert_compare != nullptr) {
      html += "<h3>Between the conditions</h3>\n" +
              plot::markdown_to_html(
                  report::render_likert(*c.likert_compare, report::OutputFormat::markdown));
    }
    r.sections.push_back({"questionnaire", "Questionnaire", html});
  }
  r.sections.push_back({"settings", "Settings", settings_html(c)});
  r.sections.push_back(
      {"reproduce", "Reproduce",
       fmt::format("<p>This report was made by feint {} with the command</p>\n<pre>{}</pre>\n"
                   "<p>Every table is also in the output folder as text, Markdown, LaTeX, CSV "
                   "and JSON; the figures as PDF and SVG, one-column (3.5 in) and two-column "
                   "(7.16 in) wide.</p>\n",
                   html_escape(c.version), html_escape(command_line()))});
  r.footer = fmt::format("feint {}: {}", c.version, command_line());
  const std::string path = (fs::path(c.out) / "report.html").string();
  io::write_file_atomically(path, plot::render_html(r));
  written.push_back(path);
  return written;
}

}  // namespace feint::cli

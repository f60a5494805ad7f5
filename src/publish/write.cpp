// A study's output folder (see feint/publish/study_report.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "feint/io/output.hpp"
#include "feint/plot/canvas.hpp"
#include "feint/publish/output_folder.hpp"
#include "feint/publish/results_text.hpp"
#include "feint/publish/study_report.hpp"
#include "feint/tables/writers.hpp"

namespace feint::publish {

namespace {

namespace fs = std::filesystem;

std::string extension(tables::OutputFormat format) {
  switch (format) {
    case tables::OutputFormat::text: return "txt";
    case tables::OutputFormat::markdown: return "md";
    case tables::OutputFormat::latex: return "tex";
    case tables::OutputFormat::csv: return "csv";
    case tables::OutputFormat::json: return "json";
  }
  return "txt";
}

// The questionnaire's tables (Likert items, the conditions compared, the yes/no questions).
template <typename Write, typename WriteAll>
void write_questionnaire_tables(const analysis::StudyResults& r, const tables::TablePresentation& presentation,
                                Write&& write, WriteAll&& write_all) {
  if (r.likert) {
    write_all("likert", [&](tables::OutputFormat f) {
      return tables::render_likert(*r.likert, f, presentation);
    });
    write("likert_summary.csv", tables::likert_summary_csv(*r.likert));
  }
  if (r.likert_compare) {
    write_all("likert_compare", [&](tables::OutputFormat f) {
      return tables::render_likert(*r.likert_compare, f, presentation);
    });
  }
  if (r.likert_conditions) {
    write_all("likert_conditions",
              [&](tables::OutputFormat f) { return tables::render_likert_conditions(*r.likert_conditions, f); });
  }
  if (r.yes_no) write_all("yes_no", [&](tables::OutputFormat f) { return tables::render_yes_no(*r.yes_no, f); });
}

}  // namespace

WrittenStudy write_study(const analysis::Study& study, const analysis::StudyResults& r,
                         const std::string& out_name, const std::string& command_line) {
  const analysis::AnalysisSettings& a = study.settings;
  for (const auto& f : a.figure_formats) plot::parse_file_format(f);  // UsageError before any work
  OutputFolder out(out_name, study.inputs());
  auto write = [&](const std::string& name, const std::string& text) {
    io::write_file_atomically(out.path(name), text);
  };
  auto write_all = [&](const std::string& stem, auto&& render) {
    for (const auto f : study.formats) write(stem + "." + extension(f), render(f));
  };
  write("scores.csv", r.scores_csv);
  if (!r.diagnostics.scoring.sidecar_path.empty()) {
    write(r.diagnostics.scoring.sidecar_path, r.scores_sidecar);
  }
  if (!r.diagnostics.scoring.rejects_path.empty() && !r.rejects_csv.empty()) {
    write(r.diagnostics.scoring.rejects_path, r.rejects_csv);
  }
  const tables::TablePresentation& presentation = study.tests.presentation;
  write_all("table1", [&](tables::OutputFormat f) {
    return tables::render_table1(r.table1, f, presentation);
  });
  if (r.comparison) {
    write_all("table1_compare", [&](tables::OutputFormat f) {
      return tables::render_table1(*r.comparison, f, presentation);
    });
  }
  if (r.anova) {
    tables::TablePresentation wide;  // analyze has no --label/--caption; table* applies to all
    wide.wide = presentation.wide;
    write_all("anova", [&](tables::OutputFormat f) {
      return tables::render_anova(*r.anova, f, r.table1.options.apa, wide);
    });
  }
  if (r.model) write_all("model", [&](tables::OutputFormat f) { return tables::render_model(*r.model, f); });
  if (r.trend_model) {
    write_all("model_trend",
              [&](tables::OutputFormat f) { return tables::render_model(*r.trend_model, f); });
  }
  if (!r.exposure.empty()) {
    write_all("exposure_by_condition",
              [&](tables::OutputFormat f) { return tables::render_exposure(r.exposure, f); });
  }
  write_questionnaire_tables(r, presentation, write, write_all);
  write("settings.toml", r.settings_toml);
  write("results.json", study_results_json(r));
  write("findings.json", analysis::findings_json(r.findings));
  write("results-text.md", study_results_text(r, ResultsFormat::markdown));  // to paste in a paper
  write("results-text.tex", study_results_text(r, ResultsFormat::latex));

  DrawnFigures drawn;
  if (!a.no_figures) drawn = draw_figures(r, a.figure_formats, out.staging().string());
  if (!a.no_report) {
    ReportContext c;
    c.study_folder = analysis::path_from(study.folder, out_name);  // as the Reproduce line
    c.questionnaire = analysis::display_path(study.questionnaire, study.folder);
    c.config = analysis::display_path(study.config, study.folder);
    c.command_line = command_line;
    c.csv_beside = std::find(study.formats.begin(), study.formats.end(),
                             tables::OutputFormat::csv) != study.formats.end();
    write("report.html", study_report_html(r, drawn.figures, drawn.notes, c));
    write("report.md", study_report_markdown(r, drawn.figures, c));
  }
  WrittenStudy w;
  w.files = out.commit(r.tool_version);
  w.folder = out_name;
  return w;
}

}  // namespace feint::publish

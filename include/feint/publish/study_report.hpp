// feint/publish/study_report.hpp - a study's results written out: the one-page report
// (report.html, report.md), the results as one JSON document (results.json), every table in every
// format, the figures (drawn by feint/plot from the results' data) and the settings that reproduce
// the run (settings.toml), into one output folder replaced as a whole (output_folder.hpp).
//
// Data flow: analysis::StudyResults (plain data) -> plot (figures) -> publish (files). Every path
// the report shows is relative to the study folder or to the output folder.
#pragma once

#include <string>
#include <vector>

#include "feint/analysis/results.hpp"
#include "feint/analysis/study.hpp"

namespace feint::publish {

/// A figure as drawn for the report.
struct RenderedFigure {
  std::string name;                ///< file stem ("error", "traces")
  std::string title;               ///< heading ("Mean error per iteration")
  std::string caption;             ///< plain text
  std::string alt;                 ///< alt text: what the figure shows, in one sentence
  std::string svg;                 ///< the two-column SVG for the page
  std::vector<std::string> files;  ///< relative to the output folder ("figures/error-2col.pdf")
  /// The one-column SVG, shown instead on a narrow screen (a phone's 390 px), where the
  /// two-column figure's 7 pt text would be drawn at 5 px.
  std::string svg_narrow = {};
};

/// The figures the results allow, drawn in `formats` (pdf, svg, png) and written into
/// `folder`/figures/; notes say which figures could not be drawn and why.
struct DrawnFigures {
  std::vector<RenderedFigure> figures;
  std::vector<std::string> notes;
  std::vector<std::string> written;  ///< paths of the files written
};
DrawnFigures draw_figures(const analysis::StudyResults& results,
                          const std::vector<std::string>& formats, const std::string& folder);

/// What the page says about where it came from.
struct ReportContext {
  std::string study_folder;   ///< as seen from the report's folder (analysis::path_from)
  std::string questionnaire;  ///< relative to the study ("" = none)
  std::string config;         ///< relative to the study or current folder ("" = none)
  std::string command_line;   ///< the command that ran ("" = not known)
  bool csv_beside = true;     ///< the tables' CSV files are written beside the report
};

/// The HTML page (self-contained: inline CSS and SVG, no script).
std::string study_report_html(const analysis::StudyResults& results,
                              const std::vector<RenderedFigure>& figures,
                              const std::vector<std::string>& figure_notes,
                              const ReportContext& context);
/// The same report in Markdown (figures as image links to figures/*-2col.svg when drawn as SVG).
std::string study_report_markdown(const analysis::StudyResults& results,
                                  const std::vector<RenderedFigure>& figures,
                                  const ReportContext& context);
/// Every result as one JSON document: {"study", "version", "diagnostics", "table1", ...}.
std::string study_results_json(const analysis::StudyResults& results);

/// One line per part of the diagnostics: what was read, excluded, warned about (also printed by
/// `feint analyze`).
std::vector<std::string> diagnostics_lines(const analysis::Diagnostics& diagnostics);

/// "1 log file", "2 log files": English plurals for the counts the report shows.
std::string count(std::size_t n, const std::string& singular, const std::string& plural = "");

struct WrittenStudy {
  std::vector<std::string> files;  ///< relative to the output folder, sorted
  std::string folder;              ///< the output folder as named
};

/// Writes everything into `out` (a staging folder swapped in at the end; see output_folder.hpp).
WrittenStudy write_study(const analysis::Study& study, const analysis::StudyResults& results,
                         const std::string& out, const std::string& command_line = "");

}  // namespace feint::publish

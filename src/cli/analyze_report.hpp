// src/cli/analyze_report.hpp - the figures (OUT/figures/) and the one-page study report
// (OUT/report.html) of `feint analyze`, drawn from the tables the command already built
// (docs/figures.md). Kept apart from cmd_analyze.cpp, which calls write_figures_and_report() once.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "feint/io/scores.hpp"
#include "feint/metrics/score.hpp"
#include "feint/report/anova_render.hpp"
#include "feint/report/likert.hpp"
#include "feint/report/table1.hpp"

namespace feint::cli {

/// `--no-figures`, `--no-report`, `--figure-formats`.
struct FigureOptions {
  bool no_figures = false;
  bool no_report = false;
  std::vector<std::string> formats = {"pdf", "svg"};
};
void add_figure_options(CLI::App& cmd, FigureOptions& options, const std::string& group);

/// What `feint analyze` computed; pointers may be null where the study has no such part.
struct AnalyzeContext {
  const CLI::App* command = nullptr;  ///< for the effective settings
  std::string study;
  std::string out;
  std::string config_path;        ///< "" when no settings file was read
  std::vector<std::string> logs;  ///< the scoring inputs (files, folders, globs)
  const metrics::ScoreSettings* scoring = nullptr;
  const metrics::ScoreSummary* scored = nullptr;
  std::string scores_path;
  const io::ScoresTable* scores = nullptr;
  const report::Table1* one_sample = nullptr;
  const report::Table1* comparison = nullptr;
  const report::AnovaReport* anova = nullptr;  ///< null when the design allows no mixed ANOVA
  std::string questionnaire_path;
  const report::LikertAnalysis* likert = nullptr;
  const report::LikertAnalysis* likert_compare = nullptr;
  std::string version;
};

/// Writes OUT/figures/<name>-1col.<fmt> and <name>-2col.<fmt> for every figure the study allows,
/// and OUT/report.html; returns the paths written (for the command's count). A figure that the
/// data cannot give (no strategy column, ...) is left out and the report says why.
std::vector<std::string> write_figures_and_report(const AnalyzeContext& context,
                                                  const FigureOptions& options);

}  // namespace feint::cli

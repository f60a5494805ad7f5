// feint/tables/simulation_render.hpp - the selection simulation's summary (`feint simulate
// selection`) as text, Markdown, CSV or JSON, and its per-run and per-iteration tidy CSV files
// (docs/selection.md, docs/simulation.md).
#pragma once

#include <string>
#include <vector>

#include "feint/sim/simulation.hpp"
#include "feint/sim/study.hpp"

namespace feint::tables {

/// The format of a simulation's output: `format` when given ("text", "markdown", "csv" or "json",
/// any case; else UsageError), otherwise from the extension of `output` (.csv, .json, .md), else
/// text.
std::string output_format(const std::string& format, const std::string& output);

/// `format`: "text", "markdown", "csv" or "json" (anything else: text). One row per simulated
/// algorithm/lambda: entropy (mean, sd, se, min, max, pooled), repetition, conditional entropy,
/// guess accuracy and the batch quantiles.
std::string render_selection(const std::vector<sim::SimulationSummary>& rows,
                             const std::string& format);

/// Every run's iterations (algorithm, lambda, run, iteration, strategy, variant, target), written
/// atomically to `path` (- = standard output); the runs are simulated again from the settings.
void write_selection_sequences(const std::string& path,
                               const std::vector<sim::SimulationSettings>& settings);

/// Per-iteration occurrence probabilities (algorithm, lambda, iteration, strategy, probability,
/// cumulative_share, runs), written atomically to `path`.
void write_selection_occurrence(const std::string& path,
                                const std::vector<sim::SimulationSummary>& rows);

/// What `feint simulate study` wrote into `dir`, and per condition the mean error of the first
/// and the last five iterations (the wear-off at a glance).
std::string study_summary_text(const std::vector<sim::ParticipantRecord>& people,
                               const sim::StudySettings& settings, const std::string& dir);

}  // namespace feint::tables

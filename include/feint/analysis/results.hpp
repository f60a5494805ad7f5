// feint/analysis/results.hpp - everything a study run computes (analyze), as plain data: no file
// is read or written through it. The writers render it: feint/publish (report.html, report.md,
// results.json, the tables in every format) and feint/plot (the figures, drawn from FigureData).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "feint/analysis/figure_data.hpp"
#include "feint/tables/exposure_render.hpp"
#include "feint/analysis/findings.hpp"
#include "feint/analysis/hypotheses.hpp"
#include "feint/io/diagnostic.hpp"
#include "feint/io/participants.hpp"
#include "feint/io/scores.hpp"
#include "feint/metrics/exposure_trend.hpp"
#include "feint/metrics/score.hpp"
#include "feint/models/condition_design.hpp"
#include "feint/models/fitted_trend.hpp"
#include "feint/models/observer_fit.hpp"
#include "feint/tables/anova.hpp"
#include "feint/tables/likert.hpp"
#include "feint/tables/likert_conditions.hpp"
#include "feint/tables/model.hpp"
#include "feint/tables/table1.hpp"
#include "feint/tables/yes_no.hpp"

namespace feint::analysis {

/// One reason trials, participants or questionnaire answers were left out or warned about.
struct Exclusion {
  std::string stage;   ///< "scoring", "participants", "questionnaire", "anova", "model", "figures"
  std::string what;    ///< "trial", "participant", "respondent", "analysis"
  std::size_t count = 0;
  std::string reason;  ///< e.g. "trial durations look like milliseconds"
  std::vector<std::string> examples;  ///< up to 5 items (file:line, respondent id)
  /// The reader's stable code for a scoring warning (io::Diagnostic::code, e.g.
  /// "time-unit-ms-suspected", "nan-padding", "iteration-base-0"); "" otherwise.
  std::string code;
};

/// What was read, left out and warned about, stage by stage.
struct Diagnostics {
  metrics::ScoreSummary scoring;  ///< files, rows and trials read, scored, rejected
  std::size_t participants = 0;   ///< distinct participants with at least one scored trial
  std::vector<std::pair<std::string, std::size_t>> participants_per_condition;
  std::size_t questionnaire_rows = 0;  ///< data rows of the questionnaire (0 without one)
  std::size_t respondents = 0;         ///< respondents analysed
  std::vector<std::string> warnings;   ///< every warning, as also printed on standard error
  std::vector<Exclusion> exclusions;   ///< what was left out and why
  /// The logs' participants against the questionnaire's (empty sides when there is none).
  std::optional<io::ParticipantComparison> participants_compared;
};

/// The data of every figure (the plot module draws them; nothing here is read from a file then).
struct FigureData {
  std::vector<TrialLabel> labels;  ///< per scored trial; empty when the logs have no strategy
  std::string labels_note;         ///< why there is no strategy figure ("" when there is)
  std::vector<TraceCurve> traces;  ///< mean pad trace per strategy, version and exposure
  /// Logs of K targets and a pointer: the map of the scored trials (metrics::mean_map), the mean
  /// robot path and pointer per strategy and version. Empty for pad logs, and when map_note says
  /// why there is none.
  std::optional<MeanMap> map;
  std::string map_note;  ///< why a study of K targets has no map ("" when it has one)
  /// Condition x exposure per strategy, one per metric (metrics::exposure_trend of the scores and
  /// the labels); empty when the logs have no strategy.
  std::vector<metrics::ExposureTrend> exposure;
  /// The mixed model's fitted trend (the linear-trend model, models::fitted_trend at the tables'
  /// confidence level), one per metric; empty without the model.
  struct ModelTrend {
    std::string metric;
    std::string model;  ///< how the model reads, e.g. "linear trend, random intercept"
    std::vector<models::FittedTrend> trend;
  };
  std::vector<ModelTrend> model_trends;
};

struct StudyResults {
  std::string study;             ///< the study's name (its folder's last component)
  std::string tool_version;
  std::string settings_toml;     ///< the feint.toml that reproduces this run (settings_toml)
  // Scores: the scored trials as written to scores.csv (with the sidecar and rejected trials).
  io::ScoresTable scores;        ///< path "scores.csv"
  std::string scores_csv;        ///< the file's bytes
  std::string scores_sidecar;    ///< scores.csv.meta.json's bytes ("" when none)
  std::string rejects_csv;       ///< scores.csv.rejects.csv's bytes ("" in strict mode)
  // Tables.
  tables::Table1 table1;                     ///< one-sample, per condition
  std::optional<tables::Table1> comparison;  ///< condition A against B (--compare)
  /// Why the conditions were compared when no setting asked it (default_comparison), for the
  /// report's Design; empty when a setting named the comparison or none was made.
  std::string comparison_note;
  /// How the conditions relate to the participants (between or within), declared or read off the
  /// data, with the participants a within design could not pair (models/condition_design.hpp).
  models::DesignCheck design;
  std::optional<tables::AnovaReport> anova;  ///< mixed ANOVA (GG); empty when the design allows none
  std::optional<tables::ModelAnalysis> model;        ///< metric ~ condition * iteration (feint model)
  std::optional<tables::ModelAnalysis> trend_model;  ///< metric ~ condition * iteration as a trend
  std::optional<tables::LikertAnalysis> likert;          ///< against the reference
  std::optional<tables::LikertAnalysis> likert_compare;  ///< A against B
  /// Three or more conditions between participants, no pair named: Kruskal-Wallis per item, then
  /// every pair (Holm over the pairs, protected by the omnibus test).
  std::optional<tables::LikertConditions> likert_conditions;
  /// The yes/no questions (questionnaire_yesno.csv): proportions per condition, and with two
  /// conditions compared Fisher's exact test and the chi-square test (docs/yes-no.md).
  std::optional<tables::YesNoAnalysis> yes_no;
  /// The one-sided tests of a confirmatory hypothesis with a direction (H1: the comparison, H2:
  /// the questionnaire between the conditions), with that alternative: its findings rest on them;
  /// the tables above, and every exploratory finding, stay two-sided (docs/findings.md).
  std::optional<tables::Table1> comparison_one_sided;
  std::optional<tables::LikertAnalysis> likert_compare_one_sided;
  /// Condition x exposure per strategy, one per metric (two conditions and the trials' strategies
  /// needed; analysis::exposure_table); the findings' source "exposure".
  std::vector<tables::ExposureTable> exposure;
  /// The goal-inference observer's log beta and tau compared between the compared pair (fitted to
  /// each participant's pad traces; docs/analysis.md "The observer's parameters compared"); empty
  /// for pointer logs or when no pair is compared, and with `observer_note` when it failed.
  std::vector<models::ObserverComparison> observer;
  std::string observer_note;
  FigureData figures;
  Diagnostics diagnostics;
  std::vector<Finding> findings;  ///< filled by the findings engine (empty until then)
  /// The hypotheses the findings answer (feint.toml [hypotheses], else the paper's H1 and H2, with
  /// the compared conditions' names); empty without a comparison of two conditions.
  std::vector<Hypothesis> hypotheses;
};

}  // namespace feint::analysis

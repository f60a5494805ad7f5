// The study pipeline as a library: load_study -> analyze -> StudyResults (plain data).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>
#include <string>

#include "feint/analysis/analyze.hpp"
#include "feint/error.hpp"

namespace fs = std::filesystem;
using namespace feint;

namespace {
const std::string kDemo = std::string(FEINT_SOURCE_DIR) + "/data/demo";

analysis::AnalysisSettings demo_settings() {
  analysis::AnalysisSettings s;  // as data/demo/feint.toml
  s.compare = "adaptive,random";
  s.likert.reference = 3.5;
  return s;
}
}  // namespace

TEST(Study, LoadsTheDemoAndChecksSettingsFirst) {
  const analysis::Study study = analysis::load_study(kDemo, demo_settings());
  EXPECT_EQ(study.name, "demo");
  EXPECT_EQ(study.logs.size(), 60u);
  ASSERT_TRUE(study.answers.has_value());
  EXPECT_EQ(study.answers->participants.size(), 60u);
  EXPECT_EQ(study.compare->first, "adaptive");

  auto bad = demo_settings();
  bad.report.alpha = 2;
  EXPECT_THROW(analysis::load_study(kDemo, bad), UsageError);
  bad = demo_settings();
  bad.formats.clear();
  EXPECT_THROW(analysis::load_study(kDemo, bad), UsageError);
  EXPECT_THROW(analysis::load_study(kDemo + "/no-such-folder", demo_settings()), IoError);
  EXPECT_THROW(analysis::load_study(kDemo + "/logs", demo_settings()), InvalidData);  // no logs/
}

TEST(Analyze, TheDemoGivesEveryPartAsPlainData) {
  const analysis::Study study = analysis::load_study(kDemo, demo_settings());
  const analysis::StudyResults r = analysis::analyze(study, "test");
  const auto& d = r.diagnostics;
  EXPECT_EQ(d.scoring.files, 60u);
  EXPECT_EQ(d.scoring.trials_scored, 1200u);
  EXPECT_EQ(d.scoring.trials_rejected, 0u);
  EXPECT_EQ(d.scoring.rows_read, d.scoring.rows_scored + d.scoring.rows_rejected);
  EXPECT_EQ(d.participants, 60u);
  ASSERT_EQ(d.participants_per_condition.size(), 2u);
  EXPECT_EQ(d.participants_per_condition[0].second + d.participants_per_condition[1].second, 60u);
  // Scores: one record per scored trial; no path of the scratch folder survives.
  EXPECT_EQ(r.scores.records.size(), 1200u);
  EXPECT_EQ(r.scores.path, "scores.csv");
  EXPECT_EQ(r.scores_sidecar.find("feint-analyze-"), std::string::npos);
  // Table 1: 2 conditions x 20 iterations x 2 metrics one-sample tests.
  EXPECT_EQ(r.table1.rows.size(), 80u);
  ASSERT_TRUE(r.comparison.has_value());
  EXPECT_EQ(r.comparison->rows.size(), 40u);
  ASSERT_TRUE(r.anova.has_value());
  EXPECT_EQ(r.anova->analyses.size(), 2u);
  ASSERT_TRUE(r.model.has_value());
  ASSERT_EQ(r.model->models.size(), 2u);
  EXPECT_EQ(r.model->models[0].contrasts.size(), 20u);  // A - B per iteration
  ASSERT_TRUE(r.trend_model.has_value());
  ASSERT_TRUE(r.likert.has_value());
  ASSERT_TRUE(r.likert_compare.has_value());
  EXPECT_EQ(d.respondents, 60u);
  // Figure data: a label per scored trial, first and later exposures per strategy.
  EXPECT_EQ(r.figures.labels.size(), 1200u);
  EXPECT_FALSE(r.figures.traces.empty());
  for (const auto& c : r.figures.traces) EXPECT_EQ(c.mean.size(), analysis::kTracePoints);
  // The findings engine: H1 per metric (the comparison's per-iteration contrasts), the demo's
  // confusion reference 0.95 inside the data (one scale), H2 per item against the reference and between.
  ASSERT_FALSE(r.findings.empty());
  EXPECT_EQ(r.findings.front().id, "H1-iterations-error");
  EXPECT_NE(r.findings.front().sentence.find("(Westfall\u2013Young maxT-adjusted over 20 iterations, 10,000 labellings of the participants drawn at random)"), std::string::npos);
  bool reference_warning = false, h2 = false;
  for (const auto& f : r.findings) {
    reference_warning |= f.id == "reference-confusion" && !f.warnings.empty();
    h2 |= f.hypothesis == "H2" && f.sentence.find("BF") != std::string::npos;
  }
  // Raw, the default normalisation, is the scale of the default reference 0.95: no warning.
  EXPECT_FALSE(reference_warning);
  EXPECT_TRUE(h2);
  // The settings that reproduce the run name the design read off the data (each of the 60
  // participants in one condition), so that a rerun declares it.
  EXPECT_EQ(r.design.design, models::ConditionDesign::between);
  EXPECT_FALSE(r.design.declared);
  analysis::AnalysisSettings printed = study.settings;
  printed.design = "between";
  EXPECT_EQ(r.settings_toml, analysis::settings_toml(printed));
}

TEST(Analyze, ScoringWarningsAreCollectedNotPrinted) {
  auto s = demo_settings();
  s.scoring.time_unit = "ms";  // the demo's seconds read as milliseconds: implausibly short trials
  const analysis::StudyResults r = analysis::analyze(analysis::load_study(kDemo, s));
  ASSERT_FALSE(r.diagnostics.warnings.empty());
  bool listed = false;
  for (const auto& e : r.diagnostics.exclusions) listed |= e.stage == "scoring" && e.what == "warning";
  EXPECT_TRUE(listed);
}

TEST(Settings, TomlNamesEverySettingAndQuotesStrings) {
  analysis::AnalysisSettings s;
  s.likert.labels = "Agree \"a lot\"=7";
  s.scoring.trim = 0.1;
  const std::string t = analysis::settings_toml(s);
  EXPECT_NE(t.find("labels = \"Agree \\\"a lot\\\"=7\"\n"), std::string::npos) << t;
  EXPECT_NE(t.find("trim = 0.1\n"), std::string::npos) << t;
  EXPECT_NE(t.find("# compare = \"\""), std::string::npos) << t;
  EXPECT_NE(t.find("formats = [\"text\", \"markdown\", \"latex\", \"csv\", \"json\"]\n"),
            std::string::npos);
  EXPECT_EQ(t.find("\nstudy"), std::string::npos) << "no positional argument in the block";
}

TEST(DisplayPath, RelativeToTheBaseNeverAbsolute) {
  EXPECT_EQ(analysis::display_path(kDemo + "/questionnaire.csv", kDemo), "questionnaire.csv");
  EXPECT_EQ(analysis::display_path(kDemo + "/logs/../feint.toml", kDemo), "feint.toml");
  const std::string outside = analysis::display_path(kDemo, kDemo + "/logs");
  EXPECT_FALSE(fs::path(outside).is_absolute()) << outside;
  EXPECT_EQ(analysis::display_path("", kDemo), "");
}

TEST(Analyze, RejectedTrialsAndParticipantsAreCountedByReason) {
  // Two participants; P2's only trial goes back in time and is rejected (--on-error skip).
  const fs::path study = fs::temp_directory_path() / "feint-test-rejects-study";
  fs::remove_all(study);
  fs::create_directories(study / "logs");
  {
    std::ofstream f(study / "logs" / "s.csv");
    f << "participant,condition,iteration,target,t,pad,pad_speed\n";
    for (int it = 1; it <= 2; ++it) {
      for (int k = 0; k <= 5; ++k) f << "P1,adaptive," << it << ",right," << k * 0.2 << ",0.6,0.5\n";
    }
    f << "P2,adaptive,1,right,0,0.5,0.5\nP2,adaptive,1,right,0.4,0.5,0.5\n"
      << "P2,adaptive,1,right,0.2,0.5,0.5\n";
  }
  analysis::AnalysisSettings s;
  s.scoring.on_error = "skip";
  const auto r = analysis::analyze(analysis::load_study(study.string(), s), "test");
  EXPECT_EQ(r.diagnostics.scoring.trials_scored, 2u);
  EXPECT_EQ(r.diagnostics.scoring.trials_rejected, 1u);
  EXPECT_EQ(r.diagnostics.participants, 1u);
  bool trial = false, participant = false;
  for (const auto& e : r.diagnostics.exclusions) {
    if (e.stage == "scoring" && e.what == "trial") {
      trial = e.count == 1 && e.examples == std::vector<std::string>{"s.csv:16"};
      EXPECT_EQ(e.reason.find("s.csv"), std::string::npos) << "the reason without the place: "
                                                          << e.reason;
    }
    if (e.what == "participant") {
      participant = e.count == 1 && e.examples == std::vector<std::string>{"P2"};
    }
  }
  EXPECT_TRUE(trial) << r.rejects_csv;
  EXPECT_TRUE(participant);
  EXPECT_FALSE(r.rejects_csv.empty());
  fs::remove_all(study);
}

namespace {

// A small study: participants P1, P2 (adaptive) and P3, P4 (random), two iterations of a 1 s
// trial each (times as `scale` says: 1 = seconds, 1000 = milliseconds), with or without a
// condition column, and optionally a questionnaire naming `respondents`.
fs::path small_study(const std::string& name, double scale, bool with_condition,
                     const std::vector<std::string>& respondents = {}) {
  const fs::path study = fs::temp_directory_path() / ("feint-test-" + name);
  fs::remove_all(study);
  fs::create_directories(study / "logs");
  std::ofstream f(study / "logs" / "s.csv");
  f << "participant," << (with_condition ? "condition," : "")
    << "iteration,strategy,target,t,pad,pad_speed\n";
  const char* ids[] = {"P1", "P2", "P3", "P4"};
  for (int p = 0; p < 4; ++p) {
    for (int it = 1; it <= 2; ++it) {
      for (int k = 0; k <= 5; ++k) {
        f << ids[p] << ',';
        if (with_condition) f << (p < 2 ? "adaptive," : "random,");
        f << it << ',' << (it == 1 ? "L" : "R") << ",right," << k * 0.1 * scale << ','
          << 0.5 + 0.05 * k * (p + 1) / 4.0 + 0.01 * it << ",0.5\n";
      }
    }
  }
  if (!respondents.empty()) {
    std::ofstream q(study / "questionnaire.csv");
    q << "participant,condition,trust\n";
    for (std::size_t i = 0; i < respondents.size(); ++i) {
      q << respondents[i] << ',' << (i % 2 ? "random" : "adaptive") << ',' << 3 + i % 3 << "\n";
    }
  }
  return study;
}

}  // namespace

TEST(Analyze, TheDemoHasTheExposureAndModelTrendFigureData) {
  const analysis::StudyResults r = analysis::analyze(analysis::load_study(kDemo, demo_settings()));
  ASSERT_EQ(r.figures.exposure.size(), 2u);  // error, confusion
  EXPECT_EQ(r.figures.exposure[0].metric, "error");
  EXPECT_EQ(r.figures.exposure[0].conditions, (std::vector<std::string>{"adaptive", "random"}));
  ASSERT_FALSE(r.figures.exposure[0].strategies.empty());
  std::size_t trials = 0;
  for (const auto& st : r.figures.exposure[0].strategies) {
    ASSERT_EQ(st.series.size(), 2u);
    for (const auto& se : st.series) {
      for (const auto& p : se.points) trials += p.n;
    }
  }
  EXPECT_EQ(trials + r.figures.exposure[0].unmatched, 1200u) << "every scored trial, once";
  ASSERT_EQ(r.figures.model_trends.size(), 2u);
  const auto& mt = r.figures.model_trends[0];
  EXPECT_EQ(mt.metric, "error");
  ASSERT_EQ(mt.trend.size(), 2u);  // one line per condition
  for (const auto& g : mt.trend) {
    ASSERT_EQ(g.points.size(), 20u);
    // A linear trend: equal steps, the fit inside its band.
    const double step = g.points[1].fit - g.points[0].fit;
    EXPECT_NEAR(g.points[19].fit - g.points[18].fit, step, 1e-12);
    for (const auto& p : g.points) {
      EXPECT_LT(p.low, p.fit);
      EXPECT_GT(p.high, p.fit);
    }
  }
  // The demo's questionnaire names exactly the logs' participants.
  ASSERT_TRUE(r.diagnostics.participants_compared.has_value());
  EXPECT_TRUE(r.diagnostics.participants_compared->matches());
  EXPECT_EQ(r.diagnostics.participants_compared->in_both, 60u);
}

TEST(Analyze, ParticipantsMissingOnEitherSideAreListed) {
  const fs::path study = small_study("ids", 1, true, {"P1", "P2", "P3", "P9"});
  const auto r = analysis::analyze(analysis::load_study(study.string(), {}), "test");
  ASSERT_TRUE(r.diagnostics.participants_compared.has_value());
  EXPECT_EQ(r.diagnostics.participants_compared->only_in_logs, std::vector<std::string>{"P4"});
  EXPECT_EQ(r.diagnostics.participants_compared->only_in_questionnaire,
            std::vector<std::string>{"P9"});
  EXPECT_EQ(r.diagnostics.participants_compared->in_both, 3u);
  int listed = 0;
  for (const auto& e : r.diagnostics.exclusions) {
    if (e.stage != "participants") continue;
    ++listed;
    EXPECT_EQ(e.count, 1u);
    EXPECT_EQ(e.examples, std::vector<std::string>{e.reason.find("not in the questionnaire") !=
                                                           std::string::npos
                                                       ? "P4"
                                                       : "P9"});
  }
  EXPECT_EQ(listed, 2);
  bool warned = false;
  for (const auto& w : r.diagnostics.warnings) {
    warned |= w.find("P4") != std::string::npos && w.find("P9") != std::string::npos;
  }
  EXPECT_TRUE(warned) << "the warning (standard error) names both ids";
  fs::remove_all(study);
}

TEST(Analyze, MillisecondTimesAreAStructuredScoringWarning) {
  const fs::path study = small_study("ms", 1000, true);  // 0.5 s trials written in ms
  const auto r = analysis::analyze(analysis::load_study(study.string(), {}), "test");
  int notes = 0;
  for (const auto& e : r.diagnostics.exclusions) {
    if (e.code != "time-unit-ms-suspected") continue;
    ++notes;
    EXPECT_EQ(e.stage, "scoring");
    EXPECT_NE(e.reason.find("--time-unit ms"), std::string::npos) << e.reason;
  }
  EXPECT_EQ(notes, 1) << "listed once, not once per source";
  fs::remove_all(study);
}

TEST(Analyze, TwoConditionsAndALogWithoutTheConditionColumnIsRefused) {
  const fs::path study = small_study("nocond", 1, false);
  auto s = analysis::AnalysisSettings{};
  s.compare = "adaptive,random";
  const auto loaded = analysis::load_study(study.string(), s);
  EXPECT_EQ(loaded.scoring.reading.expected_conditions,
            (std::vector<std::string>{"adaptive", "random"}));
  try {
    analysis::analyze(loaded, "test");
    ADD_FAILURE() << "pooled instead of refused";
  } catch (const InvalidData& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("s.csv:1: no condition column"), std::string::npos) << m;
    EXPECT_NE(m.find("--map condition="), std::string::npos) << m;
  }
  // Without the comparison the same log is one condition, as before.
  EXPECT_NO_THROW(analysis::analyze(analysis::load_study(study.string(), {}), "test"));
  fs::remove_all(study);
}

TEST(Analyze, ReadingNotesNameTheFileRelativeToTheStudy) {
  // Other labs' exports (tests/data/labs): a European CSV and fixed-length NaN padding. The study
  // is named by an absolute path; the notes name the log relative to it.
  for (const std::string name : {"european.csv", "fixed_length_nan.csv"}) {
    const fs::path study = fs::temp_directory_path() / ("feint-test-notes-" + name);
    fs::remove_all(study);
    fs::create_directories(study / "logs");
    fs::copy_file(std::string(FEINT_SOURCE_DIR) + "/tests/data/labs/" + name, study / "logs" / name);
    analysis::AnalysisSettings s;
    s.scoring.norm = "raw";  // the padded file has no pad_speed column
    const auto r = analysis::analyze(analysis::load_study(study.string(), s), "test");
    const std::string code = name == "european.csv" ? "decimal-comma" : "nan-padding";
    int notes = 0;
    for (const auto& e : r.diagnostics.exclusions) {
      if (e.code != code) continue;
      ++notes;
      EXPECT_EQ(e.reason.find(study.string()), std::string::npos) << e.reason;
      if (code == "decimal-comma") {
        EXPECT_EQ(e.reason.rfind("logs/european.csv:2: numbers read with a decimal comma", 0), 0u)
            << e.reason;
      } else {
        EXPECT_NE(e.reason.find("dropped"), std::string::npos) << e.reason;
      }
    }
    EXPECT_EQ(notes, 1) << name;
    fs::remove_all(study);
  }
}

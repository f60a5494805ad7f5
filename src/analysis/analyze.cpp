// The study pipeline: Study -> StudyResults (see feint/analysis/analyze.hpp).
#include "feint/analysis/analyze.hpp"
#include "feint/analysis/study_findings.hpp"

#include <fmt/format.h>
#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/trace.hpp"
#include "pointer_design.hpp"
#include "observer_stage.hpp"
#include "scratch_folder.hpp"

namespace feint::analysis {

namespace {

namespace fs = std::filesystem;

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The scratch folder's name never reaches an output: the sidecar names the scores file relative
// to the output folder it is written into.
std::string without_prefix(std::string text, const std::string& prefix) {
  for (auto pos = text.find(prefix); pos != std::string::npos; pos = text.find(prefix, pos)) {
    text.erase(pos, prefix.size());
  }
  return text;
}

// "logs/p01.csv:12: column 't': not increasing (trial p01/adaptive/3)" -> "column 't': not
// increasing": the reason without where it happened, so that rejections can be counted by reason.
std::string bare_reason(const std::string& reason) {
  std::string r = reason;
  const auto trial = r.rfind(" (trial ");
  if (trial != std::string::npos) r.erase(trial);
  // Drop a leading "file:line: ".
  const auto colon = r.find(": ");
  if (colon != std::string::npos) {
    const auto first = r.find(':');
    if (first < colon && r.find_first_not_of("0123456789", first + 1) == colon) {
      r.erase(0, colon + 2);
    }
  }
  return r;
}

// Rejected trials counted by reason; the participants of the rejected trials returned.
std::set<std::string> count_rejections(const fs::path& rejects, Diagnostics& d) {
  std::set<std::string> participants;
  if (!fs::exists(rejects)) return participants;
  io::CsvReader csv(rejects.string());
  const int reason = csv.column("reason");
  const int file = csv.column("file");
  const int line = csv.column("line");
  const int participant = csv.column("participant");
  if (reason < 0) return participants;
  std::map<std::string, Exclusion> by_reason;
  while (csv.next()) {
    if (participant >= 0) {
      participants.insert(std::string(csv.field(static_cast<std::size_t>(participant))));
    }
    const std::string why = bare_reason(std::string(csv.field(static_cast<std::size_t>(reason))));
    Exclusion& e = by_reason[why];
    e.stage = "scoring";
    e.what = "trial";
    e.reason = why;
    ++e.count;
    if (e.examples.size() < 5 && file >= 0 && line >= 0) {
      e.examples.push_back(fmt::format(
          "{}:{}", fs::path(std::string(csv.field(static_cast<std::size_t>(file)))).filename().string(),
          csv.field(static_cast<std::size_t>(line))));
    }
  }
  for (auto& [_, e] : by_reason) d.exclusions.push_back(std::move(e));
  return participants;
}

// A scoring diagnostic as an entry of the accounting: where it applies is added as an example
// unless the message names it already.
Exclusion scoring_note(const io::Diagnostic& n, const std::string& prefix,
                       const std::string& study_folder) {
  std::string message = without_prefix(n.message, prefix);
  if (!n.file.empty() && n.file != "-") {
    // The file as the report names every path: relative to the study, never absolute.
    const std::string shown = display_path(n.file, study_folder);
    for (auto pos = message.find(n.file); pos != std::string::npos;
         pos = message.find(n.file, pos + shown.size())) {
      message.replace(pos, n.file.size(), shown);
    }
  }
  Exclusion e{"scoring", "warning", 0, message, {}, n.code};
  const std::string file = n.file.empty() ? "" : fs::path(n.file).filename().string();
  if (!file.empty() && e.reason.find(file) == std::string::npos) {
    e.examples.push_back(n.line > 0 ? fmt::format("{}:{}", file, n.line) : file);
  }
  if (!n.column.empty() && e.reason.find("'" + n.column + "'") == std::string::npos) {
    e.examples.push_back(fmt::format("column '{}'", n.column));
  }
  return e;
}

std::vector<std::string> first_ten(const std::vector<std::string>& ids) {
  return {ids.begin(), ids.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(ids.size(), 10))};
}

void note_left_out(Diagnostics& d, const std::string& stage, const std::string& reason) {
  d.exclusions.push_back({stage, "analysis", 0, reason, {}, ""});
  d.warnings.push_back(fmt::format("{}: {}", stage, reason));
}

// The scores file of a run, in the scratch folder, and what the later stages need of scoring.
struct Scored {
  fs::path path;        ///< scratch/scores.csv
  std::string prefix;   ///< the scratch folder with a trailing '/', removed from every message
  metrics::ScoreSettings settings;
  std::set<std::string> rejected_participants;
};

// Stage 1. Score every trial into the scratch folder: the scores file with its sidecar is the
// study's record of how each number was made, and Table 1 reads its provenance from there.
Scored score_trials(const Study& study, const std::string& tool_version,
                    const fs::path& scratch, StudyResults& r) {
  Diagnostics& d = r.diagnostics;
  Scored sc;
  sc.settings = study.scoring;
  sc.settings.tool_version = tool_version;
  sc.settings.on_warning = [&d](const std::string& w) { d.warnings.push_back(w); };
  sc.path = scratch / "scores.csv";
  d.scoring = metrics::score_to_file(study.log_inputs, sc.settings, sc.path.string());
  sc.prefix = (scratch / "").string();
  r.scores_csv = read_all(sc.path);
  if (!d.scoring.sidecar_path.empty()) {
    r.scores_sidecar = without_prefix(read_all(d.scoring.sidecar_path), sc.prefix);
  }
  if (!d.scoring.rejects_path.empty()) {
    r.rejects_csv = read_all(d.scoring.rejects_path);
    sc.rejected_participants = count_rejections(d.scoring.rejects_path, d);
  }
  d.scoring.output_path = "scores.csv";
  if (!d.scoring.sidecar_path.empty()) {
    d.scoring.sidecar_path = fs::path(d.scoring.sidecar_path).filename().string();
  }
  if (!d.scoring.rejects_path.empty()) {
    d.scoring.rejects_path = fs::path(d.scoring.rejects_path).filename().string();
  }
  // The reader's and the time-unit check's notes, structured (code, file, line, column): one
  // entry each (their messages are also in d.warnings, through on_warning).
  for (const auto& n : d.scoring.diagnostics) {
    d.exclusions.push_back(scoring_note(n, sc.prefix, study.folder));
  }
  return sc;
}

tables::Table1Options table1_options(const Study& study) {
  tables::Table1Options t;
  t.metrics = study.metrics;
  t.alpha = study.tests.alpha;
  t.test = study.tests.test;
  t.p_adjust = study.tests.p_adjust;
  t.equivalence = study.settings.equivalence;
  t.apa = study.tests.apa;
  t.bf_prior_r = study.tests.bf_prior_r;
  return t;
}

std::vector<std::string> metric_columns(const tables::Table1Options& t) {
  std::vector<std::string> columns;
  for (const auto& m : t.metrics) columns.push_back(m.column);
  return columns;
}

// Stage 2. The scores as a table; who is in it, per condition, and who lost every trial.
void load_scored(const Scored& sc, const std::vector<std::string>& metrics, StudyResults& r) {
  Diagnostics& d = r.diagnostics;
  io::ScoresOptions load;
  // A study of two conditions never pools a table without its condition column.
  load.expected_conditions = sc.settings.reading.expected_conditions;
  load.metrics = metrics;
  r.scores = io::load_scores(sc.path.string(), load);
  std::map<std::string, std::set<std::string>> per;
  std::set<std::string> all;
  for (const auto& rec : r.scores.records) {
    per[rec.condition].insert(rec.participant);
    all.insert(rec.participant);
  }
  d.participants = all.size();
  // A participant whose every trial was rejected is not in the scores at all: say so.
  Exclusion gone{"scoring", "participant", 0, "every trial rejected (not in the analysis)", {}, ""};
  for (const auto& p : sc.rejected_participants) {
    if (all.count(p) != 0) continue;
    ++gone.count;
    if (gone.examples.size() < 5) gone.examples.push_back(p);
  }
  if (gone.count > 0) d.exclusions.push_back(std::move(gone));
  for (const auto& c : r.scores.conditions()) d.participants_per_condition.emplace_back(c, per[c].size());
}

using Comparison = std::optional<std::pair<std::string, std::string>>;

// Stage 2b. The condition design, declared or read off the data and checked against it: a
// contradiction stops the run (InvalidData naming the participant and what to set); participants
// a within design cannot pair are named in the accounting.
void check_design(const Study& study, const std::vector<std::string>& metrics, StudyResults& r) {
  if (metrics.empty()) return;
  // The scored trials' lines are those of a scratch file: the messages name the study instead.
  auto rows = tables::observations(r.scores, metrics.front());
  for (auto& row : rows) row.line = 0;
  r.design = models::check_condition_design(rows, study.design, fmt::format("study {}", study.name));
  for (const auto& w : r.design.warnings) note_left_out(r.diagnostics, "design", w);
}

bool within(const StudyResults& r) { return r.design.design == models::ConditionDesign::within; }

// Stage 3. Table 1: one-sample per condition, and A against B when asked (paired when the
// conditions are within participants).
void build_tables(const Study& study, const Comparison& compare, const tables::Table1Options& t,
                  StudyResults& r) {
  tables::Table1Options one = t;
  one.design = r.design.design;  // the design the study checked (declared or read off the data)
  r.table1 = tables::build_table1(r.scores, one);
  if (compare) {
    tables::Table1Options c = t;
    c.compare = compare;
    c.var_equal = study.settings.var_equal && !within(r);
    c.paired = study.settings.paired || within(r);
    r.comparison = tables::build_table1(r.scores, c);
  }
}

// Stage 4. The mixed ANOVA (GG, as afex) and the mixed models (as lme4/lmerTest): left out, with
// the reason, when the design does not allow them (one iteration, one condition, a constant
// metric).
void fit_models(const Study& study, const Comparison& compare,
                const std::vector<std::string>& metrics, const std::string& prefix,
                StudyResults& r) {
  Diagnostics& d = r.diagnostics;
  try {
    r.anova = tables::build_anova_report(r.scores, models::SphericityCorrection::GG, false, {}, within(r));
  } catch (const InvalidData& e) {
    note_left_out(d, "anova", fmt::format("no mixed ANOVA: {}", without_prefix(e.what(), prefix)));
  }
  // The model of condition x iteration needs two of each (and models::fit_mixed_model does not
  // yet refuse fewer cleanly).
  if (r.scores.conditions().size() < 2 || r.scores.iterations().size() < 2) {
    note_left_out(d, "model",
                  "no mixed model: it needs at least two conditions and two iterations");
    return;
  }
  if (study.tests.test.alternative != stats::Alternative::two_sided) {
    note_left_out(d, "model", "no mixed model: its contrasts are two-sided (alternative = two.sided)");
    return;
  }
  tables::ModelOptions o;
  o.metrics = metrics;
  o.compare = compare;
  o.alpha = study.tests.alpha;
  o.conf_level = study.tests.test.conf_level;
  o.p_adjust = study.tests.p_adjust;
  o.apa = study.tests.apa;
  o.condition_within = within(r);
  try {
    r.model = tables::build_model_analysis(r.scores, o);
    o.trend = true;
    r.trend_model = tables::build_model_analysis(r.scores, o);
  } catch (const InvalidData& e) {
    note_left_out(d, "model", fmt::format("no mixed model: {}", without_prefix(e.what(), prefix)));
  }
}

// Who answered the questionnaire but has no scored trial, and the reverse. Only a warning: the
// two analyses are independent, and an anonymous questionnaire (its own ids) is a design, not an
// error; the report and standard error list the ids.
void compare_respondents(const io::Questionnaire& q, StudyResults& r) {
  Diagnostics& d = r.diagnostics;
  std::vector<std::string> log_ids;
  for (const auto& rec : r.scores.records) log_ids.push_back(rec.participant);
  io::ParticipantComparison pc = io::compare_participants(log_ids, q.participants);
  if (!pc.matches()) {
    const std::string why =
        pc.in_both == 0
            ? fmt::format("no participant id in common between the logs and the questionnaire "
                          "(as when the questionnaire is anonymous, or the ids are written "
                          "differently): {}",
                          pc.message())
            : pc.message();
    if (!pc.only_in_logs.empty()) {
      d.exclusions.push_back({"participants", "participant", pc.only_in_logs.size(),
                              "in the logs but not in the questionnaire",
                              first_ten(pc.only_in_logs), ""});
    }
    if (!pc.only_in_questionnaire.empty()) {
      d.exclusions.push_back({"participants", "participant", pc.only_in_questionnaire.size(),
                              "in the questionnaire but not in the logs",
                              first_ten(pc.only_in_questionnaire), ""});
    }
    d.warnings.push_back(fmt::format("participants: {}", why));
  }
  d.participants_compared = std::move(pc);
}

// Stage 5. The questionnaire, when the study has one.
void analyze_questionnaire(const Study& study, const Comparison& compare, StudyResults& r) {
  if (!study.answers) return;
  Diagnostics& d = r.diagnostics;
  const io::Questionnaire& q = *study.answers;
  d.questionnaire_rows = q.rows_read;
  d.respondents = q.participants.size();
  std::map<std::string, Exclusion> excluded;
  for (const auto& x : q.excluded) {
    Exclusion& e = excluded[x.reason];
    e.stage = "questionnaire";
    e.what = "respondent";
    e.reason = x.reason;
    ++e.count;
    if (e.examples.size() < 5) e.examples.push_back(x.id);
  }
  for (auto& [_, e] : excluded) d.exclusions.push_back(std::move(e));
  compare_respondents(q, r);
  r.likert = tables::analyze_likert(q, study.likert);
  if (compare) {
    tables::LikertSettings lc = study.likert;
    lc.compare = compare;
    lc.paired = within(r);  // each participant answered after each condition: compared paired
    r.likert_compare = tables::analyze_likert(q, lc);
  } else if (q.has_condition && q.condition_names().size() > 2) {
    // Three or more conditions and no pair named: the omnibus test per item (Friedman's within
    // participants), then every pair.
    try {
      tables::LikertSettings lc = study.likert;
      lc.paired = within(r);
      r.likert_conditions = tables::analyze_likert_conditions(q, lc);
    } catch (const InvalidData& e) {
      note_left_out(d, "questionnaire", fmt::format("no comparison of the conditions' answers: {}", e.what()));
    }
  }
}

// Stage 5b. The yes/no questions (questionnaire_yesno.csv), compared as the logs are.
void analyze_yes_no_answers(const Study& study, const Comparison& compare, StudyResults& r) {
  if (!study.yes_no_answers) return;
  tables::YesNoSettings s;
  s.test.conf_level = study.tests.test.conf_level;
  s.alpha = study.tests.alpha;
  const auto groups = study.yes_no_answers->condition_names();
  // Compared only when both conditions answered; otherwise described per condition.
  if (compare && study.yes_no_answers->has_condition &&
      std::find(groups.begin(), groups.end(), compare->first) != groups.end() &&
      std::find(groups.begin(), groups.end(), compare->second) != groups.end())
    s.compare = compare;
  s.paired = within(r);  // each participant answered after each condition: McNemar's test
  r.yes_no = tables::analyze_yes_no(*study.yes_no_answers, s);
}

// Stage 6. Figure data: the strategies shown (from the scores), the mean pad traces (the logs,
// streamed once more), condition x exposure per strategy (the wear-off of a strategy, H1) with
// its table, and the mixed model's fitted trend.
void collect_figure_data(const Study& study, const Scored& sc, const tables::Table1Options& t,
                         const std::vector<std::string>& metrics, StudyResults& r) {
  try {
    r.figures.labels = read_trial_labels(sc.path.string());
  } catch (const InvalidData& e) {
    r.figures.labels_note = without_prefix(e.what(), sc.prefix);
  }
  if (!r.figures.labels.empty()) {
    // Read as the scorer read them (other labs' options: decimal mark, headerless files, ...).
    const io::TraceOptions topt = metrics::reading_options(sc.settings);
    // Logs of K targets have no pad to average: their Design row says so instead (pointer_design.hpp).
    if (const std::string k = detail::pointer_design_note(study.logs, topt); !k.empty()) {
      r.design.note += (r.design.note.empty() ? "" : "; ") + k;
      note_left_out(r.diagnostics, "traces", "no mean pad traces: the logs are of K targets and a pointer");
    } else {
      r.figures.traces = mean_traces(study.logs, topt, r.figures.labels, t.test.conf_level);
    }
    for (const auto& m : metrics) {
      r.figures.exposure.push_back(
          metrics::exposure_trend(r.scores, r.figures.labels, m, t.test.conf_level));
    }
    // Its table (slopes per condition and their difference): two conditions, in the model's order.
    if (const std::size_t k = r.scores.conditions().size(); k > 2 && !study.compare) {
      // Two of three or more conditions would be an arbitrary pair: the lab names the pair.
      note_left_out(r.diagnostics, "exposure",
                    fmt::format("no condition x exposure table: it compares two conditions and the study has {}; "
                                "set compare = \"A,B\" in feint.toml to compare a pair",
                                k));
    } else if (r.model && !r.model->models.empty() && !r.model->models.front().group1.empty()) {
      const std::vector<std::string> order = {r.model->models.front().group1, r.model->models.front().group2};
      try {
        for (const auto& m : metrics)
          r.exposure.push_back(
              exposure_table(r.scores, r.figures.labels, m, order, t.test.conf_level, t.bf_prior_r, within(r)));
      } catch (const std::exception& e) {
        r.exposure.clear();  // the findings say why, from their own fit
        note_left_out(r.diagnostics, "exposure",
                      fmt::format("no condition x exposure table: {}", e.what()));
      }
    }
  }
  // The mixed model's fitted trend (the linear-trend model: the line the trend F-test is about).
  if (r.trend_model) {
    const tables::ModelOptions& o = r.trend_model->options;
    for (const auto& mm : r.trend_model->models) {
      r.figures.model_trends.push_back(
          {mm.metric,
           fmt::format("linear trend over the iterations, random {}",
                       o.random_slope ? "intercept and slope" : "intercept"),
           models::fitted_trend(mm.fit, t.test.conf_level)});
    }
  }
}

// Stage 6b. The map of a study of K targets and a pointer (metrics::mean_map): the scored trials'
// mean robot paths and pointers per strategy and version, the logs read as the scorer read them.
// A pad study has no map and nothing is said; a study of K targets without one says why (the
// report's figure notes).
void collect_map_data(const Study& study, const Scored& sc, StudyResults& r) {
  try {
    r.figures.map = mean_map(study.logs, metrics::reading_options(sc.settings), r.scores);
    if (r.figures.map && r.figures.map->trials == 0) {
      r.figures.map.reset();
      r.figures.map_note = "no scored trial was found again in the logs.";
    }
  } catch (const Error& e) {
    r.figures.map.reset();
    r.figures.map_note = without_prefix(e.what(), sc.prefix);
  }
}

}  // namespace

std::optional<std::pair<std::string, std::string>> default_comparison(
    const Study& study, const std::vector<std::string>& conditions) {
  if (study.compare || !study.config.empty() || conditions.size() != 2) return std::nullopt;
  std::vector<std::string> c = conditions;
  if (c[0].empty() || c[1].empty()) return std::nullopt;
  std::sort(c.begin(), c.end());
  if (c[1] == "adaptive") std::swap(c[0], c[1]);
  return std::pair{c[0], c[1]};
}

namespace {

// The comparison of the run: the one set, or the default one (said in the report's Design, and
// written into the printed settings so that they reproduce the run).
Comparison decide_comparison(const Study& study, StudyResults& r) {
  if (study.compare) return study.compare;
  Comparison c = default_comparison(study, r.scores.conditions());
  if (c) {
    r.comparison_note = fmt::format(
        "compared by default: the logs hold exactly these two conditions and no settings file "
        "names a comparison (set compare = \"A,B\" in feint.toml to choose)");
  }
  return c;
}

// The settings that reproduce the run: as given, with the comparison and the design that were
// decided without a setting written in, so that a rerun makes the same decisions on purpose.
void print_settings(const Study& study, const Comparison& compare, StudyResults& r) {
  AnalysisSettings printed = study.settings;
  if (!study.compare && compare) printed.compare = compare->first + "," + compare->second;
  if (!r.design.declared && !r.design.note.empty()) printed.design = std::string(models::to_string(r.design.design));
  r.settings_toml = settings_toml(printed);
}

// The one-sided tests of the confirmatory hypotheses with a direction: H1 on the comparison of
// the metrics, H2 on the questionnaire between the conditions (the findings' hypotheses).
void one_sided_tests(const Study& study, StudyResults& r) {
  for (const auto& h : r.hypotheses) {
    if (!h.confirmatory || (h.direction != "greater" && h.direction != "less")) continue;
    const stats::Alternative alt = stats::parse_alternative(h.direction);
    if (h.id == "H1" && r.comparison) {
      tables::Table1Options c = r.comparison->options;
      c.test.alternative = alt;
      r.comparison_one_sided = tables::build_table1(r.scores, c);
    }
    if (h.id == "H2" && r.likert_compare && study.answers) {
      tables::LikertSettings lc = r.likert_compare->settings;
      lc.test.alternative = alt;
      r.likert_compare_one_sided = tables::analyze_likert(*study.answers, lc);
    }
  }
}

}  // namespace

StudyResults analyze(const Study& study, const std::string& tool_version) {
  StudyResults r;
  r.study = study.name;
  r.tool_version = tool_version;
  r.settings_toml = settings_toml(study.settings);
  const detail::ScratchFolder scratch("feint-analyze");  // the scores file, removed however this ends
  const Scored scored = score_trials(study, tool_version, scratch.path(), r);
  const tables::Table1Options t = table1_options(study);
  const std::vector<std::string> metrics = metric_columns(t);
  load_scored(scored, metrics, r);
  check_design(study, metrics, r);
  const Comparison compare = decide_comparison(study, r);
  print_settings(study, compare, r);
  build_tables(study, compare, t, r);
  fit_models(study, compare, metrics, scored.prefix, r);
  analyze_questionnaire(study, compare, r);
  analyze_yes_no_answers(study, compare, r);
  collect_figure_data(study, scored, t, metrics, r);
  collect_map_data(study, scored, r);
  detail::fit_observer_stage(study.logs, metrics::reading_options(scored.settings), r);
  r.scores.path = "scores.csv";
  // Stage 7. The findings (docs/findings.md): what the study shows, and how strongly. A
  // confirmatory hypothesis with a direction is tested one-sided, in that direction.
  if (r.comparison && r.comparison->options.compare) {
    const auto& [a, b] = *r.comparison->options.compare;
    r.hypotheses = parse_hypotheses(study.settings.hypotheses, a, b);
    one_sided_tests(study, r);
  } else if (const auto conditions = r.scores.conditions(); conditions.size() > 2) {
    // Three or more conditions and no pair named: the omnibus tests and their pairs answer them.
    r.hypotheses = parse_hypotheses(study.settings.hypotheses, default_hypotheses(conditions));
  }
  r.findings = study_findings(r, t.metrics);
  for (auto& f : r.findings)
    for (const auto& h : r.hypotheses)
      if (f.hypothesis == h.id) f.confirmatory = h.confirmatory;
  return r;
}

}  // namespace feint::analysis

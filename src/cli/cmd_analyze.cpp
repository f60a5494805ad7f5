// `feint analyze STUDY`: a whole study in one command — score the pad-trace logs, tabulate them
// (the paper's Table 1 per condition and, if asked, condition A against B), and analyse the
// questionnaire, writing every table in every format into one output folder.
//
// A study folder holds `logs/` (pad-trace logs, any number of .csv/.csv.gz files), optionally
// `questionnaire.csv` (Likert), and optionally `feint.toml`, whose settings have the names of this
// command's options (read through CLI11's TOML/INI config reader). The command line wins over the
// file, so a script can change one setting without editing the study.
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analyze_anova.hpp"
#include "analyze_report.hpp"
#include "commands.hpp"
#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/io/questionnaire.hpp"
#include "feint/io/scores.hpp"
#include "feint/io/output.hpp"
#include "feint/metrics/score.hpp"
#include "feint/report/likert.hpp"
#include "feint/report/table1.hpp"
#include "feint/report/writers.hpp"
#include "feint/stats/p_adjust.hpp"
#include "output_folder.hpp"
#include "report_options.hpp"
#include "score_options.hpp"
#include "study_config.hpp"

#ifndef FEINT_VERSION
#define FEINT_VERSION "dev"
#endif

namespace feint::cli {

namespace {

namespace fs = std::filesystem;

struct AnalyzeArgs {
  std::string study;
  std::string out = "feint-analysis";
  std::string config;  // default: STUDY/feint.toml when it exists
  // Scoring.
  std::vector<std::string> logs;  // default: STUDY/logs
  ScoreOptions scoring;
  // Tables.
  std::vector<std::string> metrics;
  std::string compare;
  bool var_equal = false;
  bool paired = false;
  std::optional<double> equivalence;
  // Questionnaire.
  std::string questionnaire;  // default: STUDY/questionnaire.csv when it exists
  std::optional<double> likert_reference;
  std::string likert_scale = "1-7";
  std::vector<std::string> composites;
  std::vector<std::string> reverse;
  std::string layout = "auto";
  std::string labels;
  std::vector<std::string> items;
  std::string id_column = "participant";
  std::string condition_column = "condition";
  std::string item_column = "item";
  std::string response_column = "response";
  std::string alpha_missing = "pairwise";
  bool keep_unfinished = false;
  bool keep_previews = false;
  // Shared report settings.
  ReportOptions report;
  std::vector<std::string> formats = {"text", "markdown", "latex", "csv", "json"};
  FigureOptions figures;  // OUT/figures/ and OUT/report.html (analyze_report.cpp)
};

std::string extension(report::OutputFormat format) {
  switch (format) {
    case report::OutputFormat::text:
      return "txt";
    case report::OutputFormat::markdown:
      return "md";
    case report::OutputFormat::latex:
      return "tex";
    case report::OutputFormat::csv:
      return "csv";
    case report::OutputFormat::json:
      return "json";
  }
  return "txt";
}

std::vector<report::OutputFormat> resolve_formats(const std::vector<std::string>& names) {
  std::vector<report::OutputFormat> out;
  for (const auto& n : names) out.push_back(report::parse_output_format(n));
  if (out.empty())
    throw UsageError("--formats: name at least one of text, markdown, latex, csv, json");
  return out;
}

// The study's input files and folders; relative paths in the settings are relative to the study.
struct StudyInputs {
  std::vector<std::string> logs;  // files, folders or globs
  std::string questionnaire;      // "" = none
  std::string config;             // "" = none
  /// Everything the output folder must stay clear of.
  std::vector<std::string> all() const {
    std::vector<std::string> v = logs;
    for (const auto& p : {questionnaire, config}) {
      if (!p.empty()) v.push_back(p);
    }
    return v;
  }
};

StudyInputs locate_inputs(const AnalyzeArgs& a, const fs::path& study, std::string config) {
  auto in_study = [&](const std::string& p) {
    const fs::path path(p);
    return path.is_absolute() ? path.string() : (study / path).string();
  };
  StudyInputs in;
  in.config = std::move(config);
  for (const auto& l : a.logs) in.logs.push_back(in_study(l));
  if (in.logs.empty()) {
    if (!fs::is_directory(study / "logs")) {
      throw InvalidData(
          fmt::format("{}: no logs/ folder (put the pad-trace logs there, or name "
                      "them with --logs)",
                      a.study));
    }
    in.logs.push_back((study / "logs").string());
  }
  in.questionnaire = a.questionnaire.empty() ? "" : in_study(a.questionnaire);
  if (in.questionnaire.empty() && fs::exists(study / "questionnaire.csv")) {
    in.questionnaire = (study / "questionnaire.csv").string();
  }
  return in;
}

// The scores' sidecar records where the scores (and rejects) were written: in the staging folder
// until it is swapped in. Record the final folder instead.
void record_final_paths(const std::string& sidecar, const fs::path& staging,
                        const std::string& final_folder) {
  std::ifstream in(sidecar, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const auto unquoted = [](const std::string& s) {
    const std::string q = io::json_quote(s);
    return q.substr(1, q.size() - 2);
  };
  const std::string from = unquoted((staging / "").string());
  const std::string to = unquoted((fs::path(final_folder) / "").string());
  for (auto pos = text.find(from); pos != std::string::npos;
       pos = text.find(from, pos + to.size())) {
    text.replace(pos, from.size(), to);
  }
  io::write_file_atomically(sidecar, text);
}

void run(CLI::App& cmd, AnalyzeArgs& a) {
  const fs::path study(a.study);
  if (!fs::is_directory(study)) {
    throw IoError(fmt::format("study folder '{}' does not exist or is not a folder", a.study));
  }
  const std::string config = settings_file(a.config, study);
  if (!config.empty()) apply_settings_file(cmd, config, SettingsSection::analyze);

  const ResolvedReportOptions report_opts = resolve_report_options(a.report);
  const std::vector<report::OutputFormat> formats = resolve_formats(a.formats);
  const StudyInputs inputs = locate_inputs(a, study, config);

  // Everything is written into a staging folder, swapped in as a whole at the end (see
  // output_folder.hpp): a failed run leaves OUT as it was, and runs never mix.
  OutputFolder out(a.out, inputs.all());
  auto write_all = [&](const std::string& stem, auto&& render) {
    for (const auto f : formats) write_report(out.path(stem + "." + extension(f)), render(f));
  };

  // 1. Score every trial.
  metrics::ScoreSettings s = score_settings(a.scoring);
  s.tool_version = FEINT_VERSION;
  const std::string scores_path = out.path("scores.csv");
  const metrics::ScoreSummary scored = metrics::score_to_file(inputs.logs, s, scores_path);
  if (!scored.sidecar_path.empty()) {
    record_final_paths(scored.sidecar_path, out.staging(), a.out);
  }

  // 2. Table 1: one-sample per condition, and A against B when asked.
  report::Table1Options t;
  t.metrics = parse_metric_specs(a.metrics);
  t.alpha = report_opts.alpha;
  t.test = report_opts.test;
  t.p_adjust = report_opts.p_adjust;
  t.equivalence = a.equivalence;
  t.apa = report_opts.apa;
  io::ScoresOptions load;
  load.metrics.clear();
  for (const auto& m : t.metrics) load.metrics.push_back(m.column);
  const io::ScoresTable scores = io::load_scores(scores_path, load);

  const report::Table1 one_sample = report::build_table1(scores, t);
  write_all("table1", [&](report::OutputFormat f) {
    return report::render_table1(one_sample, f, report_opts.presentation);
  });
  std::optional<report::Table1> two_sample;
  if (!a.compare.empty()) {
    report::Table1Options c = t;
    c.compare = parse_compare(a.compare);
    c.var_equal = a.var_equal;
    c.paired = a.paired;
    two_sample.emplace(report::build_table1(scores, c));
    write_all("table1_compare",
              [&](report::OutputFormat f) {
                return report::render_table1(*two_sample, f, report_opts.presentation);
              });
  }
  const std::optional<report::AnovaReport> anova = analyze_anova(scores);  // docs/anova-power.md
  if (anova) {
    report::TablePresentation wide;  // analyze has no --label/--caption; table* applies to all
    wide.wide = report_opts.presentation.wide;
    write_all("anova",
              [&](report::OutputFormat f) { return report::render_anova(*anova, f, t.apa, wide); });
  }

  // 3. The questionnaire, when the study has one.
  std::optional<report::LikertAnalysis> likert, between;
  if (!inputs.questionnaire.empty()) {
    report::LikertSettings l;
    const auto [lo, hi] = io::parse_scale(a.likert_scale);
    l.load.scale_min = lo;
    l.load.scale_max = hi;
    l.load.reverse = a.reverse;
    l.load.layout = io::parse_questionnaire_layout(a.layout);
    if (!a.labels.empty()) l.load.labels = io::parse_label_map(a.labels);
    l.load.items = a.items;
    l.load.id_column = a.id_column;
    l.load.condition_column = a.condition_column;
    l.load.item_column = a.item_column;
    l.load.response_column = a.response_column;
    l.load.keep_unfinished = a.keep_unfinished;
    l.alpha_missing = stats::parse_alpha_missing(a.alpha_missing);
    l.load.keep_previews = a.keep_previews;
    for (const auto& c : a.composites) l.composites.push_back(report::parse_composite(c));
    l.reference = a.likert_reference;
    l.test = report_opts.test;
    l.alpha = report_opts.alpha;
    l.p_adjust = report_opts.p_adjust;
    l.apa = report_opts.apa;
    likert.emplace(report::analyze_likert_file(inputs.questionnaire, l));
    write_all("likert", [&](report::OutputFormat f) {
      return report::render_likert(*likert, f, report_opts.presentation);
    });
    write_report(out.path("likert_summary.csv"), report::likert_summary_csv(*likert));
    if (!a.compare.empty()) {
      report::LikertSettings lc = l;
      lc.compare = parse_compare(a.compare);
      between.emplace(report::analyze_likert_file(inputs.questionnaire, lc));
      write_all("likert_compare", [&](report::OutputFormat f) {
        return report::render_likert(*between, f, report_opts.presentation);
      });
    }
  }

  // 4. Figures and report.html, drawn into the staging folder like every other output.
  write_figures_and_report(
      {&cmd, a.study, out.staging().string(), config, inputs.logs, &s, &scored, scores_path,
       &scores, &one_sample, two_sample ? &*two_sample : nullptr, anova ? &*anova : nullptr,
       inputs.questionnaire, likert ? &*likert : nullptr, between ? &*between : nullptr,
       FEINT_VERSION},
      a.figures);

  const std::vector<std::string> written = out.commit(FEINT_VERSION);
  fmt::print(stderr,
             "feint analyze: {} rows read, {} trials scored, {} rejected; {} files written to {}\n",
             scored.rows_read, scored.trials_scored, scored.trials_rejected, written.size(), a.out);
}

}  // namespace

// CLI11 2.1: a list option otherwise swallows the positional STUDY that follows it
// (`--metric error=0.5 data/demo`); each occurrence takes one value (or one comma list).
CLI::Option* one_per_use(CLI::Option* opt) {
  return opt->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false);
}

void add_analyze_command(CLI::App& app) {
  auto args = std::make_shared<AnalyzeArgs>();
  auto* cmd = app.add_subcommand(
      "analyze",
      "Run a whole study: score the logs in STUDY/logs, tabulate them (Table 1 per condition, and "
      "A against B with --compare), analyse STUDY/questionnaire.csv if present; every table in "
      "every format goes to the output folder. Settings may also be given in STUDY/feint.toml, "
      "one `name = value` per option (without dashes); the command line wins.");
  cmd->add_option("study", args->study, "Study folder (logs/, questionnaire.csv, feint.toml)")
      ->required();
  cmd->add_option("-o,--output", args->out,
                  "Output folder, replaced as a whole when the run succeeds (new, empty, or "
                  "written by an earlier feint analyze; never inside the logs)")
      ->capture_default_str();
  cmd->add_option("--config", args->config,
                  "Settings file (TOML/INI; default STUDY/feint.toml when present)");
  auto* score = "Scoring (see feint score)";
  one_per_use(
      cmd->add_option(
          "--logs", args->logs,
          "Pad-trace logs: files, folders or globs, relative to STUDY (default: STUDY/logs)"))
      ->group(score);
  add_score_options(*cmd, args->scoring, score);
  auto* tables = "Tables (see feint table)";
  one_per_use(cmd->add_option("--metric", args->metrics,
                              "NAME=REF: metric column and reference mean "
                              "(default error=0.5 confusion=0.95)"))
      ->group(tables);
  cmd->add_option("--compare", args->compare,
                  "A,B: also compare condition A with B (tables and "
                  "questionnaire), e.g. adaptive,random")
      ->group(tables);
  cmd->add_flag("--var-equal", args->var_equal, "Student's t instead of Welch's")->group(tables);
  cmd->add_flag("--paired", args->paired, "Paired t (same participants in both)")->group(tables);
  cmd->add_option("--equivalence", args->equivalence, "TOST margin: '≈' must be earned")
      ->group(tables);
  auto* likert = "Questionnaire (see feint likert)";
  cmd->add_option("--questionnaire", args->questionnaire,
                  "Likert file, relative to STUDY "
                  "(default STUDY/questionnaire.csv when present)")
      ->group(likert);
  cmd->add_option("--likert-reference", args->likert_reference,
                  "Reference of the one-sample "
                  "tests (default: the scale midpoint; the paper used 3.5)")
      ->group(likert);
  cmd->add_option("--likert-scale", args->likert_scale, "MIN-MAX")
      ->capture_default_str()
      ->group(likert);
  one_per_use(cmd->add_option("--composite", args->composites,
                              "NAME=ITEM,ITEM,...: a multi-item scale "
                              "(repeatable)"))
      ->group(likert);
  one_per_use(cmd->add_option("--reverse", args->reverse, "Items to reverse-code")->delimiter(','))
      ->group(likert);
  one_per_use(cmd->add_option("--items", args->items,
                              "Items to analyse, in order; NAME=COLUMN renames (trust=Q5_1)")
                  ->delimiter(','))
      ->group(likert);
  cmd->add_option("--labels", args->labels,
                  "Text answers to scale points: \"Strongly disagree=1,Disagree=2,...\"")
      ->group(likert);
  cmd->add_option("--id-column", args->id_column, "Questionnaire: respondent id column")
      ->capture_default_str()
      ->group(likert);
  cmd->add_option("--condition-column", args->condition_column,
                  "Questionnaire: condition column")
      ->capture_default_str()
      ->group(likert);
  cmd->add_option("--layout", args->layout, "Questionnaire: long, wide or auto")
      ->capture_default_str()
      ->group(likert);
  cmd->add_option("--item-column", args->item_column, "Questionnaire, long layout: item column")
      ->capture_default_str()
      ->group(likert);
  cmd->add_option("--response-column", args->response_column,
                  "Questionnaire, long layout: response column")
      ->capture_default_str()
      ->group(likert);
  cmd->add_option("--alpha-missing", args->alpha_missing,
                  "Cronbach's alpha with missing answers: pairwise (psych's default) or complete")
      ->capture_default_str()
      ->group(likert);
  cmd->add_flag("--keep-unfinished", args->keep_unfinished,
                "Survey exports: keep unfinished responses (Finished False, Progress < 100)")
      ->group(likert);
  cmd->add_flag("--keep-previews", args->keep_previews,
                "Survey exports: keep Survey Preview / Test / Spam responses")
      ->group(likert);
  auto* out = "Output";
  one_per_use(cmd->add_option("--formats", args->formats, "Formats written for every table")
                  ->delimiter(',')
                  ->capture_default_str())
      ->group(out);
  add_figure_options(*cmd, args->figures, out);
  cmd->add_flag("--apa", args->report.apa, "Add APA-style strings")->group(out);
  cmd->add_flag("--latex-wide", args->report.latex_wide,
                "LaTeX table* (both columns of a two-column paper); each table has its own "
                "label, e.g. tab:feint-table1-adaptive-vs-random")
      ->group(out);
  cmd->add_option("--alpha", args->report.alpha, "Significance level")
      ->capture_default_str()
      ->group(out);
  cmd->add_option("--alternative", args->report.alternative, "two.sided, greater or less")
      ->capture_default_str()
      ->group(out);
  cmd->add_option("--conf-level", args->report.conf_level, "Confidence level")
      ->capture_default_str()
      ->group(out);
  cmd->add_option("--p-adjust", args->report.p_adjust,
                  "none, bonferroni, holm, hochberg, hommel, "
                  "BH or BY (family: one metric column / the items)")
      ->capture_default_str()
      ->group(out);
  cmd->callback([cmd, args] { run(*cmd, *args); });
}

}  // namespace feint::cli

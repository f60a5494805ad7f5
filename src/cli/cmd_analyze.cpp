// `feint analyze STUDY`: a whole study in one command. The pipeline is the library's
// (feint/analysis: load_study -> analyze -> StudyResults; feint/publish: write_study); this file
// only binds the options and prints what happened.
//
// A study folder holds `logs/`, optionally `questionnaire.csv` and `feint.toml`, whose settings
// have the names of this command's options (read through CLI11's TOML/INI config reader). The
// command line wins over the file, so a script can change one setting without editing the study.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "feint/analysis/analyze.hpp"
#include "feint/analysis/findings.hpp"
#include "feint/commands/analyze_command.hpp"
#include "feint/error.hpp"
#include "feint/publish/study_report.hpp"
#include "options.hpp"

namespace feint::cli {

namespace {

namespace fs = std::filesystem;

struct AnalyzeArgs {
  std::string study;
  std::string out;  // default: feint-analysis in the current folder (said on standard error)
  std::string config;
  analysis::AnalysisSettings s;
};

void run(CLI::App& cmd, AnalyzeArgs& a) {
  if (!fs::is_directory(a.study)) {
    throw IoError(fmt::format("study folder '{}' does not exist or is not a folder", a.study));
  }
  const std::string config = settings_file(a.config, a.study);
  if (!config.empty()) apply_settings_file(cmd, config, SettingsSection::analyze);
  const analysis::Study study = analysis::load_study(a.study, a.s, config);
  const std::string out = a.out.empty() ? std::string("feint-analysis") : a.out;
  const analysis::StudyResults results = analysis::analyze(study, FEINT_VERSION);
  for (const auto& w : results.diagnostics.warnings) fmt::print(stderr, "feint: warning: {}\n", w);
  // The Reproduce line runs from the report's folder: its paths are relative to it.
  const std::string command = commands::quoted_command_line(commands::process_arguments(), out);
  const publish::WrittenStudy written = publish::write_study(study, results, out, command);
  // What the study shows (docs/findings.md), also in OUT/findings.json and first in the report.
  if (!results.findings.empty()) fmt::print("{}", analysis::findings_text(results.findings));
  fmt::print(
      stderr, "{}",
      commands::run_summary(study, results, written.files.size(), written.folder, a.out.empty()));
}

}  // namespace

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
                  "written by an earlier feint analyze; never inside the logs; default "
                  "feint-analysis in the current folder)");
  cmd->add_option("--config", args->config,
                  "Settings file (TOML/INI; default STUDY/feint.toml when present)");
  // Each block's options are shown under its heading in --help.
  cmd->option_defaults()->group("Scoring (see feint score)");
  one_per_use(cmd->add_option(
      "--logs", args->s.logs,
      "Pad-trace logs: files, folders or globs, relative to STUDY (default: STUDY/logs)"));
  add_score_options(*cmd, args->s.scoring, "Scoring (see feint score)");
  cmd->option_defaults()->group("Tables (see feint table)");
  one_per_use(cmd->add_option("--metric", args->s.metrics,
                              "NAME=REF: metric column and reference mean "
                              "(default error=0.5 confusion=0.95@raw)"));
  cmd->add_option("--compare", args->s.compare,
                  "A,B: also compare condition A with B (tables and "
                  "questionnaire), e.g. adaptive,random");
  cmd->add_flag("--var-equal", args->s.var_equal, "Student's t instead of Welch's");
  cmd->add_flag("--paired", args->s.paired, "Paired t (same participants in both)");
  cmd->add_option("--design", args->s.design, analysis::kDesignHelp);
  cmd->add_option("--equivalence", args->s.equivalence, "TOST margin: '≈' must be earned");
  one_per_use(cmd->add_option("--hypothesis", args->s.hypotheses, "ID:KEY=VALUE, e.g. H1:confirmatory=true"));
  cmd->option_defaults()->group("Questionnaire (see feint likert)");
  cmd->add_option("--questionnaire", args->s.questionnaire,
                  "Likert file, relative to STUDY "
                  "(default STUDY/questionnaire.csv when present)");
  add_questionnaire_options(*cmd, args->s.likert, true, "Questionnaire (see feint likert)");
  cmd->option_defaults()->group("Output");
  one_per_use(cmd->add_option("--formats", args->s.formats, "Formats written for every table")
                  ->capture_default_str()
                  ->delimiter(','));
  cmd->add_flag("--no-figures", args->s.no_figures,
                "Do not draw the figures (OUT/figures/); report.html then has tables only");
  cmd->add_flag("--no-report", args->s.no_report, "Do not write OUT/report.html and report.md");
  one_per_use(cmd->add_option("--figure-formats", args->s.figure_formats,
                              "Figure file formats: pdf (for LaTeX), svg (web), png (300 dpi)")
                  ->capture_default_str()
                  ->delimiter(','));
  cmd->add_flag("--apa", args->s.report.apa, "Add APA-style strings");
  cmd->add_flag("--latex-wide", args->s.report.latex_wide,
                "LaTeX table* (both columns of a two-column paper); each table has its own "
                "label, e.g. tab:feint-table1-adaptive-vs-random");
  cmd->add_option("--alpha", args->s.report.alpha, "Significance level")->capture_default_str();
  cmd->add_option("--alternative", args->s.report.alternative, "two.sided, greater or less")
      ->capture_default_str();
  cmd->add_option("--conf-level", args->s.report.conf_level, "Confidence level")
      ->capture_default_str();
  cmd->add_option("--p-adjust", args->s.report.p_adjust,
                  "none, bonferroni, holm, hochberg, hommel, "
                  "BH or BY (family: one metric column / the items)")
      ->capture_default_str();
  cmd->add_option("--bf-prior-scale", args->s.report.bf_prior_scale, analysis::kBfPriorScaleHelp)
      ->capture_default_str();
  cmd->callback([cmd, args] { run(*cmd, *args); });
}

}  // namespace feint::cli

// src/cli/options.hpp - command-line options shared by several commands: the report options
// (`feint table`, `likert`, `describe`, ...) and the atomic write of their rendered output, the
// scoring options (`feint score`, `analyze`), and the study's settings file (feint.toml) of
// `feint analyze` (top-level keys and [analyze]) and `feint collect` ([collect]).
// A one-table command: ReportCommand<LibraryOptions> bound with add_report_options, and
// run_report(args, library_function) as its callback.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "feint/analysis/settings.hpp"
#include "feint/io/scores.hpp"
#include "feint/tables/table1.hpp"
#include "feint/tables/writers.hpp"
#include "feint/stats/htest.hpp"
#include "feint/stats/p_adjust.hpp"

namespace feint::cli {

/// The option values and their checks live in the library (feint/analysis/settings.hpp).
using analysis::parse_compare;
using analysis::parse_metric_specs;
using analysis::parse_p_adjust_option;
using analysis::ReportOptions;
using analysis::resolve_report_options;
using analysis::ResolvedReportOptions;

/// Which of the shared options a command offers (describe has no tests: only format and output).
struct ReportOptionSet {
  bool tests = true;          ///< --apa --alpha --alternative --conf-level --p-adjust
  bool presentation = false;  ///< --label --caption --latex-wide
  bool bayes = false;         ///< --bf-prior-scale (the commands that compute Bayes factors)
};

/// Registers `--format`, `-o/--output` and (unless `set.tests` is false) `--apa`, `--alpha`,
/// `--alternative`, `--conf-level`, `--p-adjust` on `cmd`, bound to `options` (which must outlive
/// the parse).
void add_report_options(CLI::App& cmd, ReportOptions& options, ReportOptionSet set = {});

/// Registers `--participant-column`, `--iteration-column`, `--condition-column`, bound to the
/// column names of `columns` (the scores loader's options; must outlive the parse). `role` starts
/// each description, e.g. "Pilot: " for a pilot file.
void add_scores_column_options(CLI::App& cmd, io::ScoresOptions& columns,
                               std::string_view role = "");

/// Registers `--label`, `--caption`, `--latex-wide` (in CLI11 group `group` when not empty).
void add_presentation_options(CLI::App& cmd, ReportOptions& options, const std::string& group = "");

/// Registers the questionnaire options (analysis::LikertOptions): --layout, --scale, --labels,
/// --items, the column names, --reverse, --composite, --reference, --alpha-missing,
/// --keep-unfinished, --keep-previews; `in_analyze` names the scale and the reference
/// --likert-scale and --likert-reference (feint analyze's tables have a reference of their own).
void add_questionnaire_options(CLI::App& cmd, analysis::LikertOptions& options, bool in_analyze,
                               const std::string& group = "");

/// CLI11 2.1: a list option otherwise swallows a positional that follows it (`--metric
/// error=0.5 data/demo`); each occurrence takes one value (or one comma list). Returns `opt`.
CLI::Option* one_per_use(CLI::Option* opt);

/// Writes `content` to `path` atomically (temporary file + rename; `-` = standard output).
void write_report(const std::string& path, std::string_view content);

/// A one-table command's options: the library's and the shared report options.
template <class Options>
struct ReportCommand {
  Options o;
  ReportOptions report;
};

/// Resolves the report options, renders with `render(options, resolved)` (a library call) and
/// writes the text to -o.
template <class Options, class Render>
void run_report(const ReportCommand<Options>& a, Render render) {
  const ResolvedReportOptions r = resolve_report_options(a.report);
  write_report(r.output, render(a.o, r));
}

// --- scoring options
using analysis::score_settings;
using analysis::ScoreOptions;

/// Registers --trim, --trim-start, --trim-end, --deadband, --belief-deadband, --confusion-norm,
/// --pad-speed, then the loader options, on `cmd` (in help group `group`, if not empty).
void add_score_options(CLI::App& cmd, ScoreOptions& options, const std::string& group = "");

/// The loader options, how to READ logs (every command that reads logs takes them): --map,
/// --delimiter, --on-error, --time-unit, --decimal, --no-header, --columns, --iteration-base,
/// --participant-from-path, --samples-column, --single-condition, bound to `options`.
void add_loader_options(CLI::App& cmd, ScoreOptions& options, const std::string& group = "");

// --- the settings file
/// The settings file of a run: `given` (--config) when set, else STUDY/feint.toml when it exists,
/// else "" (no settings file).
std::string settings_file(const std::string& given, const std::filesystem::path& study);

/// Which keys of the settings file a command takes.
enum class SettingsSection {
  analyze,  ///< top-level keys and [analyze]; [collect] is skipped, any other section is an error
  collect,  ///< [collect] only; everything else belongs to feint analyze and is skipped
};

/// Applies the settings file `path` (TOML/INI, CLI11's parser) to every option of `cmd` that the
/// command line left unset: the command line wins. A key that is no option of `cmd` (without
/// dashes) or a value the option rejects is InvalidData naming the file and the key; an unreadable
/// file is IoError.
void apply_settings_file(CLI::App& cmd, const std::string& path, SettingsSection section);

}  // namespace feint::cli

// A study's inputs, located and checked once (see feint/analysis/study.hpp).
#include "feint/analysis/study.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "feint/error.hpp"
#include "feint/analysis/hypotheses.hpp"
#include "feint/io/trace.hpp"
#include "feint/stats/reliability.hpp"
#include "feint/tables/yes_no.hpp"

namespace feint::analysis {

namespace fs = std::filesystem;

std::string display_path(const std::string& path, const std::string& base) {
  if (path.empty()) return path;
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  const fs::path b = fs::weakly_canonical(fs::absolute(base.empty() ? "." : base, ec), ec);
  fs::path rel = p.lexically_relative(b);
  if (rel.empty() || *rel.begin() == "..") {
    rel = p.lexically_relative(fs::weakly_canonical(fs::current_path(ec), ec));
  }
  if (rel.empty()) return fs::path(path).filename().string();
  return rel.generic_string();
}

namespace {

std::filesystem::path canonical_of(const std::string& p) {
  std::error_code ec;
  const fs::path c = fs::weakly_canonical(fs::absolute(p, ec), ec);
  return ec ? fs::absolute(p).lexically_normal() : c;
}

}  // namespace

std::string path_from(const std::string& path_text, const std::string& folder_text) {
  const fs::path path = canonical_of(path_text), from = canonical_of(folder_text);
  if (path == from) return (fs::path("..") / from.filename()).generic_string();
  auto p = path.begin(), f = from.begin();
  std::size_t shared = 0;
  for (; p != path.end() && f != from.end() && *p == *f; ++p, ++f) ++shared;
  if (shared <= 1) return (fs::path(kPathPlaceholder) / path.filename()).generic_string();
  return path.lexically_relative(from).generic_string();
}

std::vector<std::string> Study::inputs() const {
  std::vector<std::string> v = log_inputs;
  for (const auto& p : {questionnaire, config}) {
    if (!p.empty()) v.push_back(p);
  }
  if (yes_no_answers) v.push_back(yes_no_answers->source);
  return v;
}

Study load_study(const std::string& folder, const AnalysisSettings& a, const std::string& config) {
  const fs::path study(folder);
  if (!fs::is_directory(study)) {
    throw IoError(fmt::format("study folder '{}' does not exist or is not a folder", folder));
  }
  Study s;
  s.folder = folder;
  // The folder's own name, also for "." or "data/demo/" (absolute "/x/demo/." normalises to
  // "/x/demo/", whose filename() is empty).
  fs::path named = fs::absolute(study).lexically_normal();
  if (named.filename().empty()) named = named.parent_path();
  s.name = named.filename().string();
  if (s.name.empty()) s.name = "study";  // the root folder
  s.config = config;
  s.settings = a;

  // Typed settings first: a usage error is reported before any file is read.
  s.scoring = score_settings(a.scoring);
  s.tests = resolve_report_options(a.report);
  s.metrics = parse_metric_specs(a.metrics);
  (void)parse_hypotheses(a.hypotheses, "A", "B");  // a bad [hypotheses] before any file is read
  // One scale: refused here, before a log is read, not found as "reference outside the data".
  tables::check_reference_scales(s.metrics, metrics::to_string(s.scoring.metrics.norm),
                                 "the study's settings");
  s.design = models::parse_condition_design(a.design);
  if (!a.compare.empty()) {
    s.compare = parse_compare(a.compare);
    // A log without a condition column is then refused, not pooled.
    s.scoring.reading.expected_conditions = {s.compare->first, s.compare->second};
  }
  for (const auto& n : a.formats) s.formats.push_back(tables::parse_output_format(n));
  if (s.formats.empty()) {
    throw UsageError("--formats: name at least one of text, markdown, latex, csv, json");
  }

  auto in_study = [&](const std::string& p) {
    const fs::path path(p);
    return path.is_absolute() ? path.string() : (study / path).string();
  };
  std::vector<std::string> inputs;
  for (const auto& l : a.logs) inputs.push_back(in_study(l));
  if (inputs.empty()) {
    if (!fs::is_directory(study / "logs")) {
      throw InvalidData(fmt::format(
          "{}: no logs/ folder (put the pad-trace logs there, or name them with --logs)", folder));
    }
    inputs.push_back((study / "logs").string());
  }
  s.log_inputs = inputs;
  s.logs = io::expand_inputs(inputs);
  s.questionnaire = a.questionnaire.empty() ? "" : in_study(a.questionnaire);
  if (s.questionnaire.empty() && fs::exists(study / "questionnaire.csv")) {
    s.questionnaire = (study / "questionnaire.csv").string();
  }

  s.likert = likert_settings(a.likert, s.tests);
  if (!s.questionnaire.empty()) s.answers = io::load_questionnaire(s.questionnaire, s.likert.load);
  if (fs::exists(study / "questionnaire_yesno.csv")) {
    io::QuestionnaireOptions o = tables::yes_no_load_options();
    o.id_column = s.likert.load.id_column;
    o.condition_column = s.likert.load.condition_column;
    s.yes_no_answers = io::load_questionnaire((study / "questionnaire_yesno.csv").string(), o);
  }
  return s;
}

}  // namespace feint::analysis

// feint.toml of a run (see feint/analysis/settings.hpp).
#include "feint/analysis/settings.hpp"

#include <fmt/format.h>

#include "feint/io/number.hpp"

namespace feint::analysis {

namespace {

// A TOML basic string (CLI11's TOML reader takes the same escapes).
std::string quoted(const std::string& s) {
  std::string o = "\"";
  for (const char c : s) {
    switch (c) {
      case '"': o += "\\\""; break;
      case '\\': o += "\\\\"; break;
      case '\n': o += "\\n"; break;
      case '\t': o += "\\t"; break;
      default: o += c;
    }
  }
  return o + "\"";
}

struct Toml {
  std::string text;
  void str(const char* key, const std::string& v) { text += fmt::format("{} = {}\n", key, quoted(v)); }
  void num(const char* key, double v) { text += fmt::format("{} = {}\n", key, io::format_double(v)); }
  void flag(const char* key, bool v) { text += fmt::format("{} = {}\n", key, v ? "true" : "false"); }
  void opt(const char* key, const std::optional<double>& v, const char* unset) {
    if (v) {
      num(key, *v);
    } else {
      text += fmt::format("# {} = ...  ({})\n", key, unset);
    }
  }
  // An empty list is a comment: CLI11 would read `[]` as one empty value.
  void list(const char* key, const std::vector<std::string>& v, const char* unset) {
    if (v.empty()) {
      text += fmt::format("# {} = [...]  ({})\n", key, unset);
      return;
    }
    std::string items;
    for (const auto& x : v) items += (items.empty() ? "" : ", ") + quoted(x);
    text += fmt::format("{} = [{}]\n", key, items);
  }
  void maybe(const char* key, const std::string& v, const char* unset) {
    if (v.empty()) {
      text += fmt::format("# {} = \"\"  ({})\n", key, unset);
    } else {
      str(key, v);
    }
  }
};

}  // namespace

std::string settings_toml(const AnalysisSettings& a) {
  Toml t;
  t.text = "# feint analyze settings: feint analyze --config THIS_FILE STUDY reproduces the run.\n"
           "# Paths are relative to the study folder.\n\n# Scoring\n";
  t.list("logs", a.logs, "default: logs/");
  const ScoreOptions& s = a.scoring;
  if (s.trim_start || s.trim_end) {
    t.opt("trim-start", s.trim_start ? s.trim_start : s.trim, "default 0.05");
    t.opt("trim-end", s.trim_end ? s.trim_end : s.trim, "default 0.05");
  } else {
    t.opt("trim", s.trim, "default 0.05 at both ends");
  }
  t.num("deadband", s.deadband);
  t.str("confusion-norm", s.norm);
  t.opt("pad-speed", s.pad_speed, "default: the logs' pad_speed column");
  t.list("map", s.maps, "none: the logs use feint's column names");
  t.maybe("delimiter", s.delimiter, "detected per file");
  t.str("on-error", s.on_error);
  t.str("time-unit", s.time_unit);
  t.text += "\n# Tables\n";
  t.list("metric", a.metrics, "default: error=0.5 and confusion=0.95@raw");
  t.maybe("compare", a.compare, "no comparison of two conditions");
  t.maybe("design", a.design, "read off the data: between or within participants");
  t.list("hypothesis", a.hypotheses, "the paper's H1 and H2");
  t.flag("var-equal", a.var_equal);
  t.flag("paired", a.paired);
  t.opt("equivalence", a.equivalence, "no equivalence test");
  t.text += "\n# Questionnaire\n";
  const LikertOptions& l = a.likert;
  t.maybe("questionnaire", a.questionnaire, "default: questionnaire.csv when present");
  t.opt("likert-reference", l.reference, "default: the scale midpoint");
  t.str("likert-scale", l.scale);
  t.list("composite", l.composites, "none");
  t.list("reverse", l.reverse, "none");
  t.list("items", l.items, "every item of the file");
  t.maybe("labels", l.labels, "built-in agree scales");
  t.str("id-column", l.id_column);
  t.str("condition-column", l.condition_column);
  t.str("layout", l.layout);
  t.str("item-column", l.item_column);
  t.str("response-column", l.response_column);
  t.str("alpha-missing", l.alpha_missing);
  t.flag("keep-unfinished", l.keep_unfinished);
  t.flag("keep-previews", l.keep_previews);
  t.text += "\n# Output\n";
  t.list("formats", a.formats, "none");
  t.flag("no-figures", a.no_figures);
  t.flag("no-report", a.no_report);
  t.list("figure-formats", a.figure_formats, "none");
  t.flag("apa", a.report.apa);
  t.flag("latex-wide", a.report.latex_wide);
  t.num("alpha", a.report.alpha);
  t.str("alternative", a.report.alternative);
  t.num("conf-level", a.report.conf_level);
  t.str("p-adjust", a.report.p_adjust);
  t.str("bf-prior-scale", a.report.bf_prior_scale);
  return t.text;
}

}  // namespace feint::analysis

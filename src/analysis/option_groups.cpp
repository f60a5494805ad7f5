// Settings as text -> typed settings (see feint/analysis/settings.hpp).
#include "feint/analysis/settings.hpp"

#include <fmt/format.h>

#include <cmath>
#include <set>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/io/questionnaire.hpp"
#include "feint/stats/bayes_factor.hpp"
#include "feint/stats/reliability.hpp"

namespace feint::analysis {

namespace {

char parse_delimiter(const std::string& text) {
  const std::string d = io::to_lower(text);
  if (d.empty() || d == "auto") return 0;
  if (d == "," || d == "comma") return ',';
  if (d == ";" || d == "semicolon") return ';';
  if (d == "\t" || d == "\\t" || d == "tab") return '\t';
  if (d == "|" || d == "pipe") return '|';
  throw UsageError(fmt::format("--delimiter '{}': expected , ; tab | or auto", text));
}

}  // namespace

metrics::ScoreSettings score_settings(const ScoreOptions& o) {
  metrics::ScoreSettings s;
  if (o.trim) s.metrics.trim_start = s.metrics.trim_end = *o.trim;
  if (o.trim_start) s.metrics.trim_start = *o.trim_start;
  if (o.trim_end) s.metrics.trim_end = *o.trim_end;
  s.metrics.deadband = o.deadband;
  s.metrics.belief_deadband = o.belief_deadband;
  const auto norm = metrics::parse_confusion_norm(o.norm);
  if (!norm) throw UsageError(fmt::format("--confusion-norm '{}': expected speed or raw", o.norm));
  s.metrics.norm = *norm;
  s.metrics.pad_speed = o.pad_speed;
  for (const auto& m : o.maps) {
    const auto eq = m.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == m.size()) {
      throw UsageError(fmt::format("--map '{}': expected NAME=COLUMN, e.g. --map pad=position", m));
    }
    const std::string name = io::to_lower(io::trim(m.substr(0, eq)));
    if (s.column_map.count(name) != 0) {
      throw UsageError(fmt::format("--map: '{}' is mapped twice", name));
    }
    s.column_map[name] = std::string(io::trim(m.substr(eq + 1)));
  }
  s.delimiter = parse_delimiter(o.delimiter);
  if (o.on_error != "strict" && o.on_error != "skip") {
    throw UsageError(fmt::format("--on-error '{}': expected strict or skip", o.on_error));
  }
  s.on_error = o.on_error == "skip" ? metrics::OnError::skip : metrics::OnError::strict;
  const auto unit = metrics::parse_time_unit(o.time_unit);
  if (!unit) throw UsageError(fmt::format("--time-unit '{}': expected s or ms", o.time_unit));
  s.time_unit = *unit;
  if (!o.decimal.empty()) {
    if (o.decimal == "." || io::to_lower(o.decimal) == "point") {
      s.reading.decimal = '.';
    } else if (o.decimal == "," || io::to_lower(o.decimal) == "comma") {
      s.reading.decimal = ',';
    } else {
      throw UsageError(fmt::format("--decimal '{}': expected . or ,", o.decimal));
    }
    if (s.reading.decimal == ',' && s.delimiter == ',') {
      throw UsageError("--decimal , with --delimiter , : the comma cannot be both; a European "
                       "export is read with --delimiter ';' --decimal ,");
    }
  }
  s.reading.no_header = o.no_header;
  if (!o.columns.empty()) {
    if (!o.no_header) {
      throw UsageError("--columns names the columns of a file without a header: give --no-header "
                       "too (a file with a header is renamed with --map FIELD=COLUMN)");
    }
    for (auto& name : io::split_csv_line(o.columns)) s.reading.column_names.emplace_back(io::trim(name));
  }
  if (o.no_header && s.reading.column_names.empty() && s.column_map.empty()) {
    throw UsageError("--no-header needs the columns' names: --columns participant,iteration,"
                     "target,t,pad (in the file's order) or --map FIELD=N for each field (N = "
                     "column number from 1)");
  }
  if (!o.iteration_base.empty()) s.reading.iteration_base = o.iteration_base == "0" ? 0 : 1;
  s.reading.participant_from_path = o.participant_from_path;
  s.reading.samples_column = o.samples_column;
  s.reading.single_condition = o.single_condition;
  return s;
}

ResolvedReportOptions resolve_report_options(const ReportOptions& o) {
  ResolvedReportOptions r;
  r.format = tables::parse_output_format(o.format);
  r.output = o.output.empty() ? std::string("-") : o.output;
  r.apa = o.apa;
  if (!(std::isfinite(o.alpha) && o.alpha > 0.0 && o.alpha < 1.0)) {
    throw UsageError(fmt::format("--alpha {}: expected a number in (0, 1), e.g. 0.05", o.alpha));
  }
  r.alpha = o.alpha;
  if (!(std::isfinite(o.conf_level) && o.conf_level > 0.0 && o.conf_level < 1.0)) {
    throw UsageError(
        fmt::format("--conf-level {}: expected a number in (0, 1), e.g. 0.95", o.conf_level));
  }
  r.test.conf_level = o.conf_level;
  try {
    r.test.alternative = stats::parse_alternative(o.alternative);
  } catch (const UsageError&) {
    throw UsageError(
        fmt::format("--alternative '{}': expected two.sided, greater or less", o.alternative));
  }
  r.p_adjust = parse_p_adjust_option(o.p_adjust);
  if (!o.label.empty()) tables::validate_latex_label(o.label);
  r.presentation.label = o.label;
  r.presentation.caption = o.caption;
  r.presentation.wide = o.latex_wide;
  r.bf_prior_r = parse_bf_prior_scale(o.bf_prior_scale);
  return r;
}

double parse_bf_prior_scale(std::string_view text) {
  const std::string s = io::to_lower(std::string(text));
  if (s == "medium") return stats::kJzsMediumScale;
  if (s == "wide") return 1.0;
  if (s == "ultrawide") return std::sqrt(2.0);
  const std::optional<double> r = io::parse_double(text);
  if (!r || !std::isfinite(*r) || !(*r > 0)) {
    throw UsageError(fmt::format(
        "--bf-prior-scale '{}': expected the Cauchy prior scale r of the JZS Bayes factor, a "
        "number > 0 (e.g. 0.5) or medium (sqrt(2)/2, the default), wide (1) or ultrawide (sqrt(2))",
        text));
  }
  return *r;
}

stats::PAdjustMethod parse_p_adjust_option(std::string_view text) {
  // R's p.adjust.methods, in any case (R itself is case-sensitive, but nobody means anything else
  // by "Holm" or "bh"); "fdr" is R's alias of BH.
  const std::string name = io::to_lower(io::trim(text));
  if (name == "none") return stats::PAdjustMethod::none;
  if (name == "bonferroni") return stats::PAdjustMethod::bonferroni;
  if (name == "holm") return stats::PAdjustMethod::holm;
  if (name == "hochberg") return stats::PAdjustMethod::hochberg;
  if (name == "hommel") return stats::PAdjustMethod::hommel;
  if (name == "bh" || name == "fdr") return stats::PAdjustMethod::BH;
  if (name == "by") return stats::PAdjustMethod::BY;
  throw UsageError(fmt::format("--p-adjust '{}': expected none, bonferroni, holm, hochberg, "
                               "hommel, BH (alias fdr) or BY, in any case",
                               text));
}

std::pair<std::string, std::string> parse_compare(const std::string& text) {
  const auto parts = io::split_csv_line(text);
  if (parts.size() != 2 || io::trim(parts[0]).empty() || io::trim(parts[1]).empty()) {
    throw UsageError(
        fmt::format("--compare '{}': expected two conditions A,B (e.g. adaptive,random)", text));
  }
  return {std::string(io::trim(parts[0])), std::string(io::trim(parts[1]))};
}

std::vector<tables::MetricSpec> parse_metric_specs(const std::vector<std::string>& texts) {
  if (texts.empty()) return tables::default_metrics();
  std::vector<tables::MetricSpec> specs;
  std::set<std::string> seen;
  for (const auto& m : texts) {
    auto spec = tables::parse_metric_spec(m);
    if (!seen.insert(io::to_lower(spec.column)).second) {
      throw UsageError(fmt::format("--metric '{}': metric '{}' given twice", m, spec.column));
    }
    specs.push_back(std::move(spec));
  }
  return specs;
}

namespace {

std::vector<std::string> split_lists(const std::vector<std::string>& values) {
  std::vector<std::string> out;
  for (const auto& v : values) {
    for (const auto& part : io::split_csv_line(v, ',')) {
      const auto t = io::trim(part);
      if (!t.empty()) out.emplace_back(t);
    }
  }
  return out;
}

}  // namespace

tables::LikertSettings likert_settings(const LikertOptions& o, const ResolvedReportOptions& r) {
  tables::LikertSettings s;
  s.load.layout = io::parse_questionnaire_layout(o.layout);
  const auto [lo, hi] = io::parse_scale(o.scale);
  s.load.scale_min = lo;
  s.load.scale_max = hi;
  if (!o.labels.empty()) s.load.labels = io::parse_label_map(o.labels);
  s.load.items = split_lists(o.items);
  s.load.id_column = o.id_column;
  s.load.condition_column = o.condition_column;
  s.load.item_column = o.item_column;
  s.load.response_column = o.response_column;
  s.load.reverse = split_lists(o.reverse);
  s.load.keep_unfinished = o.keep_unfinished;
  s.load.keep_previews = o.keep_previews;
  s.alpha_missing = stats::parse_alpha_missing(o.alpha_missing);
  for (const auto& c : o.composites) s.composites.push_back(tables::parse_composite(c));
  s.reference = o.reference;
  s.test = r.test;
  s.alpha = r.alpha;
  s.p_adjust = r.p_adjust;
  s.apa = r.apa;
  s.bf_prior_r = r.bf_prior_r;
  return s;
}

}  // namespace feint::analysis

#include "report_options.hpp"

#include <fmt/format.h>

#include <cmath>
#include <set>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/io/output.hpp"

namespace feint::cli {

void add_scores_column_options(CLI::App& cmd, io::ScoresOptions& columns, std::string_view role) {
  cmd.add_option("--participant-column", columns.participant_column,
                 fmt::format("{}Name of the participant column", role))
      ->capture_default_str();
  cmd.add_option("--iteration-column", columns.iteration_column,
                 fmt::format("{}Name of the iteration column", role))
      ->capture_default_str();
  cmd.add_option("--condition-column", columns.condition_column,
                 fmt::format("{}Name of the (optional) condition column", role))
      ->capture_default_str();
}

void add_presentation_options(CLI::App& cmd, ReportOptions& options, const std::string& group) {
  auto* label = cmd.add_option("--label", options.label,
                               "LaTeX \\label of the table (default: unique per table, e.g. "
                               "tab:feint-table1-adaptive-vs-random)");
  auto* caption =
      cmd.add_option("--caption", options.caption, "Caption of the table (default: describes it)");
  auto* wide = cmd.add_flag("--latex-wide", options.latex_wide,
                            "LaTeX table* (spans both columns of a two-column paper)");
  if (!group.empty()) {
    label->group(group);
    caption->group(group);
    wide->group(group);
  }
}

void add_report_options(CLI::App& cmd, ReportOptions& options, ReportOptionSet set) {
  cmd.add_option("--format", options.format,
                 "Output format: text (aligned table), markdown, latex (booktabs fragment), csv or "
                 "json (tidy: one row per test)")
      ->capture_default_str();
  cmd.add_option("-o,--output", options.output,
                 "Output file, written atomically (temporary file + rename); - = standard output")
      ->capture_default_str();
  if (set.presentation) add_presentation_options(cmd, options);
  if (!set.tests) return;
  cmd.add_flag("--apa", options.apa,
               "Add an APA-style string per test, e.g. 't(29) = 2.93, p = .007, d = 0.53' "
               "(column 'apa' in csv/json)");
  cmd.add_option("--alpha", options.alpha, "Significance level for the labels, in (0, 1)")
      ->capture_default_str();
  cmd.add_option("--alternative", options.alternative,
                 "Alternative hypothesis: two.sided, greater or less (as R's t.test)")
      ->capture_default_str();
  cmd.add_option("--conf-level", options.conf_level,
                 "Confidence level of the intervals (conf_low, conf_high), in (0, 1)")
      ->capture_default_str();
  cmd.add_option("--p-adjust", options.p_adjust,
                 "Multiple-comparison adjustment within a family (R's p.adjust): none, bonferroni, "
                 "holm, hochberg, hommel, BH (alias fdr), BY; any case")
      ->capture_default_str();
}

ResolvedReportOptions resolve_report_options(const ReportOptions& o) {
  ResolvedReportOptions r;
  r.format = report::parse_output_format(o.format);
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
  if (!o.label.empty()) report::validate_latex_label(o.label);
  r.presentation.label = o.label;
  r.presentation.caption = o.caption;
  r.presentation.wide = o.latex_wide;
  return r;
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

void write_report(const std::string& path, std::string_view content) {
  io::AtomicOutput out(path);
  out.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  out.commit();
}

std::pair<std::string, std::string> parse_compare(const std::string& text) {
  const auto parts = io::split_csv_line(text);
  if (parts.size() != 2 || io::trim(parts[0]).empty() || io::trim(parts[1]).empty()) {
    throw UsageError(
        fmt::format("--compare '{}': expected two conditions A,B (e.g. adaptive,random)", text));
  }
  return {std::string(io::trim(parts[0])), std::string(io::trim(parts[1]))};
}

std::vector<report::MetricSpec> parse_metric_specs(const std::vector<std::string>& texts) {
  if (texts.empty()) return report::default_metrics();
  std::vector<report::MetricSpec> specs;
  std::set<std::string> seen;
  for (const auto& m : texts) {
    auto spec = report::parse_metric_spec(m);
    if (!seen.insert(io::to_lower(spec.column)).second) {
      throw UsageError(fmt::format("--metric '{}': metric '{}' given twice", m, spec.column));
    }
    specs.push_back(std::move(spec));
  }
  return specs;
}

}  // namespace feint::cli

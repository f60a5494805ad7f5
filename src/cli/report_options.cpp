#include "report_options.hpp"

#include <fmt/format.h>

#include <cmath>
#include <set>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/io/output.hpp"

namespace feint::cli {

void add_report_options(CLI::App& cmd, ReportOptions& options, ReportOptionSet set) {
  cmd.add_option("--format", options.format,
                 "Output format: text (aligned table), markdown, latex (booktabs fragment), csv or "
                 "json (tidy: one row per test)")
      ->capture_default_str();
  cmd.add_option("-o,--output", options.output,
                 "Output file, written atomically (temporary file + rename); - = standard output")
      ->capture_default_str();
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
                 "holm, hochberg, hommel, BH, BY")
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
  try {
    r.p_adjust = stats::parse_p_adjust(o.p_adjust);
  } catch (const UsageError&) {
    throw UsageError(
        fmt::format("--p-adjust '{}': expected none, bonferroni, holm, hochberg, hommel, BH or BY",
                    o.p_adjust));
  }
  return r;
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

// The condition x exposure table (see feint/tables/exposure_render.hpp).
#include "feint/tables/exposure_render.hpp"

#include <fmt/format.h>

#include "feint/stats/p_adjust.hpp"

namespace feint::tables {

namespace {

/// Holm over a metric's strategies, as analysis::exposure_findings adjusts them.
std::vector<std::optional<double>> holm(const models::ExposureByCondition& e) {
  std::vector<std::optional<double>> p;
  for (const auto& d : e.differences) p.push_back(d.test.computed ? d.test.p_value : std::nullopt);
  return stats::p_adjust(p, stats::PAdjustMethod::holm);
}

std::string slope_cell(const models::ExposureSlope& s) {
  if (!s.test.computed || !s.test.estimate || !s.test.conf_low || !s.test.conf_high) return std::string(kNotComputable);
  return fmt::format("{:.4f} [{:.4f}, {:.4f}]", *s.test.estimate, *s.test.conf_low, *s.test.conf_high);
}

constexpr std::string_view kColumns[] = {"metric",  "strategy",  "condition",  "estimate", "std_error",
                                         "df",      "statistic", "p_value",    "p_adjusted", "conf_low",
                                         "conf_high", "conf_level", "note"};

Record record(const std::string& metric, const models::ExposureSlope& s, std::optional<double> adjusted) {
  const auto& t = s.test;
  return {Cell::str(metric),
          Cell::str(s.strategy),
          Cell::str(s.condition),
          Cell::num(t.estimate),
          t.computed ? Cell::num(s.std_error) : Cell::none(),
          Cell::num(t.df),
          Cell::num(t.statistic),
          Cell::num(t.p_value),
          Cell::num(adjusted),
          Cell::num(t.conf_low),
          Cell::num(t.conf_high),
          Cell::num(t.conf_level),
          t.note.empty() ? Cell::none() : Cell::str(t.note)};
}

}  // namespace

std::string render_exposure(const std::vector<ExposureTable>& tables, OutputFormat format) {
  if (format == OutputFormat::csv || format == OutputFormat::json) {
    std::vector<Record> records;
    for (const auto& t : tables) {
      for (const auto& s : t.result.slopes) records.push_back(record(t.metric, s, std::nullopt));
      const auto adj = holm(t.result);
      for (std::size_t i = 0; i < t.result.differences.size(); ++i)
        records.push_back(record(t.metric, t.result.differences[i], adj[i]));
    }
    const std::vector<std::string_view> cols(std::begin(kColumns), std::end(kColumns));
    return format == OutputFormat::csv ? write_csv(cols, records) : write_json(cols, records);
  }
  TextTable out;
  out.caption = "Condition \u00d7 exposure per strategy: exposure slopes (change per earlier exposure)";
  double conf = 0.95;
  std::string a = "A", b = "B";
  for (const auto& t : tables)
    if (!t.result.differences.empty() && !t.result.slopes.empty()) {
      const std::size_t k = t.result.differences.size();
      a = t.result.slopes.front().condition;
      b = t.result.slopes[k].condition;
      conf = t.result.differences.front().test.conf_level;
      break;
    }
  const std::string ci = fmt::format("{:g}% CI", 100 * conf);
  out.header = {"Strategy", fmt::format("{} slope [{}]", a, ci), fmt::format("{} slope [{}]", b, ci),
                fmt::format("Difference {} \u2212 {} [{}]", a, b, ci), "t", "df", "p", "p Holm"};
  out.right_align = {false, true, true, true, true, true, true, true};
  for (const auto& t : tables) {
    TextTable::Row sec;
    sec.section = true;
    sec.cells.assign(out.header.size(), "");
    sec.cells[0] = "Metric: " + t.metric;
    out.rows.push_back(sec);
    out.latex_cells.emplace_back(out.header.size());
    const std::size_t k = t.result.differences.size();
    if (k == 0) {
      for (const auto& s : t.result.slopes) {
        out.rows.push_back({{s.strategy, slope_cell(s), "", "", "", "", "", ""}, false});
        out.latex_cells.emplace_back(out.header.size());
      }
      continue;
    }
    const auto adj = holm(t.result);
    for (std::size_t i = 0; i < k; ++i) {
      const auto& d = t.result.differences[i];
      const bool ok = d.test.computed && d.test.statistic && d.test.df && d.test.p_value;
      out.rows.push_back({{d.strategy, slope_cell(t.result.slopes[i]), slope_cell(t.result.slopes[k + i]),
                           slope_cell(d), ok ? fmt::format("{:.2f}", *d.test.statistic) : "",
                           ok ? fmt::format("{:.1f}", *d.test.df) : "", ok ? format_p(d.test.p_value) : "",
                           ok && adj[i] ? format_p(adj[i]) : ""},
                          false});
      std::vector<std::string> latex(out.header.size());
      if (ok) latex[6] = format_p(d.test.p_value, PStyle::latex);
      if (ok && adj[i]) latex[7] = format_p(adj[i], PStyle::latex);
      out.latex_cells.push_back(std::move(latex));
    }
  }
  bool paired = false;
  for (const auto& t : tables)
    for (const auto& d : t.result.differences) paired = paired || d.test.test == "paired_t";
  out.notes.push_back(fmt::format(
      "Two-stage (slopes as outcomes): each participant's OLS slope of the metric on exposure (the "
      "number of the participant's earlier trials of the strategy{}) over their trials of the strategy, "
      "from participants with at least 2 trials at 2 distinct exposures; a condition's slope is the mean "
      "of its participants' slopes (one-sample t, df = n - 1), the difference between conditions {}. ",
      paired ? " in that condition" : "",
      paired ? "a paired t test on the slopes of the participants with one in both conditions (with d_z and "
               "the JZS Bayes factor in the findings)"
             : "a Welch t test on the participants' slopes (with Cohen's d and the JZS Bayes factor in the "
               "findings)") +
      "p Holm: Holm-adjusted over the strategies of the metric, as the findings use it "
      "(docs/findings.md).");
  out.latex_label = "tab:feint-exposure";
  return render_table(out, format);
}

}  // namespace feint::tables

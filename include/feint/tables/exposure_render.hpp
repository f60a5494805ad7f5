// feint/tables/exposure_render.hpp - the table of condition x exposure per strategy (H1):
// each strategy's exposure slope in each condition and the difference of the slopes between the
// conditions (models::exposure_slopes_by_condition), with the Holm adjustment over the strategies
// of a metric that the findings use (docs/findings.md).
#pragma once

#include <string>
#include <vector>

#include "feint/models/exposure.hpp"
#include "feint/tables/writers.hpp"

namespace feint::tables {

/// The exposure slopes of one metric.
struct ExposureTable {
  std::string metric;
  models::ExposureByCondition result;
};

/// Text, Markdown, LaTeX: one table, a section per metric, a row per strategy (the slope with its
/// CI in each condition, the difference with its CI, t, df, p and the Holm-adjusted p), and a note.
/// CSV/JSON: one tidy row per slope and per difference (metric, strategy, condition, estimate,
/// std_error, df, statistic, p_value, p_adjusted (differences only), conf_low, conf_high, conf_level,
/// note).
std::string render_exposure(const std::vector<ExposureTable>& tables, OutputFormat format);

}  // namespace feint::tables

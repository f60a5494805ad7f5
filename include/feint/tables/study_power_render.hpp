// feint/tables/study_power_render.hpp - `feint power observer` (power of an adaptive-vs-random
// study of simulated goal-inference participants) in text, Markdown, LaTeX, CSV and JSON.
#pragma once

#include <string>

#include "feint/tables/writers.hpp"
#include "feint/sim/study_power.hpp"

namespace feint::tables {

/// Tidy columns: participants, power, mc_se, mean_difference, studies, seed, alpha,
/// from_iteration, iterations, target_power, smallest_n. Default LaTeX label
/// "tab:feint-power-observer". `source` names where the observer's parameters came from.
std::string render_study_power(const sim::StudyPowerResult& result, const std::string& source,
                               OutputFormat format, const TablePresentation& presentation = {});

}  // namespace feint::tables

// feint/tables/power_render.hpp - `feint power` results in text, Markdown, booktabs LaTeX, tidy CSV
// and JSON (docs/anova-power.md).
#pragma once

#include <string>

#include "feint/models/power.hpp"
#include "feint/models/power_sim.hpp"
#include "feint/tables/writers.hpp"

namespace feint::tables {

/// Which quantity was solved for: "n", "delta" or "power".
std::string solved_for(const models::TTestPowerSpec& given);

/// Analytic t-test power. Tidy columns: method, type, alternative, solved, n1, n2, n1_ceiling,
/// n2_ceiling, delta, sd, sd2, alpha, tests, alpha_per_test, power, power_at_ceiling, df, ncp,
/// note. `presentation` (--label, --caption, --latex-wide) applies to the one table; default
/// label "tab:feint-power".
std::string render_t_test_power(const models::TTestPowerResult& result, const std::string& solved,
                                OutputFormat format, const TablePresentation& presentation = {});

/// Simulation power. Tidy columns: test, iteration, power, mc_se, studies, seed, n_a, n_b, alpha,
/// correction, p_adjust. `presentation` applies to the one table; default label
/// "tab:feint-power-simulated".
std::string render_simulation_power(const models::SimulationPowerResult& result,
                                    const std::string& source, OutputFormat format,
                                    const TablePresentation& presentation = {});

}  // namespace feint::tables

// feint/commands/power_reports.hpp - `feint power t-test` and `feint power simulate` from their
// options (power_options.hpp) to the rendered result (report/power_render.hpp).
#pragma once

#include <string>

#include "feint/analysis/settings.hpp"
#include "feint/commands/power_options.hpp"

namespace feint::commands {

/// t_test_power_spec, models::solve_t_test_power, rendered in `r.format`.
std::string t_test_power_report(const TTestPowerOptions& options, const analysis::ResolvedReportOptions& r);

/// power_design (its errors first), models::simulate_power, rendered in `r.format`.
std::string power_simulation_report(const PowerSimulationOptions& options,
                                    const analysis::ResolvedReportOptions& r);

}  // namespace feint::commands

#include "feint/commands/power_reports.hpp"

#include "feint/models/power.hpp"
#include "feint/models/power_sim.hpp"
#include "feint/tables/power_render.hpp"

namespace feint::commands {

std::string t_test_power_report(const TTestPowerOptions& o, const analysis::ResolvedReportOptions& r) {
  const models::TTestPowerSpec s = t_test_power_spec(o);
  const models::TTestPowerResult result = models::solve_t_test_power(s);
  return tables::render_t_test_power(result, tables::solved_for(s), r.format, r.presentation);
}

std::string power_simulation_report(const PowerSimulationOptions& o,
                                    const analysis::ResolvedReportOptions& r) {
  const models::SimulationDesign design = power_design(o);  // its errors first
  const auto result = models::simulate_power(design, power_simulation_options(o));
  return tables::render_simulation_power(result, o.pilot, r.format, r.presentation);
}

}  // namespace feint::commands

#include "feint/analysis/power_reports.hpp"

#include "feint/models/power.hpp"
#include "feint/models/power_sim.hpp"
#include "feint/report/power_render.hpp"

namespace feint::analysis {

std::string t_test_power_report(const TTestPowerOptions& o, const ResolvedReportOptions& r) {
  const models::TTestPowerSpec s = t_test_power_spec(o);
  const models::TTestPowerResult result = models::solve_t_test_power(s);
  return report::render_t_test_power(result, report::solved_for(s), r.format, r.presentation);
}

std::string power_simulation_report(const PowerSimulationOptions& o,
                                    const ResolvedReportOptions& r) {
  const models::SimulationDesign design = power_design(o);  // its errors first
  const auto result = models::simulate_power(design, power_simulation_options(o));
  return report::render_simulation_power(result, o.pilot, r.format, r.presentation);
}

}  // namespace feint::analysis

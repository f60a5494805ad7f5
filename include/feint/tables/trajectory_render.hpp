// feint/tables/trajectory_render.hpp - the observer's deceptiveness measures of each trajectory
// (`feint simulate trajectories`; docs/observer.md) as text, Markdown, CSV or JSON.
#pragma once

#include <string>
#include <vector>

#include "feint/models/deceptiveness.hpp"
#include "feint/sim/trajectory_measures.hpp"

namespace feint::tables {

/// `format`: "csv" and "json" (one row/object per trajectory, every measure and the observer's
/// parameters), "markdown", anything else text (an aligned table with the observer's parameters
/// above and the measures' definitions below). `settings` are the observer's and the pad speed.
std::string render_trajectories(const std::vector<sim::TrajectoryMeasuresRow>& rows,
                                const models::DeceptivenessSettings& settings,
                                const std::string& format);

}  // namespace feint::tables

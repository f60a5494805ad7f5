// feint/sim/trajectory_measures.hpp - the observer's deceptiveness measures (models/deceptiveness.hpp)
// of the paper's strategies (trajectory.hpp), and the robot path of a logged trial rebuilt from its
// strategy, variant and target (docs/observer.md).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "feint/models/deceptiveness.hpp"
#include "feint/sim/trajectory.hpp"

namespace feint::sim {

/// The two goals of a geometry: (-d/2, h) and (d/2, h).
models::Goals goals_of(const Geometry& g) noexcept;

/// A sim trajectory as a models path.
std::vector<models::PathSample> to_path(const std::vector<TrajectorySample>& samples);

struct TrajectoryMeasuresRow {
  std::string strategy;  // exaggerating, switching, ambiguous, optimal, or "custom"
  std::string variant;   // main, v2
  std::string target;    // left, right
  models::DeceptivenessMeasures measures;
};

/// Every strategy and version of the paper (S0-S2 main and v2, S3) toward both targets, in that
/// order; the goals come from `g` (settings.goals is ignored).
std::vector<TrajectoryMeasuresRow> strategy_measures(const Geometry& g,
                                                     const models::DeceptivenessSettings& settings);

}  // namespace feint::sim

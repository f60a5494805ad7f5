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

/// Parses a strategy name as the logs write it (case-insensitive: exaggerating, switching,
/// ambiguous, optimal, or S0..S3). Throws InvalidData naming the value otherwise.
Strategy parse_strategy(std::string_view name);
/// main / v2 (empty = main; also 1 / 2, v1). Throws InvalidData otherwise.
Variant parse_variant(std::string_view name);

/// The robot path of a logged trial, rebuilt from its strategy, variant and target pad coordinate
/// (0 = left, 1 = right) with geometry `g`. Throws InvalidData naming the bad field.
std::vector<models::PathSample> rebuild_path(std::string_view strategy, std::string_view variant,
                                             double target, const Geometry& g);

}  // namespace feint::sim

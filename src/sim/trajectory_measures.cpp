// Deceptiveness of the paper's strategies and path rebuilding (feint/sim/trajectory_measures.hpp).
#include "feint/sim/trajectory_measures.hpp"

#include <cctype>

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::sim {

models::Goals goals_of(const Geometry& g) noexcept {
  models::Goals goals;
  goals.left = {-g.target_distance / 2, g.target_height};
  goals.right = {g.target_distance / 2, g.target_height};
  return goals;
}

std::vector<models::PathSample> to_path(const std::vector<TrajectorySample>& samples) {
  std::vector<models::PathSample> out;
  out.reserve(samples.size());
  for (const auto& s : samples) out.push_back({s.t, s.x, s.y});
  return out;
}

std::vector<TrajectoryMeasuresRow> strategy_measures(const Geometry& g,
                                                     const models::DeceptivenessSettings& settings) {
  validate(g);
  models::DeceptivenessSettings s = settings;
  s.goals = goals_of(g);
  std::vector<TrajectoryMeasuresRow> rows;
  for (auto st : {Strategy::exaggerating, Strategy::switching, Strategy::ambiguous, Strategy::optimal}) {
    for (auto v : {Variant::main, Variant::v2}) {
      if (st == Strategy::optimal && v == Variant::v2) continue;
      for (auto t : {Target::left, Target::right}) {
        const auto path = to_path(trajectory(st, v, t, g));
        rows.push_back({std::string(to_string(st)), std::string(to_string(v)), std::string(to_string(t)),
                        models::deceptiveness(path, t == Target::right ? models::GoalSide::right
                                                                       : models::GoalSide::left,
                                              s)});
      }
    }
  }
  return rows;
}

}  // namespace feint::sim

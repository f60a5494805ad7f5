// Deceptiveness of the paper's strategies and path rebuilding (feint/sim/trajectory_measures.hpp).
#include "feint/sim/trajectory_measures.hpp"

#include <cctype>

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::sim {

namespace {
std::string lower(std::string_view s) {
  std::string out(s);
  for (auto& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}
}  // namespace

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

Strategy parse_strategy(std::string_view name) {
  const std::string s = lower(name);
  if (s == "exaggerating" || s == "s0") return Strategy::exaggerating;
  if (s == "switching" || s == "s1") return Strategy::switching;
  if (s == "ambiguous" || s == "s2") return Strategy::ambiguous;
  if (s == "optimal" || s == "s3") return Strategy::optimal;
  throw InvalidData(fmt::format("strategy '{}' is not one of exaggerating, switching, ambiguous, optimal "
                                "(or S0-S3)", name));
}

Variant parse_variant(std::string_view name) {
  const std::string s = lower(name);
  if (s.empty() || s == "main" || s == "1" || s == "v1") return Variant::main;
  if (s == "v2" || s == "2") return Variant::v2;
  throw InvalidData(fmt::format("variant '{}' is not main or v2", name));
}

std::vector<models::PathSample> rebuild_path(std::string_view strategy, std::string_view variant,
                                             double target, const Geometry& g) {
  const Strategy st = parse_strategy(strategy);
  Variant v = parse_variant(variant);
  if (st == Strategy::optimal) v = Variant::main;
  if (target != 0.0 && target != 1.0) {
    throw InvalidData(fmt::format("target {} is not 0 (left) or 1 (right): the path cannot be rebuilt",
                                  target));
  }
  return to_path(trajectory(st, v, target == 1.0 ? Target::right : Target::left, g));
}

}  // namespace feint::sim

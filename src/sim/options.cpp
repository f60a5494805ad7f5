#include "feint/sim/options.hpp"

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/file_identity.hpp"
#include "feint/io/number.hpp"
#include "feint/sim/sweep.hpp"

namespace feint::sim {

std::vector<SimulationSettings> selection_settings(const SelectionOptions& o) {
  SimulationSettings base;
  base.run.algorithm = parse_algorithm(o.algorithm);
  base.run.lambda = o.lambda;
  base.run.iterations = o.iterations;
  base.run.targets = parse_target_order(o.targets);
  base.runs = o.runs;
  base.seed = o.seed;
  base.batch = o.batch;
  base.threads = o.threads;
  return selection_grid(base, o.compare,
                        o.sweep.empty() ? std::vector<double>{} : parse_lambda_sweep(o.sweep));
}

StudySettings study_settings(const StudyOptions& o) {
  StudySettings s;
  s.participants = o.participants;
  if (o.design != "between" && o.design != "within")
    throw UsageError(fmt::format("--design '{}': expected between (each participant in one condition) or "
                                 "within (each participant in both, counterbalanced)", o.design));
  s.within = o.design == "within";
  s.conditions.clear();
  std::string_view rest = o.conditions;
  bool named = false;
  while (!rest.empty()) {
    const std::size_t comma = rest.find(',');
    const std::string_view item = io::trim(rest.substr(0, comma));
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    // ALGORITHM, or NAME=ALGORITHM (every condition named then).
    const std::size_t eq = item.find('=');
    named = named || eq != std::string_view::npos;
    s.condition_names.emplace_back(io::trim(item.substr(0, eq)));
    try {
      s.conditions.push_back(parse_algorithm(io::trim(eq == std::string_view::npos ? item : item.substr(eq + 1))));
    } catch (const UsageError& e) {
      throw UsageError(fmt::format("--conditions '{}': {}", o.conditions, e.what()));
    }
  }
  if (!named) s.condition_names.clear();
  validate_conditions(s);
  s.iterations = o.iterations;
  s.lambda = o.lambda;
  s.seed = o.seed;
  s.geometry.sample_rate = o.sample_rate;
  if (parse_participant_model(o.participant_model) == ParticipantModel::heuristic) {
    s.observer = ObserverParams{};  // feint 0.1's participant, with its own defaults
  }
  s.observer.pad_speed = o.pad_speed;
  for (const auto& kv : o.observer) set_parameter(s.observer, kv);
  if (o.targets < 2) throw UsageError(fmt::format("--targets {}: a study needs 2 or more targets", o.targets));
  if (o.layout != "fixed" && o.layout != "random")
    throw UsageError(fmt::format("--layout '{}': expected fixed (a row at the paper's height) or random (drawn "
                                 "per round)", o.layout));
  s.targets = o.targets;
  s.random_layout = o.layout == "random";
  validate(s.geometry);
  validate(s.observer);
  return s;
}

TrajectoryMeasures trajectory_measures(const TrajectoriesOptions& o) {
  io::refuse_overwriting_inputs({o.path}, {o.output});  // inputs are sacred
  TrajectoryMeasures m;
  models::DeceptivenessSettings& s = m.settings;
  s.observer = {o.beta, o.tau, o.prior};
  models::validate(s.observer);
  s.pad_speed = o.pad_speed;
  const Geometry g;
  if (o.path.empty()) {
    m.rows = strategy_measures(g, s);
    return m;
  }
  const std::string t = io::to_lower(o.target);
  if (t != "left" && t != "right") {
    throw UsageError(fmt::format("--target '{}': expected left or right", o.target));
  }
  s.goals = goals_of(g);
  const auto path = read_path_file(o.path);
  try {
    const auto goal = t == "right" ? models::GoalSide::right : models::GoalSide::left;
    m.rows.push_back({"custom", "main", t, models::deceptiveness(path, goal, s)});
  } catch (const InvalidData& e) {
    throw InvalidData(fmt::format("{}: {}", o.path, e.what()));
  }
  return m;
}

}  // namespace feint::sim

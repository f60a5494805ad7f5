#include "feint/sim/observer_logs.hpp"

#include <fmt/format.h>

#include <utility>

#include "feint/error.hpp"
#include "feint/io/file_identity.hpp"
#include "feint/io/trace.hpp"
#include "feint/sim/robot_path.hpp"
#include "feint/sim/trajectory_measures.hpp"

namespace feint::sim {

models::ObserverFitSettings observer_fit_settings(const ObserverFitOptions& a) {
  if (!a.output.empty() && a.output != "-")  // inputs are sacred
    io::refuse_overwriting_inputs(io::expand_inputs(a.inputs), {a.output});
  models::ObserverFitSettings s;
  if (a.noise == "ar1") {
    s.noise = models::PadNoise::ar1;
  } else if (a.noise == "independent") {
    s.noise = models::PadNoise::independent;
  } else {
    throw UsageError(fmt::format("--noise '{}': expected ar1 or independent", a.noise));
  }
  if (a.format != "text" && a.format != "json") {
    throw UsageError(fmt::format("--format '{}': expected text or json", a.format));
  }
  s.thin = a.thin;
  s.fit_prior = a.fit_prior;
  s.prior_right = a.prior;
  s.beta_max = a.beta_max;
  s.tau_max = a.tau_max;
  s.level = a.level;
  s.pad_speed = a.pad_speed;
  s.learning = !a.no_learning;
  return s;
}

std::string ObservedLogs::path_source() const {
  if (paths_rebuilt == 0) return "robot path from the logs' robot_x, robot_y";
  if (paths_logged == 0)
    return "path rebuilt from strategy, variant, target and the default geometry";
  return fmt::format(
      "robot path from the logs for {} trials, rebuilt from strategy, variant, "
      "target and the default geometry for {}",
      paths_logged, paths_rebuilt);
}

ObservedLogs read_observed_trials(const std::vector<std::string>& inputs,
                                  const Geometry& geometry) {
  ObservedLogs logs;
  io::TraceOptions opts;
  opts.read_robot_path = true;  // robot_x, robot_y when the logs have them
  opts.on_reject = [&](const io::Rejection& r) {
    logs.rejected.push_back(
        {fmt::format("{}/{}/{}", r.participant, r.condition, r.iteration), r.reason});
  };
  io::TraceReader reader(io::expand_inputs(inputs), opts);
  io::Trial t;
  while (reader.next(t)) {
    models::ObservedTrial o;
    o.participant = t.participant;
    o.condition = t.condition;
    o.iteration = t.iteration;
    o.strategy = t.strategy;
    o.variant = t.variant;
    o.goal = t.target >= 0.5 ? models::GoalSide::right : models::GoalSide::left;
    o.times = t.times;
    o.pads = t.pads;
    o.pad_speed = t.pad_speed;
    o.label = t.label();
    try {
      const RobotPath path = robot_path(t, geometry);
      (path.rebuilt ? logs.paths_rebuilt : logs.paths_logged) += 1;
      o.path.clear();
      for (const auto& p : path.samples) o.path.push_back({p.t + t.times.front(), p.x, p.y});
    } catch (const Error& e) {
      logs.rejected.push_back(
          {o.label, fmt::format("{}:{}: {}; the trial is left out", t.file, t.line, e.what())});
      continue;
    }
    logs.trials.push_back(std::move(o));
  }
  return logs;
}

ObserverLogFit fit_observer_to_logs(const std::vector<std::string>& inputs,
                                    models::ObserverFitSettings settings) {
  const Geometry g;
  settings.goals = goals_of(g);
  settings.validate();
  ObservedLogs logs = read_observed_trials(inputs, g);
  ObserverLogFit out;
  out.path_source = logs.path_source();
  out.rejected_rows = logs.rejected.size();
  out.fit = models::fit_study(std::move(logs.trials), settings);
  out.fit.issues.insert(out.fit.issues.begin(), logs.rejected.begin(), logs.rejected.end());
  return out;
}

}  // namespace feint::sim

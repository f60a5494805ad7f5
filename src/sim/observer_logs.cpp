#include "feint/sim/observer_logs.hpp"

#include <fmt/format.h>

#include <string>
#include <utility>
#include <vector>

#include "feint/error.hpp"
#include "feint/io/file_identity.hpp"
#include "feint/io/number.hpp"
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
  if (paths_logged == 0 && paths_rebuilt == 0) return "no robot path (no trial was read)";
  if (paths_rebuilt == 0) return "robot path from the logs' robot_x, robot_y";
  if (paths_logged == 0)
    return "path rebuilt from strategy, variant, target and the default geometry";
  return fmt::format(
      "robot path from the logs for {} trials, rebuilt from strategy, variant, "
      "target and the default geometry for {}",
      paths_logged, paths_rebuilt);
}

namespace {

models::ObservedTrial observed_trial(const io::Trial& t) {
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
  return o;
}

// A robot path that cannot be read or rebuilt: robot_path's message already starts with
// `file:line:`, which is added only to a message without it.
std::string path_rejection(const io::Trial& t, const Error& e) {
  const std::string where = fmt::format("{}:{}: ", t.file, t.line);
  const std::string what = e.what();
  return fmt::format("{}{}; the trial is left out", what.rfind(where, 0) == 0 ? "" : where, what);
}

// No trial left to fit: how many were read and left out, the first reasons and what may help.
// `fitted` trials reached the fit and were all left out by its checks; `issues` lists every reason.
InvalidData no_usable_trial(const ObservedLogs& logs, std::size_t fitted,
                            const std::vector<models::TrialIssue>& issues) {
  std::string msg = fmt::format(
      "no trial to fit the observer to: {} trial(s) read from the logs, {} left out while reading "
      "them, {} left out by the fit's checks",
      logs.trials_read, logs.rejected.size(), fitted);
  if (logs.trials_read == 0) msg += " (are these the study's pad-trace logs?)";
  for (std::size_t i = 0; i < issues.size() && i < 3; ++i)
    msg += fmt::format("{}{}: {}", i == 0 ? "; first: " : "; ", issues[i].label, issues[i].reason);
  if (issues.size() > 3) msg += fmt::format("; and {} more", issues.size() - 3);
  if (logs.without_path > 0)
    msg += fmt::format(
        "; {} trial(s) have neither robot_x, robot_y nor a strategy: name the logs' columns with "
        "--map strategy=COLUMN (and variant=COLUMN, target=COLUMN), or --map robot_x=COLUMN --map "
        "robot_y=COLUMN",
        logs.without_path);
  return InvalidData(msg);
}

}  // namespace

ObservedLogs read_observed_trials(const std::vector<std::string>& inputs, const Geometry& geometry,
                                  io::TraceOptions reading) {
  ObservedLogs logs;
  reading.read_robot_path = true;  // robot_x, robot_y when the logs have them
  if (reading.on_reject) {         // lenient (--on-error skip): list the trial too
    reading.on_reject = [&logs, pass = std::move(reading.on_reject)](const io::Rejection& r) {
      pass(r);
      ++logs.trials_read;
      const std::string label =
          r.condition.empty() ? fmt::format("{}/{}", r.participant, r.iteration)
                              : fmt::format("{}/{}/{}", r.participant, r.condition, r.iteration);
      logs.rejected.push_back({label, r.reason});
    };
  }
  io::TraceReader reader(io::expand_inputs(inputs), reading);
  io::Trial t;
  while (reader.next(t)) {
    ++logs.trials_read;
    models::ObservedTrial o = observed_trial(t);
    if (t.robot_x.empty() && io::trim(t.strategy).empty()) ++logs.without_path;
    try {
      const RobotPath path = robot_path(t, geometry);
      (path.rebuilt ? logs.paths_rebuilt : logs.paths_logged) += 1;
      for (const auto& p : path.samples) o.path.push_back({p.t + t.times.front(), p.x, p.y});
    } catch (const Error& e) {
      logs.rejected.push_back({o.label, path_rejection(t, e)});
      continue;
    }
    logs.trials.push_back(std::move(o));
  }
  return logs;
}

ObserverLogFit fit_observer_to_logs(const std::vector<std::string>& inputs,
                                    models::ObserverFitSettings settings,
                                    io::TraceOptions reading) {
  const Geometry g;
  settings.goals = goals_of(g);
  settings.validate();
  ObservedLogs logs = read_observed_trials(inputs, g, std::move(reading));
  if (logs.trials.empty()) throw no_usable_trial(logs, 0, logs.rejected);
  ObserverLogFit out;
  out.path_source = logs.path_source();
  out.rejected_rows = logs.rejected.size();
  const std::size_t handed_to_fit = logs.trials.size();
  out.fit = models::fit_study(std::move(logs.trials), settings);
  out.fit.issues.insert(out.fit.issues.begin(), logs.rejected.begin(), logs.rejected.end());
  if (out.fit.trials_used == 0) throw no_usable_trial(logs, handed_to_fit, out.fit.issues);
  return out;
}

}  // namespace feint::sim

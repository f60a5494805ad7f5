// `feint observer fit` on logs of K targets and a pointer (observer_pointer.hpp): the trials read
// with io::PointerTraceReader, their robot paths from the logs' robot_x, robot_y, the K-goal
// observer fitted (models::fit_pointer_study) and rendered (tables/observer_render.hpp).
#include "observer_pointer.hpp"

#include <fmt/format.h>

#include <utility>

#include "feint/error.hpp"
#include "feint/io/pointer_trace.hpp"
#include "feint/metrics/trial_layout.hpp"
#include "feint/models/pointer_observer_fit.hpp"
#include "feint/sim/observer_logs.hpp"
#include "feint/tables/observer_render.hpp"

namespace feint::commands::detail {

bool pointer_logs(const std::vector<std::string>& files, const io::TraceOptions& reading) {
  if (files.empty()) return false;
  const bool first = io::is_pointer_log(files.front(), reading);
  for (const auto& f : files) {
    if (io::is_pointer_log(f, reading) == first) continue;
    // A file that is not a pointer log need not be a pad log either (a study folder's
    // questionnaire): say only what the header shows.
    const auto [pointer, other] = first ? std::pair(files.front(), f) : std::pair(f, files.front());
    throw InvalidData(fmt::format(
        "{} is a log of K targets and a pointer (a belief_x column, no pad), but {} is not: one data set is one "
        "kind of log; give the pointer logs alone (a study folder's logs are in its logs/ folder), and fit pad "
        "logs separately",
        pointer, other));
  }
  return first;
}

namespace {

/// What the reading kept and left out.
struct PointerLogs {
  std::vector<models::PointerObservedTrial> trials;
  std::vector<models::TrialIssue> rejected;  // each reason names the file and line
  std::size_t trials_read = 0;
};

models::PointerObservedTrial observed(const io::Trial& t) {
  models::PointerObservedTrial o;
  o.participant = t.participant;
  o.condition = t.condition;
  o.iteration = t.iteration;
  o.strategy = t.strategy;
  o.variant = t.variant;
  o.layout = metrics::trial_layout(t);
  o.target = t.target_index;
  o.times = t.times;
  o.x = t.belief_x;
  o.y = t.belief_y;
  o.pointer_speed = t.pad_speed;
  // The robot at each pointer sample, on the pointer's clock.
  for (std::size_t i = 0; i < t.robot_x.size(); ++i) o.path.push_back({t.times[i], t.robot_x[i], t.robot_y[i]});
  o.label = t.label();
  return o;
}

PointerLogs read_pointer_trials(const std::vector<std::string>& files, io::TraceOptions reading) {
  PointerLogs logs;
  reading.require_pad_speed = false;
  if (reading.on_reject) {  // lenient (--on-error skip): list the trial too
    reading.on_reject = [&logs, pass = std::move(reading.on_reject)](const io::Rejection& r) {
      pass(r);
      ++logs.trials_read;
      const std::string label = r.condition.empty() ? fmt::format("{}/{}", r.participant, r.iteration)
                                                    : fmt::format("{}/{}/{}", r.participant, r.condition, r.iteration);
      logs.rejected.push_back({label, r.reason});
    };
  }
  io::PointerTraceReader reader(files, reading);
  io::Trial t;
  while (reader.next(t)) {
    ++logs.trials_read;
    if (t.robot_x.empty()) {
      // The paths of K targets depend on the planner's settings (decoys, the observer whose entropy
      // the ambiguous point maximises): they are not rebuilt from the strategy.
      logs.rejected.push_back(
          {t.label(), fmt::format("{}:{}: the log has no robot_x, robot_y: the robot's path on a map of K targets is "
                                  "not rebuilt from the strategy (log the robot's position, or --map robot_x=COLUMN "
                                  "--map robot_y=COLUMN); the trial is left out",
                                  t.file, t.line)});
      continue;
    }
    logs.trials.push_back(observed(t));
  }
  return logs;
}

InvalidData no_usable_trial(const PointerLogs& logs, std::size_t fitted, const std::vector<models::TrialIssue>& issues) {
  std::string msg = fmt::format(
      "no trial to fit the observer to: {} trial(s) read from the logs of K targets and a pointer, {} left out "
      "while reading them, {} left out by the fit's checks",
      logs.trials_read, logs.rejected.size(), fitted);
  for (std::size_t i = 0; i < issues.size() && i < 3; ++i)
    msg += fmt::format("{}{}: {}", i == 0 ? "; first: " : "; ", issues[i].label, issues[i].reason);
  if (issues.size() > 3) msg += fmt::format("; and {} more", issues.size() - 3);
  return InvalidData(msg);
}

/// The pad's options that have no meaning for a pointer: an error when set away from the default.
void refuse_pad_options(const sim::ObserverFitOptions& o) {
  const sim::ObserverFitOptions defaults;
  auto refuse = [](const char* option, const char* why) {
    throw UsageError(fmt::format("{} is an option of pad-trace logs; these are logs of K targets and a pointer: {}",
                                 option, why));
  };
  if (o.fit_prior)
    refuse("--fit-prior", "the observer of K targets starts from the uniform prior 1/K, which is not fitted");
  if (o.prior != defaults.prior)
    refuse("--prior", "P(right) has no meaning on a map of K targets (the prior is uniform, 1/K each)");
  if (o.pad_speed != defaults.pad_speed)
    refuse("--pad-speed", "a pad's speed has no meaning for a pointer, and the agreement table's confusion is the "
                          "raw one, which needs no speed");
}

}  // namespace

std::string pointer_observer_fit_report(const ObserverFitCommand& c, const std::vector<std::string>& files,
                                        io::TraceOptions reading) {
  refuse_pad_options(c.o);
  const models::ObserverFitSettings s = sim::observer_fit_settings(c.o);
  PointerLogs logs = read_pointer_trials(files, std::move(reading));
  if (logs.trials.empty()) throw no_usable_trial(logs, 0, logs.rejected);
  const std::size_t handed_to_fit = logs.trials.size();
  models::PointerStudyObserverFit fit = models::fit_pointer_study(std::move(logs.trials), s);
  fit.issues.insert(fit.issues.begin(), logs.rejected.begin(), logs.rejected.end());
  if (fit.trials_used == 0) throw no_usable_trial(logs, handed_to_fit, fit.issues);
  const std::string path = "robot path from the logs' robot_x, robot_y";
  return c.o.format == "json" ? tables::render_pointer_observer_fit_json(fit, s, path)
                              : tables::render_pointer_observer_fit_text(fit, s, logs.rejected.size(), path);
}

}  // namespace feint::commands::detail

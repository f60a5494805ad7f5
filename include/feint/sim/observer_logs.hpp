// feint/sim/observer_logs.hpp - the goal-inference observer fitted to pad-trace logs (`feint
// observer fit`; docs/observer.md): each trial of the logs read with io::TraceReader (with the
// reading options of `feint score`: --map, --time-unit, ...), its robot path read from the logs or
// rebuilt (sim::robot_path), then models::fit_study.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "feint/io/trace.hpp"
#include "feint/models/observer_fit.hpp"
#include "feint/sim/trajectory.hpp"

namespace feint::sim {

/// `feint observer fit`'s options as the command line spells them.
struct ObserverFitOptions {
  std::vector<std::string> inputs;
  std::string output = "-";
  std::string format = "text";  // text or json
  std::string noise = "ar1";    // ar1 or independent
  double thin = 0;
  bool fit_prior = false;
  double prior = 0.5;
  double beta_max = 20;
  double tau_max = 2;
  double level = 0.95;
  double pad_speed = 0.8;
  bool no_learning = false;
};

/// The fit's settings (goals not yet set). Throws UsageError for an unknown --noise or --format.
/// Throws UsageError when the output is one of the logs (feint never overwrites its inputs).
models::ObserverFitSettings observer_fit_settings(const ObserverFitOptions& options);

/// The trials of the logs as the fit sees them, and the trials left out on the way.
struct ObservedLogs {
  std::vector<models::ObservedTrial> trials;
  /// Trials the log reader rejected or whose robot path could not be read or rebuilt; each reason
  /// names the file and line once (`file:line: ... (trial P/C/I)`).
  std::vector<models::TrialIssue> rejected;
  std::size_t trials_read = 0;    ///< trials the reader handed out or rejected
  std::size_t paths_logged = 0;   ///< trials whose robot path came from robot_x, robot_y
  std::size_t paths_rebuilt = 0;  ///< trials whose path was rebuilt from strategy, variant, target
  std::size_t without_path = 0;   ///< trials with neither robot_x, robot_y nor a strategy
  /// One sentence saying where the robot paths of `trials` came from (for the report's first
  /// line): the logs' robot_x, robot_y; rebuilt; or how many trials had each. No claim without a
  /// trial.
  std::string path_source() const;
};

/// Reads every trial of `inputs` (files, directories or globs, as `feint score`) with `reading`
/// (the loader options: column map, delimiter, time unit, decimal mark, ...; read_robot_path is
/// set), with the robot path at its pad samples (on the pad's clock) from the logs or rebuilt with
/// `geometry`. As io::TraceReader: without `reading.on_reject` (strict, --on-error strict) the
/// first invalid trial throws InvalidData; with it (--on-error skip) each rejected trial is passed
/// to it and listed in `rejected`. A trial whose robot path cannot be read or rebuilt is always
/// listed.
ObservedLogs read_observed_trials(const std::vector<std::string>& inputs, const Geometry& geometry,
                                  io::TraceOptions reading = {});

/// The fit and what the reading left out.
struct ObserverLogFit {
  models::StudyObserverFit fit;   ///< issues start with the trials `rejected` while reading
  std::size_t rejected_rows = 0;  ///< how many of fit.issues were left out while reading the logs
  std::string path_source;
};

/// read_observed_trials with the default geometry (whose goals it sets in a copy of `settings`),
/// then models::fit_study. Throws UsageError when `settings` are invalid, InvalidData when no trial
/// is left to fit (saying how many were read and left out, the first reasons, and the --map that
/// may help when the logs have neither robot_x, robot_y nor a strategy).
ObserverLogFit fit_observer_to_logs(const std::vector<std::string>& inputs,
                                    models::ObserverFitSettings settings,
                                    io::TraceOptions reading = {});

}  // namespace feint::sim

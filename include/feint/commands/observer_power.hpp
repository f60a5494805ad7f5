// feint/commands/observer_power.hpp - the observer's commands. `feint observer fit`: the loader
// options (as `feint score` spells them) turned into the log reader's options, the fit and its
// rendering (docs/observer.md). `feint power observer`: its settings as the command line spells
// them, and their conversion into sim::StudyPowerSettings: the simulated participants' observer
// given, read from a file, set one parameter at a time, or fitted to a pilot's error by simulated
// moments (sim/pilot_fit.hpp; docs/paper-scale.md, "Power from a pilot").
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "feint/analysis/settings.hpp"
#include "feint/io/trace.hpp"
#include "feint/sim/observer_logs.hpp"
#include "feint/sim/study_power.hpp"

namespace feint::commands {

/// The loader options (--map, --delimiter, --time-unit, --decimal, --no-header, --columns,
/// --iteration-base, --participant-from-path, --samples-column, --single-condition, --on-error)
/// as io::TraceReader takes them, checked and converted as `feint score` does
/// (analysis::score_settings; UsageError names the option). --on-error skip sets a no-op
/// `on_reject` (lenient mode); strict leaves it empty. The scoring options are not used.
io::TraceOptions loader_trace_options(const analysis::ScoreOptions& loader);

/// `feint observer fit`: its options and the loader options of `feint score`.
struct ObserverFitCommand {
  sim::ObserverFitOptions o;
  analysis::ScoreOptions loader;
};

/// Checks the options, reads the logs with the loader options, fits and renders as text or JSON:
/// pad-trace logs with sim::fit_observer_to_logs; logs of K targets and a pointer (every file's
/// header has belief_x and no pad, io::is_pointer_log) with models::fit_pointer_study, where
/// --fit-prior, --prior and --pad-speed away from their defaults are UsageErrors (docs/observer.md,
/// "Fitting the observer to pointer traces"). Throws UsageError, InvalidData (no trial left to fit;
/// pad and pointer logs mixed, naming a file of each kind), IoError.
std::string observer_fit_report(const ObserverFitCommand& command);

struct ObserverPowerOptions {
  std::vector<int> participants{10, 20, 30, 40, 60, 80, 100};
  std::string observer_file;
  std::string pilot;
  std::string metric = "error";
  std::string compare = "adaptive,random";
  std::vector<std::string> observer;  // NAME=VALUE
  std::string participant_model = "goal-inference";
  int iterations = 20;
  double lambda = 0.5;
  int from_iteration = 5;
  std::size_t studies = 400;
  std::uint64_t seed = 1;
  unsigned threads = 0;  // 0: all cores
  double target_power = 0.8;
};

/// The power study's settings and one sentence saying where the observer's parameters came from.
struct ObserverPowerPlan {
  sim::StudyPowerSettings settings;
  std::string source;
};

/// The settings at significance level `alpha`; with a pilot, beta and recognition_logodds are
/// fitted to its error (a search of 100 participants per condition on its own random streams).
/// Throws UsageError for a bad parameter or --compare, InvalidData/IoError for the files.
ObserverPowerPlan observer_power_plan(const ObserverPowerOptions& options, double alpha);

/// observer_power_plan at `r.alpha`, sim::study_power, rendered in `r.format`.
std::string observer_power_report(const ObserverPowerOptions& options,
                                  const analysis::ResolvedReportOptions& r);

}  // namespace feint::commands

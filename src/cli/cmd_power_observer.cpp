// `feint power observer`: how many participants per condition an adaptive-vs-random study needs,
// by simulating whole studies of goal-inference participants (sim/study_power.hpp;
// docs/paper-scale.md, "Power from a pilot").
#include <memory>

#include "commands.hpp"
#include "feint/commands/observer_power.hpp"
#include "options.hpp"

namespace feint::cli {

void add_power_observer_command(CLI::App& power) {
  auto a = std::make_shared<ReportCommand<commands::ObserverPowerOptions>>();
  auto* cmd = power.add_subcommand(
      "observer",
      "Participants per condition for a given power to see adaptive > random, by simulating whole "
      "studies of goal-inference participants (parameters given, or fitted to a pilot)");
  cmd->add_option("--participants", a->o.participants, "Participants per condition to try")
      ->capture_default_str()
      ->delimiter(',');
  cmd->add_option(
      "--observer-file", a->o.observer_file,
      "Observer parameters, one 'name = value' per line (e.g. fitted to a pilot study)");
  cmd->add_option("--pilot", a->o.pilot,
                  "Pilot scores CSV (adaptive and random): fit beta and recognition_logodds to its "
                  "error by simulated moments (docs/paper-scale.md)");
  cmd->add_option("--metric", a->o.metric, "Pilot: the error column")->capture_default_str();
  cmd->add_option("--compare", a->o.compare, "Pilot: the adaptive and the random condition, A,B")
      ->capture_default_str();
  cmd->add_option("--observer", a->o.observer,
                  "NAME=VALUE: set an observer parameter (repeatable; after --observer-file)");
  cmd->add_option("--participant-model", a->o.participant_model, "goal-inference or heuristic")
      ->capture_default_str();
  cmd->add_option("--iterations", a->o.iterations, "Iterations per participant")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--lambda", a->o.lambda, "Lambda of the adaptive condition")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--from-iteration", a->o.from_iteration,
                  "First of the 'later iterations' whose mean error is compared")
      ->capture_default_str();
  cmd->add_option("--studies", a->o.studies, "Simulated studies per size")->capture_default_str();
  cmd->add_option("--seed", a->o.seed, "Random seed (same seed, same result)")
      ->capture_default_str();
  cmd->add_option("--threads", a->o.threads,
                  "Threads (0 = all cores; the result does not depend on it)")
      ->capture_default_str();
  cmd->add_option("--target-power", a->o.target_power, "Power wanted")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  add_report_options(*cmd, a->report, {.tests = false, .presentation = true});
  cmd->callback([a] { run_report(*a, commands::observer_power_report); });
}

}  // namespace feint::cli

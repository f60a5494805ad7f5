// `feint power observer`: how many participants per condition an adaptive-vs-random study needs,
// by simulating whole studies of goal-inference participants (sim/study_power.hpp;
// docs/paper-scale.md, "Power from a pilot").
#include <fmt/format.h>

#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "feint/error.hpp"
#include "feint/report/study_power_render.hpp"
#include "feint/io/scores.hpp"
#include "feint/sim/pilot_fit.hpp"
#include "feint/sim/study_power.hpp"
#include "report_options.hpp"

namespace feint::cli {

namespace {

struct ObserverPowerArgs {
  std::vector<int> participants{10, 20, 30, 40, 60, 80, 100};
  std::string observer_file;
  std::string pilot;
  std::string metric = "error";
  std::string compare = "adaptive,random";
  std::vector<std::string> observer;
  std::string participant_model = "goal-inference";
  int iterations = 20;
  double lambda = 0.5;
  int from_iteration = 5;
  std::size_t studies = 400;
  std::uint64_t seed = 1;
  unsigned threads = 0;
  double target_power = 0.8;
  ReportOptions report;
};

void run(const ObserverPowerArgs& a) {
  const ResolvedReportOptions r = resolve_report_options(a.report);
  sim::StudyPowerSettings s;
  s.participants = a.participants;
  s.studies = a.studies;
  s.seed = a.seed;
  s.threads = a.threads ? a.threads : std::max(1u, std::thread::hardware_concurrency());
  s.alpha = r.alpha;
  s.from_iteration = a.from_iteration;
  s.target_power = a.target_power;
  s.study.iterations = a.iterations;
  s.study.lambda = a.lambda;
  if (sim::parse_participant_model(a.participant_model) == sim::ParticipantModel::heuristic) {
    s.study.observer = sim::ObserverParams{};
  }
  if (!a.observer_file.empty()) sim::read_parameters(s.study.observer, a.observer_file);
  for (const auto& kv : a.observer) sim::set_parameter(s.study.observer, kv);
  std::string source = a.observer_file.empty() ? std::string() : "from " + a.observer_file;
  if (!a.observer.empty()) source += std::string(source.empty() ? "" : ", ") + "set on the command line";
  if (!a.pilot.empty()) {
    // beta and recognition_logodds fitted to the pilot's error by simulated moments.
    io::ScoresOptions so;
    so.metrics = {a.metric};
    const auto table = io::load_scores(a.pilot, so);
    const auto [cond_a, cond_b] = parse_compare(a.compare);
    const auto moments = sim::pilot_moments(table, 0, cond_a, cond_b, a.from_iteration);
    sim::StudySettings search = s.study;
    search.participants = 100;
    search.seed = a.seed ^ 0x5049'4C4F'54ULL;  // "PILOT": not the power studies' streams
    const auto fit = sim::fit_pilot(moments, search, a.from_iteration);
    s.study.observer = fit.observer;
    source += fmt::format("{}fitted to pilot {} ({} + {} participants): beta {:.3f}, recognition {:.2f}",
                          source.empty() ? "" : "; ", a.pilot, moments.adaptive, moments.random,
                          fit.observer.beta, fit.observer.recognition_logodds);
  }
  const auto result = sim::study_power(s);
  write_report(r.output, report::render_study_power(result, source, r.format, r.presentation));
}

}  // namespace

void add_power_observer_command(CLI::App& power) {
  auto a = std::make_shared<ObserverPowerArgs>();
  auto* cmd = power.add_subcommand(
      "observer",
      "Participants per condition for a given power to see adaptive > random, by simulating whole "
      "studies of goal-inference participants (parameters given, or fitted to a pilot)");
  cmd->add_option("--participants", a->participants, "Participants per condition to try")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--observer-file", a->observer_file,
                  "Observer parameters, one 'name = value' per line (e.g. fitted to a pilot study)");
  cmd->add_option("--pilot", a->pilot,
                  "Pilot scores CSV (adaptive and random): fit beta and recognition_logodds to its "
                  "error by simulated moments (docs/paper-scale.md)");
  cmd->add_option("--metric", a->metric, "Pilot: the error column")->capture_default_str();
  cmd->add_option("--compare", a->compare, "Pilot: the adaptive and the random condition, A,B")
      ->capture_default_str();
  cmd->add_option("--observer", a->observer,
                  "NAME=VALUE: set an observer parameter (repeatable; after --observer-file)");
  cmd->add_option("--participant-model", a->participant_model, "goal-inference or heuristic")
      ->capture_default_str();
  cmd->add_option("--iterations", a->iterations, "Iterations per participant")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  cmd->add_option("--lambda", a->lambda, "Lambda of the adaptive condition")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--from-iteration", a->from_iteration,
                  "First of the 'later iterations' whose mean error is compared")
      ->capture_default_str();
  cmd->add_option("--studies", a->studies, "Simulated studies per size")->capture_default_str();
  cmd->add_option("--seed", a->seed, "Random seed (same seed, same result)")->capture_default_str();
  cmd->add_option("--threads", a->threads, "Threads (0 = all cores; the result does not depend on it)")
      ->capture_default_str();
  cmd->add_option("--target-power", a->target_power, "Power wanted")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  add_report_options(*cmd, a->report, {.tests = false, .presentation = true});
  cmd->callback([a] { run(*a); });
}

}  // namespace feint::cli

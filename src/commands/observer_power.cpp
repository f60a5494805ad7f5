#include "feint/commands/observer_power.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <thread>

#include "feint/analysis/settings.hpp"
#include "feint/io/file_identity.hpp"
#include "feint/io/progress.hpp"
#include "feint/io/scores.hpp"
#include "feint/metrics/score.hpp"
#include "feint/tables/observer_render.hpp"
#include "feint/tables/study_power_render.hpp"
#include "feint/sim/pilot_fit.hpp"
#include "observer_pointer.hpp"

namespace feint::commands {

io::TraceOptions loader_trace_options(const analysis::ScoreOptions& loader) {
  // Read as the scorer reads (metrics' reading options; analysis/analyze.cpp's mean traces).
  const metrics::ScoreSettings s = analysis::score_settings(loader);
  io::TraceOptions t = metrics::reading_options(s);
  t.require_pad_speed = false;  // the fit has its own --pad-speed for logs without one
  if (s.on_error == metrics::OnError::skip) t.on_reject = [](const io::Rejection&) {};
  return t;
}

std::string observer_fit_report(const ObserverFitCommand& c) {
  const io::TraceOptions reading = loader_trace_options(c.loader);
  const models::ObserverFitSettings s = sim::observer_fit_settings(c.o);
  // Logs of K targets and a pointer are told apart by their header, as `feint score` does.
  const auto files = io::expand_inputs(c.o.inputs);
  if (detail::pointer_logs(files, reading)) return detail::pointer_observer_fit_report(c, files, reading);
  const sim::ObserverLogFit fit = sim::fit_observer_to_logs(c.o.inputs, s, reading);
  return c.o.format == "json" ? tables::render_observer_fit_json(fit, s)
                              : tables::render_observer_fit_text(fit, s);
}

ObserverPowerPlan observer_power_plan(const ObserverPowerOptions& a, double alpha) {
  ObserverPowerPlan plan;
  sim::StudyPowerSettings& s = plan.settings;
  s.participants = a.participants;
  s.studies = a.studies;
  s.seed = a.seed;
  s.threads = a.threads ? a.threads : std::max(1u, std::thread::hardware_concurrency());
  s.alpha = alpha;
  s.from_iteration = a.from_iteration;
  s.target_power = a.target_power;
  s.study.iterations = a.iterations;
  s.study.lambda = a.lambda;
  if (sim::parse_participant_model(a.participant_model) == sim::ParticipantModel::heuristic) {
    s.study.observer = sim::ObserverParams{};
  }
  if (!a.observer_file.empty()) sim::read_parameters(s.study.observer, a.observer_file);
  for (const auto& kv : a.observer) sim::set_parameter(s.study.observer, kv);
  std::string& source = plan.source;
  source = a.observer_file.empty() ? std::string() : "from " + a.observer_file;
  if (!a.observer.empty())
    source += std::string(source.empty() ? "" : ", ") + "set on the command line";
  if (!a.pilot.empty()) {
    // beta and recognition_logodds fitted to the pilot's error by simulated moments.
    io::ScoresOptions so;
    so.metrics = {a.metric};
    const auto table = io::load_scores(a.pilot, so);
    const auto [cond_a, cond_b] = analysis::parse_compare(a.compare);
    const auto moments = sim::pilot_moments(table, 0, cond_a, cond_b, a.from_iteration);
    sim::StudySettings search = s.study;
    search.participants = 100;
    search.seed = a.seed ^ 0x5049'4C4F'54ULL;  // "PILOT": not the power studies' streams
    const auto fit = sim::fit_pilot(moments, search, a.from_iteration);
    s.study.observer = fit.observer;
    source +=
        fmt::format("{}fitted to pilot {} ({} + {} participants): beta {:.3f}, recognition {:.2f}",
                    source.empty() ? "" : "; ", a.pilot, moments.adaptive, moments.random,
                    fit.observer.beta, fit.observer.recognition_logodds);
  }
  return plan;
}

std::string observer_power_report(const ObserverPowerOptions& options,
                                  const analysis::ResolvedReportOptions& r) {
  io::refuse_overwriting_inputs({options.pilot, options.observer_file}, {r.output});
  ObserverPowerPlan plan = observer_power_plan(options, r.alpha);
  // On stderr, only when it is a terminal (as feint score's).
  io::ProgressLine progress("feint power observer");
  if (progress.active()) {
    plan.settings.on_progress = [&progress](std::uint64_t done, std::uint64_t total) {
      progress.update_count(done, total, "participants simulated");
    };
  }
  const auto result = sim::study_power(plan.settings);
  progress.finish();
  return tables::render_study_power(result, plan.source, r.format, r.presentation);
}

}  // namespace feint::commands

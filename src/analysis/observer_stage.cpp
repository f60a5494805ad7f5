// The observer's parameters compared in `feint analyze` (observer_stage.hpp).
#include "observer_stage.hpp"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/pointer_trace.hpp"
#include "feint/models/observer_fit.hpp"
#include "feint/sim/observer_logs.hpp"

namespace feint::analysis::detail {

namespace {

// Why the fit could not be made, the same wherever the command ran: the counts without the list of
// trials ("; first: ..."), and each log named by its file name, not by the path it was given as.
std::string short_reason(std::string why, const std::vector<std::string>& logs) {
  if (const auto at = why.find("; first: "); at != std::string::npos) why.resize(at);
  for (const auto& log : logs) {
    const std::string name = std::filesystem::path(log).filename().string();
    for (std::size_t at = why.find(log); !log.empty() && at != std::string::npos; at = why.find(log, at))
      why.replace(at, log.size(), name);
  }
  return why + " (`feint observer fit` on the logs names each trial left out)";
}

}  // namespace

void fit_observer_stage(const std::vector<std::string>& logs, const io::TraceOptions& reading, StudyResults& r) {
  if (logs.empty() || !r.comparison || !r.comparison->options.compare) return;
  const auto& [a, b] = *r.comparison->options.compare;
  try {
    if (io::is_pointer_log(logs.front(), reading)) return;
    models::ObserverFitSettings s;
    s.learning = false;  // `feint observer fit` has the learning test; the comparison needs none
    s.level = r.table1.options.test.conf_level;
    const sim::ObserverLogFit fit = sim::fit_observer_to_logs(logs, s, reading);
    r.observer = models::compare_conditions(fit.fit.participants, a, b, s.level);
    if (r.observer.empty())
      r.observer_note = fmt::format("{} or {} has fewer than two participants with a fitted observer", a, b);
  } catch (const Error& e) {
    r.observer.clear();
    r.observer_note = short_reason(e.what(), logs);
  }
}

std::vector<Finding> observer_findings(const StudyResults& r, const WordingRules& rules) {
  std::vector<Finding> out;
  for (const auto& c : r.observer) {
    const bool beta = c.parameter == "log beta";
    const std::string what = fmt::format(
        "{} of the goal-inference observer fitted to each participant's pad traces, {} vs {}{}",
        beta ? "log beta (how closely the pad follows what the path says of the goal)" : "tau (its delay, s)",
        c.condition_a, c.condition_b, c.paired ? ", paired within participants" : "");
    Finding f = difference_finding(beta ? "observer-beta" : "observer-tau", "exploratory",
                                   fmt::format("Do the conditions differ in the observer's {}?", beta ? "beta" : "tau"),
                                   what, c.welch, nullptr, "", rules);
    f.measure = beta ? "observer log beta" : "observer tau";
    const auto& t = c.welch;
    if (beta && t.computed && t.estimate && t.conf_low && t.conf_high && t.mean1 && t.mean2)
      // A difference of log betas is the log of a ratio: say it on beta's own scale too.
      f.sentence += fmt::format(" On beta's own scale: geometric means {:.3f} vs {:.3f} per m, ratio {:.2f}, {:g}% CI "
                                "[{:.2f}, {:.2f}].",
                                std::exp(*t.mean1), std::exp(*t.mean2), std::exp(*t.estimate), 100 * t.conf_level,
                                std::exp(*t.conf_low), std::exp(*t.conf_high));
    if (c.at_bound > 0)
      f.warnings.push_back(fmt::format("{} participant estimate(s) at the range's bound, kept (one-sided CIs).",
                                       c.at_bound));
    out.push_back(std::move(f));
  }
  if (out.empty() && !r.observer_note.empty()) {
    Finding f;
    f.id = "observer-beta";
    f.hypothesis = "exploratory";
    f.question = "Do the conditions differ in the observer's beta and tau?";
    f.strength = Strength::not_computable;
    f.evidence = to_string(f.strength);
    f.sentence = fmt::format("The observer's beta and tau compared: not computable ({}).", r.observer_note);
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace feint::analysis::detail

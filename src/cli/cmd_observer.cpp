// `feint observer fit`: the goal-inference observer fitted to pad-trace logs (docs/observer.md).
// Thin: commands::observer_fit_report reads the logs (the loader options of `feint score`), fits
// and renders.
#include <memory>

#include "commands.hpp"
#include "feint/commands/observer_power.hpp"
#include "options.hpp"

namespace feint::cli {

void add_observer_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "observer", "The goal-inference observer (docs/observer.md): fit it to people.");
  cmd->require_subcommand(1);
  auto c = std::make_shared<commands::ObserverFitCommand>();
  sim::ObserverFitOptions* a = &c->o;
  auto* fit = cmd->add_subcommand(
      "fit",
      "Fit the observer's rationality beta and delay tau (and optionally the prior) to pad-trace "
      "logs by maximum likelihood, per participant and pooled per condition, with profile-"
      "likelihood CIs, model-human agreement per strategy and iteration, and a test of learning (a "
      "change of beta with exposure).");
  fit->add_option("inputs", a->inputs,
                  "log files, directories or globs (the format of `feint score`)")
      ->required();
  fit->add_option("-o,--output", a->output, "output file (- = standard output)")
      ->capture_default_str();
  fit->add_option("--format,-f", a->format, "text or json")->capture_default_str();
  fit->add_option("--noise", a->noise, "pad noise model: ar1 (default) or independent")
      ->capture_default_str();
  fit->add_option("--thin", a->thin, "use one pad sample per this many seconds (0 = all)")
      ->capture_default_str();
  fit->add_flag("--fit-prior", a->fit_prior, "also fit the prior P(right)");
  fit->add_option("--prior", a->prior, "the prior P(right) when it is not fitted")
      ->capture_default_str();
  fit->add_option("--beta-max", a->beta_max, "upper end of beta's range (1/m)")
      ->capture_default_str();
  fit->add_option("--tau-max", a->tau_max, "upper end of tau's range (s)")->capture_default_str();
  fit->add_option("--level", a->level, "confidence level of the CIs")->capture_default_str();
  fit->add_option("--pad-speed", a->pad_speed,
                  "pad speed for confusion when the logs have none (pad units/s)")
      ->capture_default_str();
  fit->add_flag("--no-learning", a->no_learning, "skip the learning test");
  add_loader_options(*fit, c->loader, "Reading the logs (as feint score)");
  fit->callback([c] { write_report(c->o.output, commands::observer_fit_report(*c)); });
}

}  // namespace feint::cli

// `feint observer fit`: the goal-inference observer fitted to pad-trace logs (docs/observer.md).
// Thin: the logs are read with io::TraceReader, each trial's robot path is read or rebuilt with
// sim::robot_path, models::fit_study does the work; this file prints the result.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/io/output.hpp"
#include "feint/io/trace.hpp"
#include "feint/models/observer_fit.hpp"
#include "feint/sim/robot_path.hpp"
#include "feint/sim/trajectory_measures.hpp"

namespace feint::cli {

namespace {

struct FitArgs {
  std::vector<std::string> inputs;
  std::string output = "-";
  std::string format = "text";
  std::string noise = "ar1";
  double thin = 0;
  bool fit_prior = false;
  double prior = 0.5;
  double beta_max = 20;
  double tau_max = 2;
  double level = 0.95;
  double pad_speed = 0.8;
  bool no_learning = false;
};


std::string num(double x, int digits = 3) {
  return std::isnan(x) ? std::string("-") : fmt::format("{:.{}f}", x, digits);
}

std::string ci_text(const models::ParameterEstimate& p) {
  return fmt::format("{} [{}{}, {}{}]", num(p.estimate), p.low_at_bound ? "<=" : "", num(p.conf_low),
                     num(p.conf_high), p.high_at_bound ? "(bound)" : "");
}

std::string render_text(const models::StudyObserverFit& r, const FitArgs& a, std::size_t rejected_rows,
                        const std::string& path_source) {
  std::string out = fmt::format(
      "Goal-inference observer fitted to {} trial(s) ({}); pad noise: {}{}; {}% profile-likelihood CIs.\n",
      r.trials_used, path_source, a.noise == "ar1" ? "Gaussian AR(1) around b(t)" : "independent Gaussian around b(t)",
      a.thin > 0 ? fmt::format(", one sample per {} s", a.thin) : "", num(100 * a.level, 0));
  if (rejected_rows > 0) out += fmt::format("{} trial(s) rejected by the log reader (see below).\n", rejected_rows);
  auto fits = [&](const std::vector<models::ObserverFit>& fs, const char* title) {
    out += fmt::format("\n{}\n", title);
    out += fmt::format("{:<12} {:<10} {:>6} {:>7}  {:<30} {:<30}{} {:>7} {:>6} {:>12}\n", "unit", "condition",
                       "trials", "samples", "beta (1/m) [CI]", "tau (s) [CI]",
                       a.fit_prior ? fmt::format(" {:<30}", "P(right) [CI]") : "", "sigma", "phi", "logLik");
    for (const auto& f : fs) {
      std::string prior;
      if (a.fit_prior) prior = fmt::format(" {:<30}", ci_text(f.parameter("prior_right")));
      out += fmt::format("{:<12} {:<10} {:>6} {:>7}  {:<30} {:<30}{} {:>7} {:>6} {:>12}\n", f.unit, f.condition,
                         f.trials, f.samples, ci_text(f.parameter("beta")), ci_text(f.parameter("tau")), prior,
                         num(f.sigma, 4), num(f.phi, 3), num(f.log_likelihood, 2));
    }
  };
  fits(r.participants, "Per participant");
  fits(r.conditions, "Pooled per condition");
  if (!r.learning.empty()) {
    out += "\nLearning: beta_k = beta0 exp(gamma exposure_k), exposure = earlier trials of the same strategy\n";
    for (const auto& l : r.learning) {
      out += fmt::format("  {:<10} gamma = {}, beta0 = {}, LR chi2(1) = {}, p = {}\n", l.condition,
                         ci_text(l.gamma), num(l.beta0), num(l.statistic, 3),
                         l.p_value < 1e-4 ? fmt::format("{:.2e}", l.p_value) : num(l.p_value, 4));
    }
  }
  out += "\nModel-human agreement (model b(t) at each participant's fit vs the pad; r = Pearson correlation)\n";
  out += fmt::format("{:<10} {:<13} {:>9} {:>6}  {:>7} {:>7} {:>6} {:>6}  {:>7} {:>7} {:>6} {:>6}  {:>7} {:>7}\n",
                     "condition", "strategy", "iteration", "trials", "E human", "E model", "E r", "E rmse",
                     "C human", "C model", "C r", "C rmse", "trace r", "rmse");
  for (const auto& g : r.agreement) {
    out += fmt::format("{:<10} {:<13} {:>9} {:>6}  {:>7} {:>7} {:>6} {:>6}  {:>7} {:>7} {:>6} {:>6}  {:>7} {:>7}\n",
                       g.condition, g.strategy, g.iteration == 0 ? std::string("all") : std::to_string(g.iteration),
                       g.trials, num(g.human_error), num(g.model_error), num(g.error_r, 2), num(g.error_rmse),
                       num(g.human_confusion), num(g.model_confusion), num(g.confusion_r, 2),
                       num(g.confusion_rmse), num(g.trace_r, 2), num(g.trace_rmse));
  }
  if (!r.issues.empty()) {
    out += "\nLeft out or flagged:\n";
    for (const auto& i : r.issues) out += fmt::format("  {}: {}\n", i.label, i.reason);
  }
  return out;
}

std::string json_estimate(const models::ParameterEstimate& p) {
  return fmt::format("{{\"estimate\": {}, \"conf.low\": {}, \"conf.high\": {}, \"low_at_bound\": {}, "
                     "\"high_at_bound\": {}}}",
                     io::json_number(p.estimate), io::json_number(p.conf_low), io::json_number(p.conf_high),
                     p.low_at_bound, p.high_at_bound);
}

std::string render_json(const models::StudyObserverFit& r, const FitArgs& a, const std::string& path_source) {
  auto fits = [&](const std::vector<models::ObserverFit>& fs) {
    std::string s = "[";
    for (std::size_t i = 0; i < fs.size(); ++i) {
      const auto& f = fs[i];
      s += fmt::format("{}\n    {{\"unit\": {}, \"condition\": {}, \"trials\": {}, \"samples\": {}, "
                       "\"logLik\": {}, \"sigma\": {}, \"phi\": {}",
                       i ? "," : "", io::json_quote(f.unit), io::json_quote(f.condition), f.trials, f.samples,
                       io::json_number(f.log_likelihood), io::json_number(f.sigma), io::json_number(f.phi));
      for (const auto& p : f.parameters) s += fmt::format(", {}: {}", io::json_quote(p.name), json_estimate(p));
      s += "}";
    }
    return s + "]";
  };
  std::string out = fmt::format(
      "{{\n  \"method\": \"Maximum likelihood, goal-inference observer; pad noise {}\", \"path\": {}, "
      "\"conf.level\": {},\n  \"participants\": {},\n  \"conditions\": {},\n  \"learning\": [",
      a.noise, io::json_quote(path_source), io::json_number(a.level), fits(r.participants), fits(r.conditions));
  for (std::size_t i = 0; i < r.learning.size(); ++i) {
    const auto& l = r.learning[i];
    out += fmt::format("{}\n    {{\"condition\": {}, \"gamma\": {}, \"beta0\": {}, \"statistic\": {}, \"df\": 1, "
                       "\"p.value\": {}, \"method\": {}}}",
                       i ? "," : "", io::json_quote(l.condition), json_estimate(l.gamma), io::json_number(l.beta0),
                       io::json_number(l.statistic), io::json_number(l.p_value), io::json_quote(l.method));
  }
  out += "],\n  \"agreement\": [";
  for (std::size_t i = 0; i < r.agreement.size(); ++i) {
    const auto& g = r.agreement[i];
    out += fmt::format(
        "{}\n    {{\"condition\": {}, \"strategy\": {}, \"iteration\": {}, \"trials\": {}, \"human_error\": {}, "
        "\"model_error\": {}, \"error_r\": {}, \"error_rmse\": {}, \"human_confusion\": {}, \"model_confusion\": {}, "
        "\"confusion_r\": {}, \"confusion_rmse\": {}, \"trace_r\": {}, \"trace_rmse\": {}}}",
        i ? "," : "", io::json_quote(g.condition), io::json_quote(g.strategy),
        g.iteration == 0 ? std::string("null") : std::to_string(g.iteration), g.trials, io::json_number(g.human_error),
        io::json_number(g.model_error), io::json_number(g.error_r), io::json_number(g.error_rmse),
        io::json_number(g.human_confusion), io::json_number(g.model_confusion), io::json_number(g.confusion_r),
        io::json_number(g.confusion_rmse), io::json_number(g.trace_r), io::json_number(g.trace_rmse));
  }
  out += "],\n  \"issues\": [";
  for (std::size_t i = 0; i < r.issues.size(); ++i) {
    out += fmt::format("{}\n    {{\"trial\": {}, \"reason\": {}}}", i ? "," : "", io::json_quote(r.issues[i].label),
                       io::json_quote(r.issues[i].reason));
  }
  return out + "]\n}\n";
}

void run_fit(const FitArgs& a) {
  models::ObserverFitSettings s;
  if (a.noise == "ar1") s.noise = models::PadNoise::ar1;
  else if (a.noise == "independent") s.noise = models::PadNoise::independent;
  else throw UsageError(fmt::format("--noise '{}': expected ar1 or independent", a.noise));
  if (a.format != "text" && a.format != "json") throw UsageError(fmt::format("--format '{}': expected text or json", a.format));
  s.thin = a.thin;
  s.fit_prior = a.fit_prior;
  s.prior_right = a.prior;
  s.beta_max = a.beta_max;
  s.tau_max = a.tau_max;
  s.level = a.level;
  s.pad_speed = a.pad_speed;
  s.learning = !a.no_learning;
  const sim::Geometry g;
  s.goals = sim::goals_of(g);
  s.validate();

  std::vector<models::TrialIssue> rejected;
  io::TraceOptions opts;
  opts.read_robot_path = true;  // robot_x, robot_y when the logs have them
  opts.on_reject = [&](const io::Rejection& r) {
    rejected.push_back({fmt::format("{}/{}/{}", r.participant, r.condition, r.iteration), r.reason});
  };
  io::TraceReader reader(io::expand_inputs(a.inputs), opts);
  std::vector<models::ObservedTrial> trials;
  std::size_t logged = 0, rebuilt = 0;
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
      const sim::RobotPath path = sim::robot_path(t, g);
      (path.rebuilt ? rebuilt : logged) += 1;
      o.path.clear();
      for (const auto& p : path.samples) o.path.push_back({p.t + t.times.front(), p.x, p.y});
    } catch (const Error& e) {
      rejected.push_back({o.label, fmt::format("{}:{}: {}; the trial is left out", t.file, t.line, e.what())});
      continue;
    }
    trials.push_back(std::move(o));
  }
  const std::string path_source =
      rebuilt == 0   ? std::string("robot path from the logs' robot_x, robot_y")
      : logged == 0  ? std::string("path rebuilt from strategy, variant, target and the default geometry")
                     : fmt::format("robot path from the logs for {} trials, rebuilt from strategy, variant, "
                                   "target and the default geometry for {}",
                                   logged, rebuilt);
  auto result = models::fit_study(std::move(trials), s);
  result.issues.insert(result.issues.begin(), rejected.begin(), rejected.end());
  io::AtomicOutput out(a.output);
  out.stream() << (a.format == "json" ? render_json(result, a, path_source)
                                          : render_text(result, a, rejected.size(), path_source));
  out.commit();
}

}  // namespace

void add_observer_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("observer", "The goal-inference observer (docs/observer.md): fit it to people.");
  cmd->require_subcommand(1);
  auto a = std::make_shared<FitArgs>();
  auto* fit = cmd->add_subcommand(
      "fit",
      "Fit the observer's rationality beta and delay tau (and optionally the prior) to pad-trace logs by "
      "maximum likelihood, per participant and pooled per condition, with profile-likelihood CIs, "
      "model-human agreement per strategy and iteration, and a test of learning (a change of beta with "
      "exposure).");
  fit->add_option("inputs", a->inputs, "log files, directories or globs (the format of `feint score`)")->required();
  fit->add_option("-o,--output", a->output, "output file (- = standard output)")->capture_default_str();
  fit->add_option("--format,-f", a->format, "text or json")->capture_default_str();
  fit->add_option("--noise", a->noise, "pad noise model: ar1 (default) or independent")->capture_default_str();
  fit->add_option("--thin", a->thin, "use one pad sample per this many seconds (0 = all)")->capture_default_str();
  fit->add_flag("--fit-prior", a->fit_prior, "also fit the prior P(right)");
  fit->add_option("--prior", a->prior, "the prior P(right) when it is not fitted")->capture_default_str();
  fit->add_option("--beta-max", a->beta_max, "upper end of beta's range (1/m)")->capture_default_str();
  fit->add_option("--tau-max", a->tau_max, "upper end of tau's range (s)")->capture_default_str();
  fit->add_option("--level", a->level, "confidence level of the CIs")->capture_default_str();
  fit->add_option("--pad-speed", a->pad_speed,
                  "pad speed for confusion when the logs have none (pad units/s)")->capture_default_str();
  fit->add_flag("--no-learning", a->no_learning, "skip the learning test");
  fit->callback([a] { run_fit(*a); });
}

}  // namespace feint::cli

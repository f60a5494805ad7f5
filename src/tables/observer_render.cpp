#include "feint/tables/observer_render.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "feint/io/number.hpp"
#include "feint/tables/writers.hpp"

namespace feint::tables {

namespace {

std::string num(double x, int digits = 3) {
  return std::isnan(x) ? std::string("-") : fmt::format("{:.{}f}", x, digits);
}

std::string ci_text(const models::ParameterEstimate& p) {
  return fmt::format("{} [{}{}, {}{}]", num(p.estimate), p.low_at_bound ? "<=" : "",
                     num(p.conf_low), num(p.conf_high), p.high_at_bound ? "(bound)" : "");
}

/// The two conditions compared on the participants' fits: which way, how much, how sure.
std::string comparisons_text(const std::vector<models::ObserverComparison>& comparisons) {
  if (comparisons.empty()) return "";
  const auto& first = comparisons.front();
  std::string out =
      first.paired ? fmt::format("\nConditions compared on the participants' fits, paired within each participant ({} "
                                 "against {}; paired t test with d_z and the JZS Bayes factor, Wilcoxon signed-rank test "
                                 "with r_rb):\n",
                                 first.condition_a, first.condition_b)
                   : fmt::format("\nConditions compared on the participants' fits ({} against {}; Welch t test with d "
                                 "and the JZS Bayes factor, Mann-Whitney test with r_rb):\n",
                                 first.condition_a, first.condition_b);
  for (const auto& c : comparisons) {
    const auto& w = c.welch;
    if (!w.computed) {
      out += fmt::format("  {}: {}\n", c.parameter, w.note);
      continue;
    }
    const bool log_beta = c.parameter == "log beta";
    // A difference of log betas is the log of a ratio: state the ratio of geometric means.
    const std::string size =
        log_beta ? fmt::format("beta ratio {:.2f} [{:.2f}, {:.2f}] (geometric means {:.3f} vs {:.3f} /m)",
                               std::exp(*w.estimate), std::exp(*w.conf_low), std::exp(*w.conf_high),
                               std::exp(*w.mean1), std::exp(*w.mean2))
                 : fmt::format("difference {:.3f} s [{:.3f}, {:.3f}] (means {:.3f} vs {:.3f} s)", *w.estimate,
                               *w.conf_low, *w.conf_high, *w.mean1, *w.mean2);
    out += fmt::format("  {}: {}; {}; {}{}\n", c.parameter, size, apa_string(w), apa_string(c.rank),
                       c.at_bound ? fmt::format(" ({} estimate(s) at the range's bound, kept)", c.at_bound) : "");
  }
  return out;
}

/// A table of fits (per participant or pooled), with the prior's column when it was fitted.
std::string fits_text(const std::vector<models::ObserverFit>& fs, const char* title, bool fit_prior) {
  std::string out = fmt::format("\n{}\n", title);
  out += fmt::format("{:<12} {:<10} {:>6} {:>7}  {:<30} {:<30}{} {:>7} {:>6} {:>12}\n", "unit", "condition",
                     "trials", "samples", "beta (1/m) [CI]", "tau (s) [CI]",
                     fit_prior ? fmt::format(" {:<30}", "P(right) [CI]") : "", "sigma", "phi", "logLik");
  for (const auto& f : fs) {
    std::string prior;
    if (fit_prior) prior = fmt::format(" {:<30}", ci_text(f.parameter("prior_right")));
    out += fmt::format("{:<12} {:<10} {:>6} {:>7}  {:<30} {:<30}{} {:>7} {:>6} {:>12}\n", f.unit, f.condition,
                       f.trials, f.samples, ci_text(f.parameter("beta")), ci_text(f.parameter("tau")), prior,
                       num(f.sigma, 4), num(f.phi, 3), num(f.log_likelihood, 2));
  }
  return out;
}

std::string issues_text(const std::vector<models::TrialIssue>& issues) {
  if (issues.empty()) return "";
  std::string out = "\nLeft out or flagged:\n";
  for (const auto& i : issues) out += fmt::format("  {}: {}\n", i.label, i.reason);
  return out;
}

// The learning test per condition (pad and pointer fits alike).
std::string learning_text(const std::vector<models::LearningTest>& learning) {
  if (learning.empty()) return "";
  std::string out =
      "\nLearning: beta_k = beta0 exp(gamma exposure_k), exposure = earlier trials of the same "
      "strategy\n";
  for (const auto& l : learning) {
    out += fmt::format("  {:<10} gamma = {}, beta0 = {}, LR chi2(1) = {}, p = {}\n", l.condition,
                       ci_text(l.gamma), num(l.beta0), num(l.statistic, 3),
                       l.p_value < 1e-4 ? fmt::format("{:.2e}", l.p_value) : num(l.p_value, 4));
  }
  return out;
}

// The model-human agreement table; `what` says what is compared, in the title's parentheses.
std::string agreement_text(const std::vector<models::AgreementRow>& agreement, const std::string& what) {
  std::string out = "\nModel-human agreement (" + what + ")\n";
  out += fmt::format(
      "{:<10} {:<13} {:>9} {:>6}  {:>7} {:>7} {:>6} {:>6}  {:>7} {:>7} {:>6} {:>6}  {:>7} {:>7}\n",
      "condition", "strategy", "iteration", "trials", "E human", "E model", "E r", "E rmse",
      "C human", "C model", "C r", "C rmse", "trace r", "rmse");
  for (const auto& g : agreement) {
    out += fmt::format(
        "{:<10} {:<13} {:>9} {:>6}  {:>7} {:>7} {:>6} {:>6}  {:>7} {:>7} {:>6} {:>6}  {:>7} "
        "{:>7}\n",
        g.condition, g.strategy,
        g.iteration == 0 ? std::string("all") : std::to_string(g.iteration), g.trials,
        num(g.human_error), num(g.model_error), num(g.error_r, 2), num(g.error_rmse),
        num(g.human_confusion), num(g.model_confusion), num(g.confusion_r, 2),
        num(g.confusion_rmse), num(g.trace_r, 2), num(g.trace_rmse));
  }
  return out;
}

std::string render_text(const models::StudyObserverFit& r, const models::ObserverFitSettings& a,
                        std::size_t rejected_rows, const std::string& path_source) {
  std::string out = fmt::format(
      "Goal-inference observer fitted to {} trial(s) ({}); pad noise: {}{}; {}% profile-likelihood "
      "CIs.\n",
      r.trials_used, path_source,
      a.noise == models::PadNoise::ar1 ? "Gaussian AR(1) around b(t)"
                                       : "independent Gaussian around b(t)",
      a.thin > 0 ? fmt::format(", one sample per {} s", a.thin) : "", num(100 * a.level, 0));
  if (rejected_rows > 0)
    out += fmt::format("{} trial(s) left out while reading the logs (see below).\n", rejected_rows);
  out += fits_text(r.participants, "Per participant", a.fit_prior);
  out += fits_text(r.conditions, "Pooled per condition", a.fit_prior);
  out += learning_text(r.learning);
  out += agreement_text(r.agreement, "model b(t) at each participant's fit vs the pad; r = Pearson correlation");
  out += comparisons_text(r.comparisons);
  out += issues_text(r.issues);
  return out;
}

std::string json_estimate(const models::ParameterEstimate& p) {
  return fmt::format(
      "{{\"estimate\": {}, \"conf.low\": {}, \"conf.high\": {}, \"low_at_bound\": {}, "
      "\"high_at_bound\": {}}}",
      io::json_number(p.estimate), io::json_number(p.conf_low), io::json_number(p.conf_high),
      p.low_at_bound, p.high_at_bound);
}

std::string json_fits(const std::vector<models::ObserverFit>& fs) {
  std::string s = "[";
  for (std::size_t i = 0; i < fs.size(); ++i) {
    const auto& f = fs[i];
    s += fmt::format(
        "{}\n    {{\"unit\": {}, \"condition\": {}, \"trials\": {}, \"samples\": {}, "
        "\"logLik\": {}, \"sigma\": {}, \"phi\": {}",
        i ? "," : "", io::json_quote(f.unit), io::json_quote(f.condition), f.trials, f.samples,
        io::json_number(f.log_likelihood), io::json_number(f.sigma), io::json_number(f.phi));
    for (const auto& p : f.parameters) s += fmt::format(", {}: {}", io::json_quote(p.name), json_estimate(p));
    s += "}";
  }
  return s + "]";
}

std::string json_comparisons(const std::vector<models::ObserverComparison>& comparisons) {
  std::string out = "[";
  for (std::size_t i = 0; i < comparisons.size(); ++i) {
    const auto& c = comparisons[i];
    const std::vector<std::string_view> columns{"test", "group1", "group2", "n1", "n2", "mean1", "mean2",
                                                "estimate", "conf_low", "conf_high", "statistic", "df",
                                                "p_value", "cohen_d", "cohen_d_low", "cohen_d_high",
                                                "bf10", "rank_biserial", "rank_biserial_low",
                                                "rank_biserial_high", "note"};
    TidyRow w{c.parameter, std::nullopt, c.condition_a, c.condition_b, c.welch, "", std::nullopt, ""};
    TidyRow k{c.parameter, std::nullopt, c.condition_a, c.condition_b, c.rank, "", std::nullopt, ""};
    std::string tests = write_json(columns, tidy_records(std::vector<TidyRow>{w, k}, columns));
    while (!tests.empty() && tests.back() == '\n') tests.pop_back();
    out += fmt::format("{}\n    {{\"parameter\": {}, \"at_bound\": {}, \"tests\": {}}}", i ? "," : "",
                       io::json_quote(c.parameter), c.at_bound, tests);
  }
  return out + "]";
}

std::string json_issues(const std::vector<models::TrialIssue>& issues) {
  std::string out = "[";
  for (std::size_t i = 0; i < issues.size(); ++i) {
    out += fmt::format("{}\n    {{\"trial\": {}, \"reason\": {}}}", i ? "," : "", io::json_quote(issues[i].label),
                       io::json_quote(issues[i].reason));
  }
  return out + "]";
}

// The learning tests' JSON objects, without the brackets.
std::string learning_json(const std::vector<models::LearningTest>& learning) {
  std::string out;
  for (std::size_t i = 0; i < learning.size(); ++i) {
    const auto& l = learning[i];
    out += fmt::format(
        "{}\n    {{\"condition\": {}, \"gamma\": {}, \"beta0\": {}, \"statistic\": {}, \"df\": 1, "
        "\"p.value\": {}, \"method\": {}}}",
        i ? "," : "", io::json_quote(l.condition), json_estimate(l.gamma), io::json_number(l.beta0),
        io::json_number(l.statistic), io::json_number(l.p_value), io::json_quote(l.method));
  }
  return out;
}

// The agreement rows' JSON objects, without the brackets.
std::string agreement_json(const std::vector<models::AgreementRow>& agreement) {
  std::string out;
  for (std::size_t i = 0; i < agreement.size(); ++i) {
    const auto& g = agreement[i];
    out += fmt::format(
        "{}\n    {{\"condition\": {}, \"strategy\": {}, \"iteration\": {}, \"trials\": {}, "
        "\"human_error\": {}, "
        "\"model_error\": {}, \"error_r\": {}, \"error_rmse\": {}, \"human_confusion\": {}, "
        "\"model_confusion\": {}, "
        "\"confusion_r\": {}, \"confusion_rmse\": {}, \"trace_r\": {}, \"trace_rmse\": {}}}",
        i ? "," : "", io::json_quote(g.condition), io::json_quote(g.strategy),
        g.iteration == 0 ? std::string("null") : std::to_string(g.iteration), g.trials,
        io::json_number(g.human_error), io::json_number(g.model_error), io::json_number(g.error_r),
        io::json_number(g.error_rmse), io::json_number(g.human_confusion),
        io::json_number(g.model_confusion), io::json_number(g.confusion_r),
        io::json_number(g.confusion_rmse), io::json_number(g.trace_r),
        io::json_number(g.trace_rmse));
  }
  return out;
}

std::string render_json(const models::StudyObserverFit& r, const models::ObserverFitSettings& a,
                        const std::string& path_source) {
  std::string out = fmt::format(
      "{{\n  \"model\": \"pad\", \"method\": \"Maximum likelihood, goal-inference observer; pad noise {}\", \"path\": "
      "{}, "
      "\"conf.level\": {},\n  \"participants\": {},\n  \"conditions\": {},\n  \"learning\": [",
      a.noise == models::PadNoise::ar1 ? "ar1" : "independent", io::json_quote(path_source),
      io::json_number(a.level), json_fits(r.participants), json_fits(r.conditions));
  out += learning_json(r.learning) + "],\n  \"agreement\": [" + agreement_json(r.agreement);
  out += "],\n  \"comparisons\": " + json_comparisons(r.comparisons);
  out += ",\n  \"issues\": " + json_issues(r.issues);
  return out + "\n}\n";
}

/// The pointer fit's model in words: targets, layouts, noise, thinning (text and JSON).
std::string pointer_model_text(const models::PointerStudyObserverFit& r, const models::ObserverFitSettings& a) {
  const std::string k = r.min_targets == r.max_targets ? fmt::format("{}", r.max_targets)
                                                       : fmt::format("{} to {}", r.min_targets, r.max_targets);
  return fmt::format(
      "K-goal observer over {} targets ({}); pointer = posterior mean of the targets, sum_k P(G_k | path seen "
      "up to t - tau) G_k, uniform prior, plus {} on each axis, sigma in layout scales{}",
      k, r.layouts == 1 ? std::string("one fixed layout") : fmt::format("targets placed per round, {} layouts", r.layouts),
      a.noise == models::PadNoise::ar1 ? "Gaussian AR(1) error" : "independent Gaussian error",
      a.thin > 0 ? fmt::format(", one sample per {} s", a.thin) : "");
}

}  // namespace

std::string render_pointer_observer_fit_text(const models::PointerStudyObserverFit& r,
                                             const models::ObserverFitSettings& a, std::size_t rejected_rows,
                                             const std::string& path_source) {
  std::string out = fmt::format("Goal-inference observer fitted to {} pointer trial(s) ({}); {}; {}% profile-likelihood CIs.\n",
                                r.trials_used, path_source, pointer_model_text(r, a), num(100 * a.level, 0));
  if (rejected_rows > 0)
    out += fmt::format("{} trial(s) left out while reading the logs (see below).\n", rejected_rows);
  out += fits_text(r.participants, "Per participant", false);
  out += fits_text(r.conditions, "Pooled per condition", false);
  out += learning_text(r.learning);
  out += agreement_text(r.agreement, "model mean m(t) at each participant's fit vs the pointer; E, C and trace in "
                                     "layout scales, trace = distance to the true target; r = Pearson correlation");
  out += comparisons_text(r.comparisons);
  out += issues_text(r.issues);
  return out;
}

std::string render_pointer_observer_fit_json(const models::PointerStudyObserverFit& r,
                                             const models::ObserverFitSettings& a, const std::string& path_source) {
  std::string out = fmt::format(
      "{{\n  \"model\": \"pointer\", \"method\": {}, \"noise\": \"{}\", \"targets\": {{\"min\": {}, \"max\": {}}}, "
      "\"layouts\": {}, \"sigma.unit\": \"layout scales\", \"path\": {}, \"conf.level\": {},\n  \"participants\": "
      "{},\n  \"conditions\": {}",
      io::json_quote("Maximum likelihood, " + pointer_model_text(r, a)),
      a.noise == models::PadNoise::ar1 ? "ar1" : "independent", r.min_targets, r.max_targets, r.layouts,
      io::json_quote(path_source), io::json_number(a.level), json_fits(r.participants), json_fits(r.conditions));
  out += ",\n  \"learning\": [" + learning_json(r.learning) + "],\n  \"agreement\": [" + agreement_json(r.agreement) + "]";
  out += ",\n  \"comparisons\": " + json_comparisons(r.comparisons);
  out += ",\n  \"issues\": " + json_issues(r.issues);
  return out + "\n}\n";
}

std::string render_observer_fit_text(const sim::ObserverLogFit& fit,
                                     const models::ObserverFitSettings& settings) {
  return render_text(fit.fit, settings, fit.rejected_rows, fit.path_source);
}

std::string render_observer_fit_json(const sim::ObserverLogFit& fit,
                                     const models::ObserverFitSettings& settings) {
  return render_json(fit.fit, settings, fit.path_source);
}

}  // namespace feint::tables

// feint/models/observer_fit.hpp - fitting the goal-inference observer (goal_inference.hpp) to
// people's pad traces by maximum likelihood (docs/observer.md, "Fitting the observer to people").
//
// Model of the pad. In trial j the participant's pad at time t_i is the observer's delayed belief
// plus an error that carries over from sample to sample (pads move slowly; at 25-60 Hz neighbouring
// samples are not independent):
//
//     pad_i = b(t_i; beta, tau, prior) + e_i,    e_i = phi e_{i-1} + u_i,   u_i ~ N(0, sigma^2)
//
// (PadNoise::ar1, the default; the likelihood is conditional on each trial's first used sample).
// sigma and phi are shared by the trials of a fit and profiled out in closed form: phi = S_xy / S_xx
// and sigma^2 = (S_yy - S_xy^2 / S_xx) / m over the m residual pairs, so the profile log-likelihood
// is -m/2 (log(2 pi sigma^2) + 1). PadNoise::independent sets phi = 0 (e_i iid), which is honest only
// on samples thinned to one per `thin` seconds far enough apart.
//
// beta in [0, beta_max], tau in [0, tau_max] (and prior_right in (0, 1) when fitted, on the logit
// scale) maximise the log-likelihood: the profile over tau (the others re-maximised) is rough, so it
// is scanned on a coarse grid, finer near its best, and its best local maxima refined.
// CIs are profile-likelihood intervals, {theta_j : 2 (l_max - l_p(theta_j)) <= chi2_1(level)}: each
// end solves sign(v - theta_j) sqrt(2 (l_max - l_p(v))) = +-z by safeguarded secant steps from the
// Wald end, the other parameters re-maximised at each step; an end that reaches a bound is reported
// as the bound and flagged (with a note). A profile that meets a point higher than the maximum makes
// the fit climb from there and search the CIs again (docs/observer.md, "Estimation and CIs").
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "feint/metrics/trial_metrics.hpp"
#include "feint/models/deceptiveness.hpp"
#include "feint/models/goal_inference.hpp"
#include "feint/stats/htest.hpp"

namespace feint::models {

/// One trial as seen by the fit: the robot's path and the participant's pad trace on the same clock.
struct ObservedTrial {
  std::string participant;
  std::string condition;
  long long iteration = 0;
  std::string strategy;  // names the paper uses (agreement tables group by them); may be empty
  std::string variant;
  GoalSide goal = GoalSide::right;   // the true target
  std::vector<PathSample> path;      // robot path
  std::vector<double> times;         // pad sample times (s)
  std::vector<double> pads;          // pad positions (0 = left, 1 = right)
  std::optional<double> pad_speed;   // for scoring confusion in the agreement tables
  double exposure = 0;               // earlier trials of this strategy (fit_study fills it)
  std::string label;                 // how messages name the trial (fit_study fills it if empty)
};

enum class PadNoise { ar1, independent };

struct ObserverFitSettings {
  Goals goals;
  double prior_right = 0.5;  // the prior when it is not fitted
  bool fit_prior = false;
  double beta_max = 20.0;    // 1/m: upper end of beta's range
  double tau_max = 2.0;      // s: upper end of tau's range
  PadNoise noise = PadNoise::ar1;
  double thin = 0.0;         // s: keep one pad sample per `thin` seconds (0 = all)
  double level = 0.95;       // CI level
  double pad_speed = 0.8;    // v for confusion when a trial has none (agreement tables)
  metrics::MetricSettings metric;  // trimming etc. for the agreement tables
  bool learning = true;      // fit_study: test a change of beta with exposure per condition

  /// Throws UsageError naming the setting.
  void validate() const;
};

struct ParameterEstimate {
  std::string name;  // beta, tau, prior_right, gamma
  double estimate = 0;
  double conf_low = 0;
  double conf_high = 0;
  bool low_at_bound = false;   // the CI's lower end is the range's bound (not a likelihood root)
  bool high_at_bound = false;
};

struct ObserverFit {
  std::string unit;       // a participant, or a condition for a pooled fit
  std::string condition;
  std::size_t trials = 0;
  std::size_t samples = 0;      // pad samples used
  double log_likelihood = 0;    // at the maximum (sigma, phi profiled)
  double sigma = 0;             // innovation sd (pad units)
  double phi = 0;               // lag-1 autocorrelation of the pad error (0 for independent)
  std::vector<ParameterEstimate> parameters;  // beta, tau[, prior_right]
  double prior_right = 0.5;     // the fitted prior, or the fixed one
  std::size_t evaluations = 0;  // likelihood evaluations
  std::vector<std::string> notes;  // e.g. "beta at the upper bound 20 ..."

  const ParameterEstimate& parameter(std::string_view name) const;
  /// beta, tau and the prior (fitted or fixed) at the maximum.
  GoalObserver observer() const;
};

/// Checks one trial for the fit; returns the reason it cannot be used (without the label) or
/// nullopt. Reasons: path problems (validate_path), fewer than 3 pad samples, non-finite or
/// non-increasing pad times, zero pad duration, non-finite pads.
std::optional<std::string> trial_problem(const ObservedTrial& trial);

/// The maximum-likelihood fit of beta, tau (and the prior) to `trials` (all must pass
/// trial_problem). Throws InvalidData when `trials` is empty. `start`, if given, is added to the
/// scan's grid (fit_study gives a pooled fit its participants' mean).
ObserverFit fit_observer(std::span<const ObservedTrial> trials, const ObserverFitSettings& settings,
                         std::string unit, const std::optional<GoalObserver>& start = std::nullopt);

/// The profile log-likelihood (sigma, phi profiled) at the given parameters.
double observer_log_likelihood(std::span<const ObservedTrial> trials, const ObserverFitSettings& settings,
                               const GoalObserver& observer);

/// Model-human agreement over a group of trials: the model's b(t) (at the participant's fitted
/// parameters) against the pad, per trial (error and confusion, scored alike) and per sample.
struct AgreementRow {
  std::string condition;   // "all" for every condition
  std::string strategy;    // "all" for every strategy
  long long iteration = 0; // 0 for every iteration
  std::size_t trials = 0;
  double human_error = 0, model_error = 0;  // means
  double error_r = 0, error_rmse = 0;
  double human_confusion = 0, model_confusion = 0;
  double confusion_r = 0, confusion_rmse = 0;
  double trace_r = 0, trace_rmse = 0;  // over all pad samples of the group
};

/// Learning: beta_k = beta0 exp(gamma * exposure_k) against gamma = 0, by a likelihood-ratio test
/// (chi-squared, 1 df), in a condition's pooled fit.
struct LearningTest {
  std::string condition;
  ParameterEstimate gamma;      // per earlier trial of the same strategy; profile CI
  double beta0 = 0;             // beta at exposure 0
  double statistic = 0;         // 2 (l1 - l0)
  double df = 1;
  double p_value = 1;
  double log_likelihood0 = 0, log_likelihood1 = 0;
  std::string method = "Likelihood-ratio test of gamma = 0 in beta_k = beta0 exp(gamma exposure_k)";
};

/// The learning test on trials whose `exposure` is filled, against their pooled fit `pooled` (its
/// unit names the result).
LearningTest test_learning(std::span<const ObservedTrial> trials, const ObserverFitSettings& settings,
                           const ObserverFit& pooled);

struct TrialIssue {
  std::string label;
  std::string reason;
};

/// One parameter of the participants' fits compared between two conditions (participant level:
/// one estimate per participant). beta is compared on the log scale (it is a rate, positive and
/// right-skewed: a ratio of betas is what a difference of logs estimates); tau on its own scale.
/// `welch`: Welch's t test with Cohen's d and its CI and the JZS Bayes factor (r = sqrt(2)/2);
/// `rank`: the Mann–Whitney test with the rank-biserial correlation and its CI (docs/observer.md).
struct ObserverComparison {
  std::string parameter;  // "log beta" or "tau"
  std::string condition_a, condition_b;
  stats::TestResult welch;
  stats::TestResult rank;
  std::size_t at_bound = 0;  // participants whose estimate lies at the range's bound (kept)
  /// Within participants (someone fitted in both conditions): `welch` holds the paired t test
  /// (d_z, one-sample JZS BF) and `rank` the Wilcoxon signed-rank test of each participant's pair.
  bool paired = false;
};

struct StudyObserverFit {
  std::vector<ObserverComparison> comparisons;  // two conditions: log beta, then tau
  std::vector<ObserverFit> participants;
  std::vector<ObserverFit> conditions;   // pooled per condition
  std::vector<AgreementRow> agreement;
  std::vector<LearningTest> learning;
  std::vector<TrialIssue> issues;       // trials (or participants) left out, and why
  std::size_t trials_used = 0;
};

/// The whole study: every trial checked (a bad one is reported in `issues` by label and left out;
/// the rest are fitted), per-participant fits, pooled fits per condition, agreement per condition x
/// strategy x iteration (with "all" margins), the learning test per condition, and with exactly two
/// conditions the participants' beta and tau compared between them (`comparisons`).
StudyObserverFit fit_study(std::vector<ObservedTrial> trials, const ObserverFitSettings& settings);

/// beta (log) and tau of the participants' fits compared between conditions a and b, at `level`.
/// Empty when either condition has fewer than two participants.
std::vector<ObserverComparison> compare_conditions(std::span<const ObserverFit> participants,
                                                   const std::string& a, const std::string& b,
                                                   double level);

}  // namespace feint::models

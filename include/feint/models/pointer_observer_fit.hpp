// feint/models/pointer_observer_fit.hpp - the goal-inference observer over K >= 2 goals
// (goal_posterior.hpp) fitted to people's pointer traces, the logs of K targets and a pointer, by
// maximum likelihood (docs/observer.md, "Fitting the observer to pointer traces (K targets)").
//
// Model of the pointer. In trial j (its layout: start, targets G_0 .. G_{K-1}, scale s_j =
// metrics::layout_scale) the pointer at t_i is the observer's delayed posterior mean plus an error
// that carries over from sample to sample, on each axis:
//
//     p_i = m(t_i) + s_j e_i,    m(t) = sum_k P(G_k | path seen up to t - tau; beta) G_k,
//     e_i = (e^x_i, e^y_i),      e^a_i = phi e^a_{i-1} + u^a_i,   u^a_i ~ N(0, sigma^2)
//
// with the uniform prior P(G_k) = 1/K (before the robot moves m is the targets' centroid) and the
// start S = the path's first point (Dragan & Srinivasa 2013; Baker, Saxe & Tenenbaum 2009). The x
// and y errors are independent given phi and sigma, which are shared by the trials of a fit and
// profiled out in closed form as in the pad's fit (observer_fit.hpp), over the x pairs and the y
// pairs of consecutive samples pooled: phi = S_xy / S_xx, sigma^2 = (S_yy - S_xy^2 / S_xx) / m,
// l = -m/2 (log(2 pi sigma^2) + 1), m = 2 (n_j - 1) summed over trials (the likelihood is
// conditional on each trial's first used sample). sigma is in layout scales (the residuals are
// divided by their trial's s_j, so one sigma serves layouts of any size; at K = 2 one layout scale
// is one pad unit), and l is the log density of the pointer measured in layout scales.
// PadNoise::independent sets phi = 0 (every sample's x and y, m = 2 n_j).
//
// beta in [0, beta_max] and tau in [0, tau_max] are found and their profile CIs computed by the
// pad fit's optimisers (the scan over tau, the profile-likelihood ends, the refit from a higher
// point; docs/observer.md "Estimation and CIs"). The prior is not fitted.
//
// As for the pad, a study's fit adds two things (docs/observer.md, "Agreement and learning on
// pointer traces"):
// - Learning: in a condition's pooled fit, beta_k = beta0 exp(gamma exposure_k) (exposure = the
//   participant's earlier trials of the same strategy), gamma = 0 tested by the likelihood ratio
//   against chi-squared(1), gamma's profile CI in [-1, 1]: the pad's optimiser and test.
// - Model-human agreement: with each participant's fitted beta and tau, the model's mean m(t_i) is a
//   belief-point trace; it and the pointer are scored alike (metrics::score_belief_points: error and
//   confusion in layout scales, the fit's MetricSettings: trimming, dead band, normalisation), per
//   condition x strategy x iteration cell with "all" margins. The traces are compared sample by
//   sample on the distance to the true target in layout scales, |p_i - G*| / s and |m(t_i) - G*| / s
//   (AgreementRow::trace_r, trace_rmse): the quantity the error integrates, and at K = 2 on the
//   paper's layout the pad's |pad_i - target| (the pad's RMSE exactly).
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "feint/metrics/layout.hpp"
#include "feint/models/goal_inference.hpp"
#include "feint/models/goal_posterior.hpp"
#include "feint/models/observer_fit.hpp"

namespace feint::models {

/// One trial as seen by the fit: the round's layout, the robot's path and the pointer on the same
/// clock.
struct PointerObservedTrial {
  std::string participant;
  std::string condition;
  long long iteration = 0;
  std::string strategy;  // as logged: the agreement table's cells and the exposure count use it
  std::string variant;
  metrics::Layout layout;          // the start and the K targets (m)
  std::size_t target = 0;          // the true target's index (not used by the likelihood)
  std::vector<PathSample> path;    // robot path
  std::vector<double> times;       // pointer sample times (s)
  std::vector<double> x, y;        // the pointer (m)
  std::optional<double> pointer_speed;  // layout scales/s: confusion's v in the agreement table
  double exposure = 0;             // earlier trials of this strategy (fit_pointer_study fills it)
  std::string label;               // how messages name the trial (fit_pointer_study fills it if empty)
};

/// Checks one trial for the fit; returns the reason it cannot be used (without the label) or
/// nullopt. Reasons: path problems (validate_path), a layout with fewer than 2 targets, a point
/// that is not finite, two targets at one point or a target at the start, a true target that is
/// not one of the layout's, times and pointer of different lengths, fewer than 3 samples,
/// non-finite or non-increasing times, zero duration, a pointer that is not finite.
std::optional<std::string> pointer_trial_problem(const PointerObservedTrial& trial);

/// The model's mean m(t_i) (m) at each of the trial's pointer sample times, at beta and tau: the
/// likelihood's own computation (validates the trial and the parameters: InvalidData, UsageError).
std::vector<metrics::MapPoint> pointer_observer_means(const PointerObservedTrial& trial, double beta,
                                                      double tau);

/// The profile log-likelihood (sigma and phi profiled) at beta and tau. The settings used are
/// noise and thin; `fit_prior` must be false (UsageError), prior_right, goals, pad_speed and the
/// learning switch are not used (the prior is uniform over each trial's K targets).
double pointer_observer_log_likelihood(std::span<const PointerObservedTrial> trials,
                                       const ObserverFitSettings& settings, double beta, double tau);

/// The maximum-likelihood fit of beta and tau with profile CIs (every trial must pass
/// pointer_trial_problem; InvalidData names the first that does not, or says there is none).
/// `start` (beta, tau; its prior must be empty) is added to the scan's grid. The result's sigma is
/// in layout scales; its prior_right is NaN (not a parameter of this model). Settings as
/// pointer_observer_log_likelihood.
ObserverFit fit_pointer_observer(std::span<const PointerObservedTrial> trials,
                                 const ObserverFitSettings& settings, std::string unit,
                                 const std::optional<GoalPosteriorObserver>& start = std::nullopt);

/// The learning test, beta_k = beta0 exp(gamma exposure_k) against gamma = 0, on trials whose
/// `exposure` is filled, against `pooled`: their pooled fit (fit_pointer_observer on the same trials
/// and settings; its unit names the result). Settings as pointer_observer_log_likelihood; every
/// trial must pass pointer_trial_problem (InvalidData).
LearningTest test_pointer_learning(std::span<const PointerObservedTrial> trials, const ObserverFitSettings& settings,
                                   const ObserverFit& pooled);

/// Model-human agreement per condition x strategy x iteration (with "all" margins; rows ordered as
/// the pad's): each trial whose participant has a fit in `participants` (matched by unit =
/// participant and condition) is scored with the pointer and with the model's mean at that fit's
/// beta and tau (pointer_observer_means), by metrics::score_belief_points with settings.metric and
/// v = the trial's pointer_speed, else settings.pad_speed; the traces compared on the distance to
/// the true target in layout scales. A trial that cannot be scored is named in `issues` and left
/// out of the table.
std::vector<AgreementRow> pointer_agreement(std::span<const PointerObservedTrial> trials,
                                            std::span<const ObserverFit> participants,
                                            const ObserverFitSettings& settings, std::vector<TrialIssue>& issues);

/// A study's pointer fits: per participant, pooled per condition, the learning test, the two
/// conditions compared, and the model-human agreement.
struct PointerStudyObserverFit {
  std::vector<ObserverComparison> comparisons;  // two conditions: log beta, then tau
  std::vector<ObserverFit> participants;
  std::vector<ObserverFit> conditions;          // pooled per condition
  std::vector<AgreementRow> agreement;          // pointer_agreement
  std::vector<LearningTest> learning;           // per condition (none when settings.learning is off)
  std::vector<TrialIssue> issues;               // trials (or participants) left out, and why; notes
  std::size_t trials_used = 0;
  std::size_t min_targets = 0, max_targets = 0; // K over the trials fitted
  std::size_t layouts = 0;                      // distinct layouts among them
};

/// Every trial checked (a bad one is named in `issues` and left out), each trial's exposure counted
/// (earlier trials of its strategy by its participant, by iteration), per-participant fits, pooled
/// fits per condition (started also from their participants' mean) with their learning test (when
/// settings.learning), with exactly two conditions the participants' log beta and tau compared
/// (compare_conditions), and the model-human agreement at the participants' fits.
PointerStudyObserverFit fit_pointer_study(std::vector<PointerObservedTrial> trials,
                                          const ObserverFitSettings& settings);

}  // namespace feint::models

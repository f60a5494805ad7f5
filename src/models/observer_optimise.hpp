// src/models/observer_optimise.hpp - the optimisers of the observer fit (observer_optimise.cpp):
// Nelder-Mead, the 1-D parabola search, the observed information and the profile-likelihood CI
// search (observer_optimise.cpp); the fits' box, scan plan, settled maximum with its CIs and
// estimates with their notes (observer_settle.cpp). They see the log-likelihood only as a function
// of the parameter vector; the likelihoods are in observer_fit.cpp (pad traces) and
// pointer_observer_fit.cpp (pointer traces over K targets) (docs/observer.md, "Estimation and CIs").
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "feint/models/observer_fit.hpp"

namespace feint::models::detail::observer {

// Full parameter vector: beta (1/m), tau (s), logit of the prior, gamma (learning rate).
enum Param : std::size_t { kBeta = 0, kTau = 1, kPrior = 2, kGamma = 3 };
constexpr std::size_t kParams = 4;
using Theta = std::array<double, kParams>;

/// The log-likelihood (profiled over sigma and phi) at a parameter vector: what is maximised.
using Objective = std::function<double(const Theta&)>;

/// The parameters' range, their scales (the steps and tolerances are in these units) and which of
/// them the fit moves.
struct Box {
  Theta lo{}, hi{}, scale{};
  std::array<bool, kParams> free{};
};

Theta clamp(Theta th, const Box& b);

/// Nelder & Mead (1965) on the free coordinates, every point projected into the box. Maximises f;
/// returns the best point and its value.
std::pair<Theta, double> nelder_mead(const Objective& f, Theta start, const Box& box,
                                     const std::array<bool, kParams>& free, double step_factor, int max_evals);

/// Maximises f over coordinate k by successive parabolas through points spaced h around th, until
/// one moves less than `settle` h; nullopt when the points are not concave. `curvature`, if given,
/// receives the last parabola's second derivative.
std::optional<std::pair<Theta, double>> parabolic_max(const Objective& f, Theta th, std::size_t k, double h,
                                                      const Box& box, double settle = 0.05,
                                                      double* curvature = nullptr);

/// Maximises f over the box's free parameters except `fixed` (kParams: none). Warm (a start near
/// the maximum, steps h): parabolas; otherwise Brent (one parameter) or Nelder-Mead.
std::pair<Theta, double> maximise(const Objective& f, const Box& box, const Theta& start, std::size_t fixed,
                                  bool warm, const Theta& h = Theta{});

/// What the observed information at the maximum gives: the Wald SE and the conditional SE
/// (1 / sqrt(-H_jj)) of each free parameter (zeros where the Hessian is not negative definite), and
/// the ridge of the quadratic approximation: where the other parameters' maximum moves per unit of
/// parameter j, ridge[j][k] = cov(k, j) / cov(j, j).
struct StandardErrors {
  Theta wald{}, cond{};
  std::array<Theta, kParams> ridge{};
};

/// The observed information at the maximum (th, l0) by central differences.
StandardErrors standard_errors(const Objective& f, const Box& box, const Theta& th, double l0);

struct Interval {
  double low = 0, high = 0;
  bool low_at_bound = false, high_at_bound = false;
  bool hull = false;  // the profile fell below the cut-off again beyond a first crossing
  /// A point the profile met whose log-likelihood exceeds lmax by more than kHigherTolerance: the
  /// maximum was not the global one, and the fit starts again from here (the ends are then void).
  std::optional<std::pair<Theta, double>> higher;
};

/// How much higher than the maximum a profile point must be to count as a higher maximum (below
/// it, Nelder-Mead's and the parabolas' tolerances, ~1e-5, explain the difference).
constexpr double kHigherTolerance = 1e-4;

/// Profile-likelihood interval at `level` of parameter j around the maximum (th, lmax); stops at
/// the first point higher than lmax (Interval::higher).
Interval profile_interval(const Objective& f, const Box& box, const Theta& th, double lmax, std::size_t j,
                          double level, const StandardErrors& ses);

/// The global search over parameter j (tau), the others re-maximised at each value (the profile
/// l_p): a coarse grid over j's range; a fine grid in every coarse interval with an end within
/// `near` of the best coarse value (and both beside the best); then every local maximum of the
/// grid within `refine_within` of the best (at most `max_refined`) refined by Brent's method
/// between its neighbours. At the `anchors` values of j, coordinate k is also restarted from each
/// of `restarts` (the profile over k need not be unimodal).
struct ScanPlan {
  std::size_t j = kTau;
  double coarse = 0.05, fine = 0.01;
  double near = 3, refine_within = 1;
  int max_refined = 3;
  std::size_t k = kBeta;
  std::vector<double> restarts, anchors;
  Theta h{};  // parabola steps of the re-maximised parameters
};

/// The best point the scan found, and its value; `starts` (e.g. a pooled fit's participants'
/// mean) are profile points added to the grid.
std::pair<Theta, double> scan_maximum(const Objective& f, const Box& box, const Theta& base, const ScanPlan& plan,
                                      const std::vector<Theta>& starts);

/// The observer fits' box: beta in [0, beta_max] (scale 1), tau in [0, tau_max] (scale 0.25 s),
/// the prior's logit in [-8, 8] (scale 0.5; free when fit_prior), gamma in [-1, 1] (scale 0.05;
/// free when `gamma`).
Box observer_box(const ObserverFitSettings& s, bool gamma);

/// The observer fits' scan (docs/observer.md, "Estimation and CIs"): tau on a coarse grid of
/// 0.05 s, finer (0.01 s) near its best; beta restarted from 0.1-10 at tau 0, 0.25, 0.6 and 1.2 s;
/// parabola steps a hundredth (beta, tau) or a twentieth (prior, gamma) of the box's scales.
ScanPlan observer_scan_plan(const Box& box);

/// The CIs at a maximum of every free parameter, or only of `ci_only` (the others get NaN ends);
/// or the first point higher than the maximum that a profile met.
struct Intervals {
  std::array<Interval, kParams> ci;
  std::optional<std::pair<Theta, double>> higher;
};

/// The maximum and the CIs there: when a profile meets a point higher than the maximum, the fit
/// climbs from that point (Nelder-Mead, a small simplex) and the CIs are searched again (at most
/// 20 times; if it still has not settled, the best point known with void (NaN) CIs).
std::pair<std::pair<Theta, double>, Intervals> settle(const Objective& f, const Box& box,
                                                      std::pair<Theta, double> top, double level,
                                                      std::size_t ci_only);

/// The learning test in a pooled fit, beta_k = beta0 exp(gamma exposure_k) against gamma = 0
/// (docs/observer.md, "Learning"): `f` scales each trial's beta by exp(th[kGamma] exposure_k) and
/// `box` frees gamma. The maximum starts at `base` (the pooled fit, gamma = 0), Nelder-Mead
/// restarted until it stops improving (beta0 and gamma are strongly correlated); gamma gets its
/// profile CI at `level`; the likelihood ratio against `pooled` (its unit names the condition) is
/// referred to chi-squared with 1 df. Shared by the pad's fit and the pointer's.
LearningTest learning_test(const Objective& f, const Box& box, const Theta& base, const ObserverFit& pooled,
                           double level);

/// 1 / (1 + e^-z) without overflow (the prior's logit back to a probability).
double logistic(double z) noexcept;

/// How a fit's notes name what follows the robot's path (the pad, the pointer).
struct FitWording {
  const char* at_once;  // beta at its upper bound: what the data do
  const char* ignores;  // beta at 0
};

/// The fit's estimates of the box's free parameters at th with their CIs (the prior's on the
/// probability scale), a note for each profile that was not unimodal, and the notes on beta and
/// tau at a bound of [0, beta_max] x [0, tau_max]. `fit.unit` names the fit in the notes.
void describe_estimates(ObserverFit& fit, const Box& box, const Theta& th, const Intervals& cis,
                        double beta_max, double tau_max, const FitWording& wording);

}  // namespace feint::models::detail::observer

// feint/models/goal_posterior.hpp - the goal-inference observer over K >= 2 goals: what a rational
// onlooker believes about which target the robot heads for (docs/deceptive-paths.md).
//
// For targets G_0 .. G_{K-1}, start S and the path xi seen up to the point Q (Dragan & Srinivasa
// 2013, eq. 5; Baker, Saxe & Tenenbaum 2009):
//
//     P(G_k | xi_{S->Q})  ∝  P(G_k) exp(-beta (C(xi_{S->Q}) + V_k(Q) - V_k(S)))
//
// with V_k(X) = |X - G_k| the straight-line cost to go. The path cost C is the same for every goal
// and cancels in the normalisation, so the posterior depends on the position Q alone:
//
//     ln P(G_k | Q) = a_k - logsumexp_j a_j,     a_k = ln P(G_k) - beta (V_k(Q) - V_k(S)).
//
// It is computed with the largest a_k subtracted first (log-sum-exp), so it neither overflows nor
// divides 0 by 0 for any beta. At K = 2 it is goal_inference.hpp's belief_right (target 1 = right).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "feint/metrics/layout.hpp"
#include "feint/models/goal_inference.hpp"

namespace feint::models {

/// The K-goal observer's parameters.
struct GoalPosteriorObserver {
  double beta = 1.0;          // rationality (1/m), >= 0
  double tau = 0.0;           // response delay (s), >= 0 (used by posterior_trace only)
  std::vector<double> prior;  // P(G_k) before any motion; empty = uniform 1/K
};

/// Throws UsageError naming the parameter when beta or tau is negative or not finite, or the prior
/// (when given) does not have K entries, has an entry that is not in (0, 1], or does not sum to 1
/// within 1e-9.
void validate(const GoalPosteriorObserver& o, std::size_t k);

/// Throws UsageError when the layout has fewer than 2 targets or a coordinate that is not finite.
/// (Spacing rules are metrics::validate's; the observer needs none.)
void validate_goals(const metrics::Layout& layout);

/// The observer's prior as K numbers: `o.prior`, or 1/K each when it is empty.
std::vector<double> resolved_prior(const GoalPosteriorObserver& o, std::size_t k);

/// ln P(G_k | the robot went from `start` to `q`), k = 0 .. K-1 (K = targets.size() >= 1). `prior`
/// empty means uniform. Unchecked (callers validate): a goal whose probability underflows gets a
/// large negative log, never NaN, for any finite beta >= 0.
std::vector<double> goal_log_posterior(Position start, Position q,
                                       std::span<const metrics::MapPoint> targets, double beta,
                                       std::span<const double> prior = {});

/// P(G_k | start -> q): exp of goal_log_posterior (sums to 1 within rounding).
std::vector<double> goal_posterior(Position start, Position q,
                                   std::span<const metrics::MapPoint> targets, double beta,
                                   std::span<const double> prior = {});

/// P(G_k | layout.start -> q) with the observer's beta and prior; validates both.
std::vector<double> goal_posterior(const metrics::Layout& layout, Position q,
                                   const GoalPosteriorObserver& o);

/// The posterior trace: at each of `times`, P(G_k | path seen up to t - tau), the start S being
/// path.front() (as belief_trace); before the robot starts it is the prior. Row i holds the K
/// probabilities at times[i]. Validates the observer and the layout's targets; `path` must not be
/// empty.
std::vector<std::vector<double>> posterior_trace(std::span<const PathSample> path,
                                                 std::span<const double> times,
                                                 const metrics::Layout& layout,
                                                 const GoalPosteriorObserver& o);

/// Shannon entropy of a distribution in bits, -sum p_k log2 p_k (0 log 0 = 0): 0 when one goal is
/// certain, log2 K when the posterior is flat.
double entropy_bits(std::span<const double> p) noexcept;

}  // namespace feint::models

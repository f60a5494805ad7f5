// feint/models/goal_inference.hpp - the goal-inference observer: what a rational onlooker believes
// about the robot's goal from the path it has seen (docs/observer.md).
//
// For goals G in {left, right}, start S and the path xi seen up to the point Q (Dragan & Srinivasa
// 2013, "Generating Legible Motion", eq. 5; Baker, Saxe & Tenenbaum 2009):
//
//     P(G | xi_{S->Q})  ∝  P(G) exp(-beta (C(xi_{S->Q}) + V_G(Q) - V_G(S)))
//
// with C the path length and V_G(X) = |X - G| the straight-line cost to go. C(xi) is the same for
// both goals, so it cancels when the two are normalised; with two goals the posterior is a logistic
// function of the position alone:
//
//     logit P(right | xi) = logit P(right) - beta [(V_R(Q) - V_R(S)) - (V_L(Q) - V_L(S))]
//
// beta (1/m) is the observer's rationality: 0 ignores the path (belief = prior), large beta
// commits as soon as the robot's progress favours one goal. A response delay tau (s) shifts the
// belief in time: b(t) = P(right | path seen up to t - tau); before the robot starts, b = prior.
#pragma once

#include <span>
#include <vector>

namespace feint::models {

/// A point in the study's 2-D world (metres).
struct Position {
  double x = 0;
  double y = 0;
};

/// One sample of the robot's path: time since the trial's start (s) and position (m).
struct PathSample {
  double t = 0;
  double x = 0;
  double y = 0;
};

/// The two goals: left (pad 0) and right (pad 1).
struct Goals {
  Position left{-2.0, 4.0};
  Position right{2.0, 4.0};
};

/// The observer's parameters.
struct GoalObserver {
  double beta = 1.0;         // rationality (1/m), >= 0
  double tau = 0.0;          // response delay (s), >= 0
  double prior_right = 0.5;  // P(right) before any motion, in (0, 1)
};

/// Throws UsageError naming the parameter when beta < 0, tau < 0, prior outside (0, 1), or any
/// value is not finite.
void validate(const GoalObserver& o);

/// P(right | the robot went from `start` to `q`): the closed form above, evaluated in log-odds so
/// that it neither overflows nor loses the tail (it returns values within 1e-300 of 0 or 1 exactly).
double belief_right(Position start, Position q, const Goals& goals, double beta,
                    double prior_right) noexcept;

/// The log-odds form of belief_right (unbounded; what a likelihood should use).
double belief_logit(Position start, Position q, const Goals& goals, double beta,
                    double prior_right) noexcept;

/// The robot's position at time t on a path sampled at increasing times: linear between samples,
/// path.front() before the first sample, path.back() after the last. `path` must not be empty.
Position position_at(std::span<const PathSample> path, double t) noexcept;

/// The belief trace b(t_i) = P(right | path seen up to t_i - tau) at each of `times`; the start S is
/// path.front(). `path` must not be empty.
std::vector<double> belief_trace(std::span<const PathSample> path, std::span<const double> times,
                                 const Goals& goals, const GoalObserver& observer);

}  // namespace feint::models

// Pointer traces drawn from the K-goal observer model of feint/models/pointer_observer_fit.hpp, for
// the recovery test (test_pointer_observer_recovery.cpp) and bench/bench_observer_fit.cpp
// (BM_PointerCoverage). Each trial: a layout (metrics::draw_layout in the default region, or
// sim::row_layout), a true target drawn uniformly, the robot's path for one of the paper's
// strategies (sim::k_goal_trajectory, 1 m/s, 25 Hz), the pointer at 25 Hz from the robot's start
// to 0.5 s after it stops: the posterior mean (models::posterior_trace, not the fit's code) plus
// s * e, e AR(1) on each axis with phi and innovation sd sigma (layout scales), stationary start.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "feint/metrics/layout.hpp"
#include "feint/models/goal_posterior.hpp"
#include "feint/models/pointer_observer_fit.hpp"
#include "feint/rng.hpp"
#include "feint/sim/k_goal_paths.hpp"
#include "feint/sim/pointer_participant.hpp"

namespace feint::testpointer {

struct Truth {
  double beta = 1.5;   // 1/m
  double tau = 0.4;    // s
  double phi = 0.9;
  double sigma = 0.02; // layout scales
};

/// One simulated participant's `trials` trials on maps of `k` targets: layouts drawn per round
/// (`random_layout`) or the row of sim::row_layout; strategies in turn (exaggerating, switching,
/// ambiguous, optimal), the deceptive ones' variant alternating main and v2.
inline std::vector<models::PointerObservedTrial> simulate_pointer_participant(const Truth& truth, int trials,
                                                                             std::size_t k, bool random_layout,
                                                                             Rng& rng, const std::string& id = "P1") {
  const sim::Geometry g;
  sim::KGoalPathSettings ks;
  ks.geometry = g;
  std::vector<models::PointerObservedTrial> out;
  for (int j = 0; j < trials; ++j) {
    models::PointerObservedTrial tr;
    tr.participant = id;
    tr.condition = "sim";
    tr.iteration = j + 1;
    tr.layout = random_layout ? metrics::draw_layout(rng, metrics::LayoutRegion{}, k) : sim::row_layout(k, g);
    tr.target = rng.bounded(static_cast<std::uint32_t>(k));
    const auto strategy = static_cast<sim::Strategy>(j % 4);
    const auto variant = strategy != sim::Strategy::optimal && (j / 4) % 2 == 1 ? sim::Variant::v2 : sim::Variant::main;
    for (const auto& p : sim::k_goal_trajectory(tr.layout, tr.target, strategy, variant, ks))
      tr.path.push_back({p.t, p.x, p.y});
    const double end = tr.path.back().t + 0.5;
    for (long i = 0;; ++i) {
      const double t = static_cast<double>(i) / g.sample_rate;
      if (t > end) break;
      tr.times.push_back(t);
    }
    const auto post = models::posterior_trace(tr.path, tr.times, tr.layout,
                                              models::GoalPosteriorObserver{truth.beta, truth.tau, {}});
    const double s = metrics::layout_scale(tr.layout);
    const double sd0 = truth.sigma / std::sqrt(1 - truth.phi * truth.phi);
    double ex = sd0 * rng.normal(), ey = sd0 * rng.normal();
    for (std::size_t i = 0; i < post.size(); ++i) {
      if (i > 0) {
        ex = truth.phi * ex + truth.sigma * rng.normal();
        ey = truth.phi * ey + truth.sigma * rng.normal();
      }
      double x = 0, y = 0;
      for (std::size_t q = 0; q < k; ++q) {
        x += post[i][q] * tr.layout.targets[q].x;
        y += post[i][q] * tr.layout.targets[q].y;
      }
      tr.x.push_back(x + s * ex);
      tr.y.push_back(y + s * ey);
    }
    out.push_back(std::move(tr));
  }
  return out;
}

/// Share of simulated participants whose 95 % profile CIs cover the truth (counts of `n`).
struct Coverage {
  int beta = 0, tau = 0, both = 0, n = 0;
};

/// `studies` participants of `trials` trials each, K = 3: even studies on random layouts, odd ones
/// on the row; participant k uses Rng::stream(seed, k).
inline Coverage pointer_coverage(int studies, int trials, std::uint64_t seed, const Truth& truth = {}) {
  const models::ObserverFitSettings s;
  Coverage c;
  for (int k = 0; k < studies; ++k) {
    Rng rng = Rng::stream(seed, static_cast<std::uint64_t>(k));
    const auto trs = simulate_pointer_participant(truth, trials, 3, k % 2 == 0, rng);
    const auto fit = models::fit_pointer_observer(trs, s, "P1");
    const auto& b = fit.parameter("beta");
    const auto& t = fit.parameter("tau");
    const bool cb = b.conf_low <= truth.beta && truth.beta <= b.conf_high;
    const bool ct = t.conf_low <= truth.tau && truth.tau <= t.conf_high;
    c.beta += cb;
    c.tau += ct;
    c.both += cb && ct;
    ++c.n;
  }
  return c;
}

}  // namespace feint::testpointer

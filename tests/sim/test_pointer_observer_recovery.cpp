// Parameter recovery of the K-goal observer fitted to pointer traces
// (feint/models/pointer_observer_fit.hpp): participants drawn from the model on maps of 3 targets
// (random layouts and the row), robot paths from sim::k_goal_paths. docs/observer.md reports the
// full bench run (bench/bench_observer_fit.cpp, BM_PointerCoverage).
#include <cstdio>

#include <gtest/gtest.h>

#include "pointer_observer_sim.hpp"

namespace tq = feint::testpointer;

TEST(PointerObserverRecovery, RecoversBetaTauPhiAndSigmaOfOneParticipant) {
  feint::Rng rng(7);
  const tq::Truth truth{2.0, 0.3, 0.9, 0.02};
  const auto trs = tq::simulate_pointer_participant(truth, 20, 3, true, rng);
  const auto fit = feint::models::fit_pointer_observer(trs, {}, "P1");
  const auto& b = fit.parameter("beta");
  const auto& t = fit.parameter("tau");
  EXPECT_NEAR(b.estimate, 2.0, 0.2);
  EXPECT_NEAR(t.estimate, 0.3, 0.05);
  EXPECT_LT(b.conf_low, b.estimate);
  EXPECT_GT(b.conf_high, b.estimate);
  EXPECT_LT(t.conf_low, t.estimate);
  EXPECT_GT(t.conf_high, t.estimate);
  EXPECT_NEAR(fit.phi, 0.9, 0.02);
  EXPECT_NEAR(fit.sigma, 0.02, 0.001);
}

// 100 simulated participants (8 trials each, K = 3); the 95 % profile CIs must cover the truth in
// 88-99 of them (with a true 95 %, 99 % of runs land in that band).
TEST(PointerObserverRecovery, ProfileCiCoverageOver100SimulatedStudies) {
  const auto c = tq::pointer_coverage(100, 8, 2026);
  EXPECT_GE(c.beta, 88);
  EXPECT_LE(c.beta, 99);
  EXPECT_GE(c.tau, 88);
  EXPECT_LE(c.tau, 99);
  std::printf("pointer coverage over %d studies: beta %d%%, tau %d%%, both %d%%\n", c.n, c.beta, c.tau, c.both);
}

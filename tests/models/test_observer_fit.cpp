// Fitting the goal-inference observer to pad traces (feint/models/observer_fit.hpp): parameter
// recovery and CI coverage, the likelihood's closed forms, bad input, learning and agreement.
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include <gtest/gtest.h>

#include "feint/error.hpp"
#include "feint/models/observer_fit.hpp"
#include "observer_test_paths.hpp"

using namespace feint::models;
using feint::Rng;
namespace tp = feint::testpaths;

namespace {

/// Share of `studies` simulated participants (known beta, tau) whose 95% profile CIs cover the truth.
struct Coverage {
  int beta = 0, tau = 0, both = 0, n = 0;
};

Coverage coverage(int studies, int trials, std::uint64_t seed) {
  const GoalObserver truth{1.5, 0.4, 0.5};
  ObserverFitSettings s;
  Coverage c;
  for (int k = 0; k < studies; ++k) {
    Rng rng = Rng::stream(seed, static_cast<std::uint64_t>(k));
    const auto trs = tp::simulate_participant(truth, trials, 0.9, 0.02, rng);
    const auto fit = fit_observer(trs, s, "P1");
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

}  // namespace

TEST(ObserverFit, RecoversBetaAndTauOfOneParticipant) {
  Rng rng(7);
  const GoalObserver truth{2.0, 0.3, 0.5};
  const auto trs = tp::simulate_participant(truth, 20, 0.9, 0.02, rng);
  const auto fit = fit_observer(trs, ObserverFitSettings{}, "P1");
  const auto& b = fit.parameter("beta");
  const auto& t = fit.parameter("tau");
  EXPECT_NEAR(b.estimate, 2.0, 0.15);
  EXPECT_NEAR(t.estimate, 0.3, 0.03);
  EXPECT_LT(b.conf_low, b.estimate);
  EXPECT_GT(b.conf_high, b.estimate);
  EXPECT_LT(t.conf_low, t.estimate);
  EXPECT_GT(t.conf_high, t.estimate);
  EXPECT_NEAR(fit.phi, 0.9, 0.03);
  EXPECT_NEAR(fit.sigma, 0.02, 0.002);
  // The profile at each CI end is l_max - chi2_1(0.95)/2 (re-maximised over the other parameter).
  const double q = 3.841458820694124;
  for (double v : {b.conf_low, b.conf_high}) {
    double best = -1e300;
    for (int i = 0; i <= 2000; ++i) {
      const double tau = 0.2 + 0.2 * i / 2000.0;
      best = std::max(best, observer_log_likelihood(trs, ObserverFitSettings{}, {v, tau, 0.5}));
    }
    EXPECT_NEAR(fit.log_likelihood - best, q / 2, 0.01) << v;
  }
}

TEST(ObserverFit, LogLikelihoodIsTheConcentratedAr1Gaussian) {
  // Two trials; the closed form -m/2 (log(2 pi sigma^2) + 1) with phi = Sxy/Sxx, by hand.
  Rng rng(3);
  const GoalObserver obs{1.0, 0.2, 0.5};
  const auto trs = tp::simulate_participant(obs, 2, 0.5, 0.05, rng);
  const GoalObserver at{1.3, 0.1, 0.5};
  double sxx = 0, sxy = 0, syy = 0, m = 0;
  for (const auto& tr : trs) {
    const auto b = belief_trace(tr.path, tr.times, Goals{}, at);
    for (std::size_t i = 1; i < b.size(); ++i) {
      const double r0 = tr.pads[i - 1] - b[i - 1], r1 = tr.pads[i] - b[i];
      sxx += r0 * r0; sxy += r0 * r1; syy += r1 * r1; m += 1;
    }
  }
  const double var = (syy - sxy * sxy / sxx) / m;
  const double expected = -m / 2 * (std::log(2 * std::numbers::pi * var) + 1);
  EXPECT_NEAR(observer_log_likelihood(trs, ObserverFitSettings{}, at), expected, 1e-9 * std::abs(expected));
  ObserverFitSettings ind;
  ind.noise = PadNoise::independent;
  double rss = 0, n = 0;
  for (const auto& tr : trs) {
    const auto b = belief_trace(tr.path, tr.times, Goals{}, at);
    for (std::size_t i = 0; i < b.size(); ++i) { rss += (tr.pads[i] - b[i]) * (tr.pads[i] - b[i]); n += 1; }
  }
  const double e2 = -n / 2 * (std::log(2 * std::numbers::pi * rss / n) + 1);
  EXPECT_NEAR(observer_log_likelihood(trs, ind, at), e2, 1e-9 * std::abs(e2));
}

// Parameter recovery: 100 simulated participants (10 trials each) with known beta and tau; the 95%
// profile CIs must cover the truth 90-98% of the time (docs/observer.md reports the full bench run).
TEST(ObserverFit, ProfileCiCoverageOver100SimulatedStudies) {
  const auto c = coverage(100, 10, 2026);
  EXPECT_GE(c.beta, 90);
  EXPECT_LE(c.beta, 98);
  EXPECT_GE(c.tau, 90);
  EXPECT_LE(c.tau, 98);
  std::printf("coverage over %d studies: beta %d%%, tau %d%%, both %d%%\n", c.n, c.beta, c.tau, c.both);
}

TEST(ObserverFit, RecoversAFittedPrior) {
  Rng rng(17);
  const GoalObserver truth{1.5, 0.3, 0.3};
  const auto trs = tp::simulate_participant(truth, 20, 0.9, 0.02, rng);
  ObserverFitSettings s;
  s.fit_prior = true;
  const auto fit = fit_observer(trs, s, "P1");
  const auto& p = fit.parameter("prior_right");
  EXPECT_NEAR(p.estimate, 0.3, 0.03);
  EXPECT_LT(p.conf_low, 0.3);
  EXPECT_GT(p.conf_high, 0.3);
  EXPECT_NEAR(fit.parameter("beta").estimate, 1.5, 0.2);
  // Without the prior in the fit the list has beta and tau only.
  EXPECT_EQ(fit_observer(trs, ObserverFitSettings{}, "P1").parameters.size(), 2u);
}

TEST(ObserverFit, AFixedPriorIsTheOneUsedAndReported) {
  Rng rng(23);
  const GoalObserver truth{1.5, 0.3, 0.3};
  const auto trs = tp::simulate_participant(truth, 12, 0.9, 0.02, rng);
  ObserverFitSettings s;
  s.prior_right = 0.3;  // known, not fitted
  const auto fit = fit_observer(trs, s, "P1");
  EXPECT_EQ(fit.observer().prior_right, 0.3);
  EXPECT_NEAR(fit.parameter("beta").estimate, 1.5, 0.2);
  EXPECT_NEAR(fit.log_likelihood, observer_log_likelihood(trs, s, fit.observer()), 1e-9);
}

// A start (what fit_study gives a pooled fit: its participants' mean) changes only how Nelder-Mead
// gets to the maximum: near or far, the estimates agree within its tolerance (1e-4 of each scale)
// and the CIs within the profile search's; an invalid start is refused by name.
TEST(ObserverFit, AStartLeadsToTheSameMaximum) {
  Rng rng(31);
  const GoalObserver truth{1.5, 0.4, 0.5};
  const auto trs = tp::simulate_participant(truth, 12, 0.9, 0.02, rng);
  const ObserverFitSettings s;
  const auto plain = fit_observer(trs, s, "P1");
  for (const GoalObserver start : {GoalObserver{1.45, 0.42, 0.5}, GoalObserver{8.0, 1.5, 0.5}}) {
    const auto fit = fit_observer(trs, s, "P1", start);
    for (const char* name : {"beta", "tau"}) {
      const auto& a = plain.parameter(name);
      const auto& b = fit.parameter(name);
      EXPECT_NEAR(b.estimate, a.estimate, 2e-4) << name;
      EXPECT_NEAR(b.conf_low, a.conf_low, 2e-3) << name;
      EXPECT_NEAR(b.conf_high, a.conf_high, 2e-3) << name;
    }
    EXPECT_NEAR(fit.log_likelihood, plain.log_likelihood, 1e-4);
    EXPECT_GE(fit.log_likelihood, observer_log_likelihood(trs, s, start));
  }
  EXPECT_THROW(fit_observer(trs, s, "P1", GoalObserver{-1.0, 0.4, 0.5}), feint::UsageError);
}

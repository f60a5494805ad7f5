// Fitting the K-goal observer to pointer traces (feint/models/pointer_observer_fit.hpp): the worked
// example of docs/observer.md by hand, the mean against the posterior (goal_posterior.hpp) and at
// K = 2 against the pad's b(t), the likelihood's closed form, invariance under scaling the map, and
// bad input. Recovery and CI coverage: tests/sim/test_pointer_observer_recovery.cpp (it needs
// sim::k_goal_paths).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "feint/error.hpp"
#include "feint/models/goal_posterior.hpp"
#include "feint/models/observer_fit.hpp"
#include "feint/models/pointer_observer_fit.hpp"
#include "observer_test_paths.hpp"

using namespace feint::models;
using feint::Rng;
using feint::metrics::Layout;
using feint::metrics::MapPoint;
namespace tp = feint::testpaths;

namespace {

/// docs/observer.md, "Fitting the observer to pointer traces", worked example: start (0, 0),
/// targets (-3, 4), (0, 4), (0, 8) (scale 5 m), the robot from (0, 0) at t = 0 to (3, 4) at t = 5,
/// the pointer at t = 0, 6, 11 equal to the mean plus 5 e_i, e = (0.1, -0.2), (0.2, 0.1), (0.1, 0.2).
PointerObservedTrial worked_trial() {
  PointerObservedTrial tr;
  tr.participant = "P1";
  tr.layout = Layout{{0, 0}, {{-3, 4}, {0, 4}, {0, 8}}};
  tr.target = 1;
  tr.path = {{0, 0, 0}, {5, 3, 4}};
  tr.times = {0, 6, 11};
  // Means by hand (beta = ln 2, tau = 1 s): m(0) = the centroid (-1, 16/3); at t = 6 and 11 the
  // robot (seen 1 s late) is at (3, 4), where V_k(Q) - V_k(S) = 6 - 5, 3 - 4, 5 - 8 = 1, -1, -3,
  // so the weights are 2^-1 : 2^1 : 2^3 = 1/21, 4/21, 16/21 and m = (-1/7, 148/21).
  tr.x = {-1 + 0.5, -1.0 / 7 + 1.0, -1.0 / 7 + 0.5};
  tr.y = {16.0 / 3 - 1.0, 148.0 / 21 + 0.5, 148.0 / 21 + 1.0};
  return tr;
}

/// A random K-target trial: a polyline through random points to a target, pointer noise.
PointerObservedTrial random_trial(Rng& rng, std::size_t k, double scale = 1.0) {
  PointerObservedTrial tr;
  tr.participant = "P1";
  tr.layout = feint::metrics::draw_layout(rng, {}, k);
  tr.target = rng.bounded(static_cast<std::uint32_t>(k));
  const auto& g = tr.layout.targets[tr.target];
  tr.path = tp::polyline({{0, 0}, {4 * rng.uniform() - 2, 1 + 2 * rng.uniform()}, {g.x, g.y}});
  for (double t = 0; t < tr.path.back().t + 0.5; t += 0.04) {
    tr.times.push_back(t);
    tr.x.push_back(6 * rng.uniform() - 3);
    tr.y.push_back(2 + 3 * rng.uniform());
  }
  for (auto& p : tr.layout.targets) p = {p.x * scale, p.y * scale};
  for (auto& p : tr.path) p = {p.t, p.x * scale, p.y * scale};
  for (auto& v : tr.x) v *= scale;
  for (auto& v : tr.y) v *= scale;
  return tr;
}

/// The pointer drawn from the model: the posterior mean (posterior_trace) plus AR(1) errors of
/// innovation sd sigma (layout scales) on each axis, stationary start.
void model_pointer(PointerObservedTrial& tr, double beta, double tau, double phi, double sigma, Rng& rng) {
  const auto post = posterior_trace(tr.path, tr.times, tr.layout, GoalPosteriorObserver{beta, tau, {}});
  const double s = feint::metrics::layout_scale(tr.layout);
  double ex = rng.normal() * sigma / std::sqrt(1 - phi * phi), ey = rng.normal() * sigma / std::sqrt(1 - phi * phi);
  for (std::size_t i = 0; i < post.size(); ++i) {
    if (i > 0) {
      ex = phi * ex + sigma * rng.normal();
      ey = phi * ey + sigma * rng.normal();
    }
    double x = 0, y = 0;
    for (std::size_t k = 0; k < post[i].size(); ++k) {
      x += post[i][k] * tr.layout.targets[k].x;
      y += post[i][k] * tr.layout.targets[k].y;
    }
    tr.x[i] = x + s * ex;
    tr.y[i] = y + s * ey;
  }
}

}  // namespace

TEST(PointerObserverFit, WorkedExampleByHand) {
  const PointerObservedTrial tr = worked_trial();
  const double beta = std::numbers::ln2, tau = 1.0;
  const auto m = pointer_observer_means(tr, beta, tau);
  ASSERT_EQ(m.size(), 3u);
  EXPECT_NEAR(m[0].x, -1.0, 1e-12);
  EXPECT_NEAR(m[0].y, 16.0 / 3, 1e-12);
  for (int i : {1, 2}) {
    EXPECT_NEAR(m[i].x, -1.0 / 7, 1e-12);
    EXPECT_NEAR(m[i].y, 148.0 / 21, 1e-12);
  }
  // AR(1): residual pairs x (0.1, 0.2), (0.2, 0.1); y (-0.2, 0.1), (0.1, 0.2). S_xx = 0.10,
  // S_xy = 0.04, S_yy = 0.10, m = 4: phi = 0.4, sigma^2 = (0.10 - 0.016) / 4 = 0.021,
  // l = -2 (ln(2 pi 0.021) + 1) = 2.0507115...
  const std::vector<PointerObservedTrial> one{tr};
  EXPECT_NEAR(pointer_observer_log_likelihood(one, ObserverFitSettings{}, beta, tau),
              -2 * (std::log(2 * std::numbers::pi * 0.021) + 1), 1e-12);
  EXPECT_NEAR(-2 * (std::log(2 * std::numbers::pi * 0.021) + 1), 2.0507115, 1e-7);
  // Independent errors: the 6 residuals' squares sum to 0.15: sigma^2 = 0.025, l = -3 (ln(2 pi
  // 0.025) + 1).
  ObserverFitSettings ind;
  ind.noise = PadNoise::independent;
  EXPECT_NEAR(pointer_observer_log_likelihood(one, ind, beta, tau),
              -3 * (std::log(2 * std::numbers::pi * 0.025) + 1), 1e-12);
}

// The mean is sum_k P(G_k | path seen tau ago) G_k with the posterior of goal_posterior.hpp
// (posterior_trace: another implementation), on random K = 4 layouts.
TEST(PointerObserverFit, MeanIsThePosteriorMeanOfTheTargets) {
  Rng rng(11);
  for (int rep = 0; rep < 20; ++rep) {
    const auto tr = random_trial(rng, 4);
    const double beta = 0.1 + 4 * rng.uniform(), tau = 0.8 * rng.uniform();
    const auto m = pointer_observer_means(tr, beta, tau);
    const auto post = posterior_trace(tr.path, tr.times, tr.layout, GoalPosteriorObserver{beta, tau, {}});
    ASSERT_EQ(m.size(), post.size());
    for (std::size_t i = 0; i < m.size(); ++i) {
      double x = 0, y = 0;
      for (std::size_t k = 0; k < 4; ++k) {
        x += post[i][k] * tr.layout.targets[k].x;
        y += post[i][k] * tr.layout.targets[k].y;
      }
      EXPECT_NEAR(m[i].x, x, 1e-12);
      EXPECT_NEAR(m[i].y, y, 1e-12);
    }
  }
}

// At K = 2 on the paper's layout the mean is the pad fit's b(t) mapped to the line between the
// targets: m = G_0 + b (G_1 - G_0). With the pad trace projected onto that line the x residuals are
// the pad's, the y residuals 0, so l_pointer = 2 l_pad + m ln 2 (m = the pad's pairs) and the fits
// agree on beta and tau.
TEST(PointerObserverFit, AtTwoTargetsTheMeanIsThePadsBeliefOnTheLine) {
  Rng rng(5);
  const GoalObserver truth{1.7, 0.3, 0.5};
  const auto pads = tp::simulate_participant(truth, 6, 0.9, 0.02, rng);
  const Layout paper = feint::metrics::paper_layout();
  std::vector<PointerObservedTrial> pointers;
  for (const auto& pt : pads) {
    PointerObservedTrial tr;
    tr.participant = pt.participant;
    tr.condition = pt.condition;
    tr.iteration = pt.iteration;
    tr.layout = paper;
    tr.target = pt.goal == GoalSide::right ? 1 : 0;
    tr.path = pt.path;
    tr.times = pt.times;
    for (double mu : pt.pads) {
      tr.x.push_back(-2 + 4 * mu);
      tr.y.push_back(4);
    }
    for (const GoalObserver at : {GoalObserver{1.7, 0.3, 0.5}, GoalObserver{0.4, 0.05, 0.5}, GoalObserver{9, 1.1, 0.5}}) {
      const auto m = pointer_observer_means(tr, at.beta, at.tau);
      const auto b = belief_trace(pt.path, pt.times, Goals{}, at);
      for (std::size_t i = 0; i < b.size(); ++i) {
        EXPECT_NEAR(m[i].x, -2 + 4 * b[i], 1e-12);
        EXPECT_NEAR(m[i].y, 4, 1e-12);
      }
    }
    pointers.push_back(std::move(tr));
  }
  double pairs = 0;
  for (const auto& pt : pads) pairs += static_cast<double>(pt.times.size() - 1);
  const ObserverFitSettings s;
  for (const GoalObserver at : {GoalObserver{1.7, 0.3, 0.5}, GoalObserver{0.8, 0.6, 0.5}}) {
    const double lp = observer_log_likelihood(pads, s, at);
    EXPECT_NEAR(pointer_observer_log_likelihood(pointers, s, at.beta, at.tau), 2 * lp + pairs * std::numbers::ln2,
                1e-9 * std::abs(lp));
  }
  const auto pad_fit = fit_observer(pads, s, "P1");
  const auto ptr_fit = fit_pointer_observer(pointers, s, "P1");
  for (const char* name : {"beta", "tau"})
    EXPECT_NEAR(ptr_fit.parameter(name).estimate, pad_fit.parameter(name).estimate, 2e-3) << name;
  EXPECT_NEAR(ptr_fit.phi, pad_fit.phi, 1e-3);
  EXPECT_TRUE(std::isnan(ptr_fit.prior_right));
}

// The likelihood's closed form, computed here from posterior_trace on random K = 3 trials.
TEST(PointerObserverFit, LogLikelihoodIsTheConcentratedAr1GaussianOnBothAxes) {
  Rng rng(3);
  std::vector<PointerObservedTrial> trs{random_trial(rng, 3), random_trial(rng, 3)};
  const double beta = 1.3, tau = 0.25;
  double sxx = 0, sxy = 0, syy = 0, m = 0;
  for (const auto& tr : trs) {
    const auto post = posterior_trace(tr.path, tr.times, tr.layout, GoalPosteriorObserver{beta, tau, {}});
    const double s = feint::metrics::layout_scale(tr.layout);
    std::vector<double> rx, ry;
    for (std::size_t i = 0; i < post.size(); ++i) {
      double x = 0, y = 0;
      for (std::size_t k = 0; k < 3; ++k) {
        x += post[i][k] * tr.layout.targets[k].x;
        y += post[i][k] * tr.layout.targets[k].y;
      }
      rx.push_back((tr.x[i] - x) / s);
      ry.push_back((tr.y[i] - y) / s);
    }
    for (const auto* r : {&rx, &ry}) {
      for (std::size_t i = 1; i < r->size(); ++i) {
        sxx += (*r)[i - 1] * (*r)[i - 1];
        sxy += (*r)[i - 1] * (*r)[i];
        syy += (*r)[i] * (*r)[i];
        m += 1;
      }
    }
  }
  const double var = (syy - sxy * sxy / sxx) / m;
  const double expected = -m / 2 * (std::log(2 * std::numbers::pi * var) + 1);
  EXPECT_NEAR(pointer_observer_log_likelihood(trs, ObserverFitSettings{}, beta, tau), expected,
              1e-10 * std::abs(expected));
}

// sigma is in layout scales: the same study drawn 3 times larger (layout, path and pointer) has the
// same likelihood at beta / 3, and its fit the same tau, sigma and phi and a third of the beta.
TEST(PointerObserverFit, ScalingTheMapScalesBetaOnly) {
  Rng a(8), b(8);
  std::vector<PointerObservedTrial> small, large;
  Rng noise_a(9), noise_b(9);
  for (int i = 0; i < 4; ++i) {
    small.push_back(random_trial(a, 3));
    large.push_back(random_trial(b, 3, 3.0));
    model_pointer(small.back(), 1.5, 0.3, 0.9, 0.02, noise_a);
    model_pointer(large.back(), 0.5, 0.3, 0.9, 0.02, noise_b);
  }
  const ObserverFitSettings s;
  EXPECT_NEAR(pointer_observer_log_likelihood(large, s, 0.5, 0.2), pointer_observer_log_likelihood(small, s, 1.5, 0.2),
              1e-9);
  const auto fs = fit_pointer_observer(small, s, "small");
  const auto fl = fit_pointer_observer(large, s, "large");
  EXPECT_NEAR(fl.parameter("beta").estimate, fs.parameter("beta").estimate / 3, 2e-3);
  EXPECT_NEAR(fl.parameter("tau").estimate, fs.parameter("tau").estimate, 2e-3);
  EXPECT_NEAR(fl.sigma, fs.sigma, 1e-6);
  EXPECT_NEAR(fl.log_likelihood, fs.log_likelihood, 1e-4);
}

TEST(PointerObserverFit, BadInputIsNamed) {
  const ObserverFitSettings s;
  EXPECT_THROW(fit_pointer_observer({}, s, "P1"), feint::InvalidData);
  ObserverFitSettings prior = s;
  prior.fit_prior = true;
  const std::vector<PointerObservedTrial> one{worked_trial()};
  EXPECT_THROW(fit_pointer_observer(one, prior, "P1"), feint::UsageError);
  EXPECT_THROW(pointer_observer_means(worked_trial(), -1, 0), feint::UsageError);

  auto tr = worked_trial();
  EXPECT_EQ(pointer_trial_problem(tr), std::nullopt);
  tr.times.pop_back();
  tr.x.pop_back();
  tr.y.pop_back();
  EXPECT_NE(pointer_trial_problem(tr)->find("at least 3 are needed"), std::string::npos);
  tr = worked_trial();
  tr.target = 3;
  EXPECT_NE(pointer_trial_problem(tr)->find("true target 3 is not a target of the layout (K = 3)"), std::string::npos);
  tr = worked_trial();
  tr.x[1] = std::nan("");
  EXPECT_NE(pointer_trial_problem(tr)->find("pointer sample 2 is not finite"), std::string::npos);
  tr = worked_trial();
  tr.layout.targets[2] = tr.layout.targets[1];
  EXPECT_NE(pointer_trial_problem(tr)->find("same point"), std::string::npos) << *pointer_trial_problem(tr);
  tr = worked_trial();
  tr.path = {{0, 1, 1}, {1, 1, 1}};
  EXPECT_NE(pointer_trial_problem(tr)->find("never moves"), std::string::npos);

  // In a study, a bad trial is left out by name and the rest is fitted.
  Rng rng(2);
  std::vector<PointerObservedTrial> study;
  for (int i = 0; i < 4; ++i) {
    auto t = random_trial(rng, 3);
    model_pointer(t, 1.5, 0.3, 0.9, 0.02, rng);
    t.condition = "c";
    t.iteration = i + 1;
    study.push_back(std::move(t));
  }
  study[2].x.resize(2);
  const auto r = fit_pointer_study(study, s);
  EXPECT_EQ(r.trials_used, 3u);
  ASSERT_FALSE(r.issues.empty());
  EXPECT_EQ(r.issues.front().label, "P1/c/3");
  EXPECT_EQ(r.participants.size(), 1u);
  EXPECT_EQ(r.conditions.size(), 1u);
  EXPECT_EQ(r.min_targets, 3u);
  EXPECT_EQ(r.max_targets, 3u);
  EXPECT_EQ(r.layouts, 3u);
}

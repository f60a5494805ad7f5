// What the observer fits share beyond the optimisers (observer_optimise.hpp): the box and the
// scan's plan, the maximum settled with its profile CIs, the estimates with their notes, and the
// learning test. The
// pad fit (observer_fit.cpp) and the pointer fit (pointer_observer_fit.cpp) differ only in their
// likelihoods (docs/observer.md, "Estimation and CIs").
#include <algorithm>
#include <cmath>

#include <boost/math/distributions/chi_squared.hpp>
#include <fmt/format.h>

#include "observer_optimise.hpp"

namespace feint::models::detail::observer {

namespace {
constexpr double kGammaMax = 1.0;   // |gamma| per earlier trial of the strategy
constexpr double kLogitMax = 8.0;   // prior in [3.4e-4, 0.99966]
}  // namespace

Box observer_box(const ObserverFitSettings& s, bool gamma) {
  Box b;
  b.lo = {0.0, 0.0, -kLogitMax, -kGammaMax};
  b.hi = {s.beta_max, s.tau_max, kLogitMax, kGammaMax};
  b.scale = {1.0, 0.25, 0.5, 0.05};
  b.free = {true, true, s.fit_prior, gamma};
  return b;
}

ScanPlan observer_scan_plan(const Box& box) {
  ScanPlan plan;
  plan.restarts = {0.1, 0.3, 1.0, 3.0, 10.0};
  plan.anchors = {0.0, 0.25, 0.6, 1.2};
  plan.h = {0.01 * box.scale[kBeta], 0.01 * box.scale[kTau], 0.05 * box.scale[kPrior], 0.05 * box.scale[kGamma]};
  return plan;
}

namespace {

Intervals intervals_at(const Objective& f, const Box& box, const Theta& th, double lmax, double level,
                       std::size_t ci_only) {
  Intervals out;
  const auto ses = standard_errors(f, box, th, lmax);
  for (std::size_t j = 0; j < kParams; ++j) {
    out.ci[j] = Interval{std::nan(""), std::nan(""), false, false, false, std::nullopt};
    if (!box.free[j] || (ci_only != kParams && ci_only != j)) continue;
    out.ci[j] = profile_interval(f, box, th, lmax, j, level, ses);
    if (out.ci[j].higher) {
      out.higher = out.ci[j].higher;
      return out;
    }
  }
  return out;
}

/// Refits that a fit may need before its profiles meet no higher point (each raises the maximum by
/// more than kHigherTolerance; in practice one or two are ever needed).
constexpr int kMaxRefits = 20;

}  // namespace

std::pair<std::pair<Theta, double>, Intervals> settle(const Objective& f, const Box& box,
                                                      std::pair<Theta, double> top, double level,
                                                      std::size_t ci_only) {
  Intervals cis = intervals_at(f, box, top.first, top.second, level, ci_only);
  for (int round = 0; cis.higher && round < kMaxRefits; ++round) {
    top = nelder_mead(f, cis.higher->first, box, box.free, 0.05, 3000);
    cis = intervals_at(f, box, top.first, top.second, level, ci_only);
  }
  if (cis.higher) {  // not settled: the best point known, its CIs void (NaN)
    top = *cis.higher;
    for (auto& ci : cis.ci) ci = Interval{std::nan(""), std::nan(""), false, false, false, std::nullopt};
  }
  return {top, cis};
}

double logistic(double z) noexcept {
  if (z >= 0) return 1.0 / (1.0 + std::exp(-z));
  const double e = std::exp(z);
  return e / (1.0 + e);
}

namespace {

constexpr std::array<const char*, kParams> kNames = {"beta", "tau", "prior_right", "gamma"};

ParameterEstimate estimate_of(std::size_t j, const Theta& th, const Interval& ci) {
  ParameterEstimate e;
  e.name = kNames[j];
  e.estimate = th[j];
  e.conf_low = ci.low;
  e.conf_high = ci.high;
  e.low_at_bound = ci.low_at_bound;
  e.high_at_bound = ci.high_at_bound;
  if (j == kPrior) {
    e.estimate = logistic(th[j]);
    e.conf_low = logistic(ci.low);
    e.conf_high = logistic(ci.high);
  }
  return e;
}

/// The notes on estimates at a bound of their range.
void bound_notes(ObserverFit& fit, const Theta& th, double beta_max, double tau_max, const FitWording& w) {
  const double btol = 1e-3;
  if (th[kBeta] >= beta_max - btol) {
    fit.notes.push_back(fmt::format(
        "{}: beta is at the upper bound {} ({}); beta is not identified above it, and its CI is closed at the "
        "bound",
        fit.unit, beta_max, w.at_once));
  } else if (th[kBeta] <= btol) {
    fit.notes.push_back(fmt::format("{}: beta is at 0: {}; tau is then not identified", fit.unit, w.ignores));
  }
  if (th[kTau] >= tau_max - btol) {
    fit.notes.push_back(
        fmt::format("{}: tau is at the upper bound {} s; its CI is closed at the bound", fit.unit, tau_max));
  } else if (th[kTau] == 0) {
    fit.notes.push_back(fmt::format("{}: tau is at its lower bound 0 s (the likelihood falls as the delay "
                                    "grows); its CI is closed at the bound",
                                    fit.unit));
  }
}

}  // namespace

void describe_estimates(ObserverFit& fit, const Box& box, const Theta& th, const Intervals& cis,
                        double beta_max, double tau_max, const FitWording& wording) {
  for (std::size_t j = 0; j < kParams; ++j) {
    if (!box.free[j]) continue;  // a fixed prior is not a fitted parameter
    if (cis.ci[j].hull) {
      fit.notes.push_back(fmt::format(
          "{}: the profile likelihood of {} is not unimodal; its CI is the hull of the region within the "
          "cut-off",
          fit.unit, kNames[j]));
    }
    fit.parameters.push_back(estimate_of(j, th, cis.ci[j]));
  }
  bound_notes(fit, th, beta_max, tau_max, wording);
}


namespace {

/// The learning model starts from the pooled fit (gamma = 0), already near its maximum; beta0 and
/// gamma are strongly correlated, so Nelder-Mead is restarted until it stops improving.
std::pair<Theta, double> learning_max(const Objective& f, const Box& box, const Theta& base) {
  auto r = nelder_mead(f, base, box, box.free, 0.5, 3000);
  for (int restart = 0; restart < 5; ++restart) {
    auto r2 = nelder_mead(f, r.first, box, box.free, 0.2, 3000);
    const bool better = r2.second > r.second + 1e-6;
    if (r2.second > r.second) r = r2;
    if (!better) break;
  }
  return r;
}

}  // namespace

LearningTest learning_test(const Objective& f, const Box& box, const Theta& base, const ObserverFit& pooled,
                           double level) {
  const auto [top, cis] = settle(f, box, learning_max(f, box, base), level, kGamma);
  const Theta& th = top.first;
  LearningTest lt;
  lt.condition = pooled.unit;
  lt.gamma = estimate_of(kGamma, th, cis.ci[kGamma]);
  lt.beta0 = th[kBeta];
  lt.log_likelihood0 = pooled.log_likelihood;
  // The model with gamma nests the pooled one: a maximum found below it is the optimiser's shortfall.
  lt.log_likelihood1 = std::max(f(th), pooled.log_likelihood);
  lt.statistic = 2 * (lt.log_likelihood1 - lt.log_likelihood0);
  lt.p_value = boost::math::cdf(boost::math::complement(boost::math::chi_squared(1.0), lt.statistic));
  return lt;
}

}  // namespace feint::models::detail::observer

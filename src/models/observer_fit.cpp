// Maximum-likelihood fit of the goal-inference observer to pad traces
// (feint/models/observer_fit.hpp, docs/observer.md).
#include "feint/models/observer_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <numbers>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "feint/error.hpp"
#include "observer_optimise.hpp"

namespace feint::models {

namespace {

// The parameter vector, its box and the optimisers (observer_optimise.hpp).
using namespace detail::observer;

constexpr FitWording kPadWording{"the pad follows whichever side the path leans to at once",
                                 "the pad does not follow the robot's path (belief = prior)"};

/// A trial ready for the likelihood: where its pad samples (kept after thinning) sit in the
/// problem's flat arrays, and the start's distances.
struct Prepared {
  const ObservedTrial* trial = nullptr;
  Eigen::Index offset = 0, n = 0;  // samples offset .. offset + n - 1 of Problem's arrays
  std::vector<double> inv_dt;      // 1 / (t_{k+1} - t_k) of each path segment (no division per sample)
  double right0 = 0, left0 = 0;    // |S - G_R|, |S - G_L|
  double progress_end = 0;         // D at the path's last point (after the robot stops)
};

/// The trials of a fit, with their pad samples in flat arrays so that the likelihood's inner loops
/// run over contiguous memory (vectorised by Eigen).
struct Problem {
  std::vector<Prepared> trials;
  Eigen::ArrayXd times, pads;
  Goals goals;
  PadNoise noise = PadNoise::ar1;
  std::size_t samples = 0;
  mutable std::size_t evaluations = 0;
  // The progress difference D_i = (V_R(Q_i) - V_R(S)) - (V_L(Q_i) - V_L(S)) at each sample's delayed
  // position Q_i = xi(t_i - tau) depends on tau alone. It is kept for the last few taus (least
  // recently used replaced): most evaluations change only beta or the prior (the grid, tau's
  // profile), or come back to a recent tau (a parabola's centre, the Hessian's stencil).
  struct ProgressSlot {
    double tau = std::numeric_limits<double>::quiet_NaN();
    std::size_t used = 0;
    Eigen::ArrayXd d;
    // Per trial, the samples [first, end) whose delayed time falls while the robot moves; before
    // them D = 0 (the robot is at S), after them D = progress_end.
    std::vector<std::pair<Eigen::Index, Eigen::Index>> moving;
  };
  mutable std::array<ProgressSlot, 4> slots;
  mutable std::size_t clock = 0;
  // Scratch for one trial at a time (kept in the first-level cache even in a pooled fit).
  mutable Eigen::ArrayXd x, y, resid;
};

Problem prepare(std::span<const ObservedTrial> trials, const ObserverFitSettings& s) {
  Problem p;
  p.goals = s.goals;
  p.noise = s.noise;
  std::vector<double> times, pads;
  for (const auto& tr : trials) {
    Prepared q;
    q.trial = &tr;
    q.offset = static_cast<Eigen::Index>(times.size());
    double last = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < tr.times.size(); ++i) {
      if (s.thin > 0 && tr.times[i] - last < s.thin * (1 - 1e-9)) continue;
      last = tr.times[i];
      times.push_back(tr.times[i]);
      pads.push_back(tr.pads[i]);
    }
    q.n = static_cast<Eigen::Index>(times.size()) - q.offset;
    for (std::size_t k = 0; k + 1 < tr.path.size(); ++k) q.inv_dt.push_back(1.0 / (tr.path[k + 1].t - tr.path[k].t));
    const PathSample& s0 = tr.path.front();
    q.right0 = std::hypot(s0.x - s.goals.right.x, s0.y - s.goals.right.y);
    q.left0 = std::hypot(s0.x - s.goals.left.x, s0.y - s.goals.left.y);
    const PathSample& s1 = tr.path.back();
    q.progress_end = (std::hypot(s1.x - s.goals.right.x, s1.y - s.goals.right.y) - q.right0) -
                     (std::hypot(s1.x - s.goals.left.x, s1.y - s.goals.left.y) - q.left0);
    p.trials.push_back(std::move(q));
  }
  p.samples = times.size();
  const auto n = static_cast<Eigen::Index>(times.size());
  p.times = Eigen::Map<const Eigen::ArrayXd>(times.data(), n);
  p.pads = Eigen::Map<const Eigen::ArrayXd>(pads.data(), n);
  Eigen::Index longest = 0;
  for (const auto& q : p.trials) longest = std::max(longest, q.n);
  p.x.resize(longest);
  p.y.resize(longest);
  p.resid.resize(longest);
  return p;
}

/// D_i for the delay tau (from the cache when it holds tau): the robot's position at t_i - tau,
/// linear between path samples (the path's first point before it starts, its last after it ends),
/// then both goals' distances.
const Problem::ProgressSlot& progress_at(const Problem& p, double tau) {
  ++p.clock;
  Problem::ProgressSlot* slot = &p.slots[0];
  for (auto& s : p.slots) {
    if (s.tau == tau) {
      s.used = p.clock;
      return s;
    }
    if (s.used < slot->used) slot = &s;
  }
  slot->d.resize(p.times.size());
  slot->moving.resize(p.trials.size());
  const double rx = p.goals.right.x, ry = p.goals.right.y, lx = p.goals.left.x, ly = p.goals.left.y;
  for (std::size_t tq = 0; tq < p.trials.size(); ++tq) {
    const Prepared& q = p.trials[tq];
    const auto& path = q.trial->path;
    const std::size_t last = path.size() - 1;
    // Pad times increase: the samples before the robot starts and after it stops are a prefix and
    // a suffix.
    Eigen::Index first = q.offset, end = q.offset + q.n;
    while (first < end && p.times[first] - tau <= path[0].t) ++first;
    while (end > first && p.times[end - 1] - tau >= path[last].t) --end;
    slot->d.segment(q.offset, first - q.offset).setZero();
    slot->d.segment(end, q.offset + q.n - end).setConstant(q.progress_end);
    slot->moving[tq] = {first - q.offset, end - q.offset};
    std::size_t k = 0;
    for (Eigen::Index i = first; i < end; ++i) {
      const double t = p.times[i] - tau;
      while (path[k + 1].t <= t) ++k;
      const double w = (t - path[k].t) * q.inv_dt[k];
      p.x[i - first] = path[k].x + w * (path[k + 1].x - path[k].x);
      p.y[i - first] = path[k].y + w * (path[k + 1].y - path[k].y);
    }
    const auto x = p.x.head(end - first);
    const auto y = p.y.head(end - first);
    slot->d.segment(first, end - first) = (((x - rx).square() + (y - ry).square()).sqrt() - q.right0) -
                                          (((x - lx).square() + (y - ly).square()).sqrt() - q.left0);
  }
  slot->tau = tau;
  slot->used = p.clock;
  return *slot;
}

struct Likelihood {
  double loglik = 0;
  double sigma = 0;
  double phi = 0;
};

/// The profile log-likelihood at theta (sigma and phi in closed form).
Likelihood evaluate(const Problem& p, const Theta& th) {
  ++p.evaluations;
  const Problem::ProgressSlot& slot = progress_at(p, th[kTau]);
  double sxx = 0, sxy = 0, syy = 0;
  Eigen::Index m = 0;
  // b = 1 / (1 + e^-logit), logit = prior logit - beta D. Eigen's exp saturates instead of
  // overflowing (|z| > 709), which leaves b within 1e-300 of 0 or 1. Before the robot moves, b is the
  // prior.
  const double b_start = 1.0 / (1.0 + std::exp(-th[kPrior]));
  for (std::size_t tq = 0; tq < p.trials.size(); ++tq) {
    const Prepared& q = p.trials[tq];
    const double beta = th[kBeta] * std::exp(th[kGamma] * q.trial->exposure);
    const auto [first, end] = slot.moving[tq];
    auto r = p.resid.head(q.n);
    const auto pads = p.pads.segment(q.offset, q.n);
    r.head(first) = pads.head(first) - b_start;
    r.segment(first, end - first) =
        pads.segment(first, end - first) -
        1.0 / (1.0 + (beta * slot.d.segment(q.offset + first, end - first) - th[kPrior]).exp());
    r.tail(q.n - end) = pads.tail(q.n - end) - 1.0 / (1.0 + std::exp(beta * q.progress_end - th[kPrior]));
    if (p.noise == PadNoise::independent) {
      syy += r.square().sum();
      m += q.n;
    } else {
      // Pairs of consecutive samples within the trial (conditional on its first sample).
      const auto prev = r.head(q.n - 1), cur = r.tail(q.n - 1);
      sxx += prev.square().sum();
      sxy += (prev * cur).sum();
      syy += cur.square().sum();
      m += q.n - 1;
    }
  }
  Likelihood out;
  double rss = syy;
  if (p.noise == PadNoise::ar1 && sxx > 0) {
    out.phi = std::clamp(sxy / sxx, -0.9999, 0.9999);
    rss = syy - 2 * out.phi * sxy + out.phi * out.phi * sxx;
  }
  const double md = static_cast<double>(m);
  const double var = std::max(rss / md, 1e-24);  // a perfect fit would be +inf
  out.sigma = std::sqrt(var);
  out.loglik = -md / 2 * (std::log(2 * std::numbers::pi * var) + 1);
  return out;
}

/// The global maximum: the profile over tau scanned on a coarse grid (0.05 s), finer (0.01 s) where
/// it is near its best, and its best local maxima refined (ScanPlan); beta restarted from 0.1-10 at
/// tau 0, 0.25, 0.6 and 1.2 s. The profile over tau is rough: a local search from one start stops at
/// a local maximum (or, started at tau = 0, on the bound).
std::pair<Theta, double> global_max(const Problem& p, const Box& box, Theta base,
                                    const std::optional<Theta>& start) {
  auto f = [&](const Theta& th) { return evaluate(p, th).loglik; };
  std::vector<Theta> starts;
  if (start) starts.push_back(clamp(*start, box));
  return scan_maximum(f, box, base, observer_scan_plan(box), starts);
}

double prior_logit(double p) { return std::log(p) - std::log1p(-p); }

}  // namespace

void ObserverFitSettings::validate() const {
  auto bad = [](const char* name, double v, const char* expected) {
    throw UsageError(fmt::format("observer fit setting '{}' = {} is invalid: expected {}", name, v, expected));
  };
  if (!(beta_max > 0) || !std::isfinite(beta_max)) bad("beta_max", beta_max, "a finite number > 0 (1/m)");
  if (!(tau_max > 0) || !std::isfinite(tau_max)) bad("tau_max", tau_max, "a finite delay > 0 (s)");
  if (!(prior_right > 0 && prior_right < 1)) bad("prior_right", prior_right, "a probability in (0, 1)");
  if (!(thin >= 0) || !std::isfinite(thin)) bad("thin", thin, "a finite time >= 0 (s)");
  if (!(level > 0 && level < 1)) bad("level", level, "a confidence level in (0, 1)");
  if (!(pad_speed > 0) || !std::isfinite(pad_speed)) bad("pad_speed", pad_speed, "a finite speed > 0");
  metric.validate();
}

const ParameterEstimate& ObserverFit::parameter(std::string_view name) const {
  for (const auto& p : parameters)
    if (p.name == name) return p;
  throw UsageError(fmt::format("the observer fit has no parameter '{}'", name));
}

GoalObserver ObserverFit::observer() const {
  return GoalObserver{parameter("beta").estimate, parameter("tau").estimate, prior_right};
}

std::optional<std::string> trial_problem(const ObservedTrial& tr) {
  try {
    validate_path(tr.path);
  } catch (const InvalidData& e) {
    return std::string(e.what());
  }
  if (tr.times.size() != tr.pads.size()) {
    return fmt::format("the pad trace has {} times but {} pad values", tr.times.size(), tr.pads.size());
  }
  if (tr.times.size() < 3) {
    return fmt::format("the pad trace has {} sample(s); at least 3 are needed to fit the observer",
                       tr.times.size());
  }
  for (std::size_t i = 0; i < tr.times.size(); ++i) {
    if (!std::isfinite(tr.times[i]) || !std::isfinite(tr.pads[i])) {
      return fmt::format("pad sample {} is not finite (t = {}, pad = {})", i + 1, tr.times[i], tr.pads[i]);
    }
    if (i > 0 && !(tr.times[i] > tr.times[i - 1])) {
      return fmt::format("pad times must increase strictly: sample {} has t = {} after t = {}", i + 1,
                         tr.times[i], tr.times[i - 1]);
    }
  }
  if (!(tr.times.back() - tr.times.front() > 0)) return std::string("the pad trace has zero duration");
  return std::nullopt;
}

double observer_log_likelihood(std::span<const ObservedTrial> trials, const ObserverFitSettings& settings,
                               const GoalObserver& observer) {
  settings.validate();
  validate(observer);
  const Problem p = prepare(trials, settings);
  return evaluate(p, Theta{observer.beta, observer.tau, prior_logit(observer.prior_right), 0.0}).loglik;
}

namespace {

/// The fit of beta, tau (and the prior when fitted) with their CIs.
ObserverFit fit_problem(const Problem& p, const ObserverFitSettings& settings, std::string unit, Theta base,
                        std::size_t ntrials, const std::optional<Theta>& start) {
  const Box box = observer_box(settings, false);
  const Objective f = [&p](const Theta& x) { return evaluate(p, x).loglik; };
  const auto found = global_max(p, box, base, start);
  const auto [top, cis] = settle(f, box, found, settings.level, kParams);
  const Theta& th = top.first;
  ObserverFit fit;
  fit.unit = std::move(unit);
  fit.trials = ntrials;
  fit.samples = p.samples;
  const Likelihood at = evaluate(p, th);
  fit.log_likelihood = at.loglik;
  fit.sigma = at.sigma;
  fit.phi = at.phi;
  fit.prior_right = box.free[kPrior] ? logistic(th[kPrior]) : settings.prior_right;
  describe_estimates(fit, box, th, cis, settings.beta_max, settings.tau_max, kPadWording);
  fit.evaluations = p.evaluations;
  return fit;
}

}  // namespace

ObserverFit fit_observer(std::span<const ObservedTrial> trials, const ObserverFitSettings& settings,
                         std::string unit, const std::optional<GoalObserver>& start) {
  settings.validate();
  if (trials.empty()) throw InvalidData(fmt::format("{}: no usable trial to fit the observer to", unit));
  for (const auto& tr : trials) {
    if (auto why = trial_problem(tr)) {
      throw InvalidData(fmt::format("trial {}: {}", tr.label.empty() ? tr.participant : tr.label, *why));
    }
  }
  const Problem p = prepare(trials, settings);
  std::optional<Theta> from;
  if (start) {
    validate(*start);
    from = Theta{start->beta, start->tau,
                 settings.fit_prior ? prior_logit(start->prior_right) : prior_logit(settings.prior_right), 0.0};
  }
  ObserverFit fit = fit_problem(p, settings, std::move(unit), Theta{1.0, 0.0, prior_logit(settings.prior_right), 0.0},
                                trials.size(), from);
  if (!trials.empty()) fit.condition = trials.front().condition;
  return fit;
}

LearningTest test_learning(std::span<const ObservedTrial> trials, const ObserverFitSettings& settings,
                           const ObserverFit& pooled) {
  settings.validate();
  const Problem p = prepare(trials, settings);
  const Theta base{pooled.parameter("beta").estimate, pooled.parameter("tau").estimate,
                   prior_logit(pooled.observer().prior_right), 0.0};
  const Objective f = [&p](const Theta& x) { return evaluate(p, x).loglik; };
  return learning_test(f, observer_box(settings, true), base, pooled, settings.level);
}

}  // namespace feint::models

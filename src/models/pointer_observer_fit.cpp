// Maximum-likelihood fit of the K-goal observer to pointer traces
// (feint/models/pointer_observer_fit.hpp, docs/observer.md "Fitting the observer to pointer traces
// (K targets)"). The optimisers and the CIs are the pad fit's (observer_optimise.hpp).
#include "feint/models/pointer_observer_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <tuple>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/models/deceptiveness.hpp"
#include "observer_optimise.hpp"
#include "observer_study_detail.hpp"

namespace feint::models {

namespace {

using namespace detail::observer;

constexpr FitWording kPointerWording{
    "the pointer goes at once to the target the path leans to",
    "the pointer does not follow the robot's path (it stays at the prior mean, the targets' centroid)"};

/// A trial ready for the likelihood: where its samples (kept after thinning) sit in the problem's
/// flat arrays, and its layout.
struct Prepared {
  const PointerObservedTrial* trial = nullptr;
  Eigen::Index offset = 0, n = 0;  // samples offset .. offset + n - 1 of Problem's arrays
  Eigen::Index d_offset = 0;       // its K blocks of n progress values in a ProgressSlot
  std::size_t k = 0;
  double inv_scale = 0;            // 1 / layout_scale
  std::vector<double> gx, gy;      // the targets
  double cx = 0, cy = 0;           // the targets' centroid (the prior mean)
  std::vector<double> v0;          // |S - G_k|
  std::vector<double> inv_dt;      // 1 / (t_{k+1} - t_k) of each path segment
};

struct Problem {
  std::vector<Prepared> trials;
  Eigen::ArrayXd times, px, py;
  PadNoise noise = PadNoise::ar1;
  std::size_t samples = 0;
  Eigen::Index d_size = 0;
  mutable std::size_t evaluations = 0;
  // The progress of each goal at each sample's delayed position Q_i = xi(t_i - tau),
  // V_k(Q_i) - V_k(S), less its smallest value over the goals (so that the exponentials below are
  // at most 1: no overflow for any beta), depends on tau alone: kept for the last few taus, as in
  // the pad's fit (most evaluations change only beta or return to a recent tau).
  struct ProgressSlot {
    double tau = std::numeric_limits<double>::quiet_NaN();
    std::size_t used = 0;
    Eigen::ArrayXd d;
    // Per trial, the samples [first, end) whose delayed time falls while the robot moves: before
    // them the robot is at S (the mean is the centroid), after them at its end (one mean).
    std::vector<std::pair<Eigen::Index, Eigen::Index>> moving;
  };
  mutable std::array<ProgressSlot, 4> slots;
  mutable std::size_t clock = 0;
  // Scratch for one trial at a time.
  mutable Eigen::ArrayXd qx, qy, e, nx, ny, rx, ry;
  mutable Eigen::ArrayXXd w;  // exp(-beta d), samples x goals
};

Problem prepare(std::span<const PointerObservedTrial> trials, const ObserverFitSettings& s) {
  Problem p;
  p.noise = s.noise;
  std::vector<double> times, xs, ys;
  Eigen::Index longest = 0, most_goals = 0;
  for (const auto& tr : trials) {
    Prepared q;
    q.trial = &tr;
    q.offset = static_cast<Eigen::Index>(times.size());
    double last = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < tr.times.size(); ++i) {
      if (s.thin > 0 && tr.times[i] - last < s.thin * (1 - 1e-9)) continue;
      last = tr.times[i];
      times.push_back(tr.times[i]);
      xs.push_back(tr.x[i]);
      ys.push_back(tr.y[i]);
    }
    q.n = static_cast<Eigen::Index>(times.size()) - q.offset;
    q.k = tr.layout.targets.size();
    q.d_offset = p.d_size;
    p.d_size += static_cast<Eigen::Index>(q.k) * q.n;
    q.inv_scale = 1.0 / metrics::layout_scale(tr.layout);
    const PathSample& s0 = tr.path.front();
    for (const auto& g : tr.layout.targets) {
      q.gx.push_back(g.x);
      q.gy.push_back(g.y);
      q.v0.push_back(std::hypot(s0.x - g.x, s0.y - g.y));
    }
    for (std::size_t k = 0; k < q.k; ++k) {
      q.cx += q.gx[k] / static_cast<double>(q.k);
      q.cy += q.gy[k] / static_cast<double>(q.k);
    }
    for (std::size_t k = 0; k + 1 < tr.path.size(); ++k) q.inv_dt.push_back(1.0 / (tr.path[k + 1].t - tr.path[k].t));
    longest = std::max(longest, q.n);
    most_goals = std::max(most_goals, static_cast<Eigen::Index>(q.k));
    p.trials.push_back(std::move(q));
  }
  p.samples = times.size();
  const auto n = static_cast<Eigen::Index>(times.size());
  p.times = Eigen::Map<const Eigen::ArrayXd>(times.data(), n);
  p.px = Eigen::Map<const Eigen::ArrayXd>(xs.data(), n);
  p.py = Eigen::Map<const Eigen::ArrayXd>(ys.data(), n);
  for (auto* a : {&p.qx, &p.qy, &p.e, &p.nx, &p.ny, &p.rx, &p.ry}) a->resize(longest);
  p.w.resize(longest, most_goals);
  return p;
}

/// The delayed positions of one trial: the robot at t_i - tau, linear between path samples (the
/// path's first point before it starts, its last after it ends), as models::position_at.
void delayed_positions(const Problem& p, const Prepared& q, double tau) {
  const auto& path = q.trial->path;
  const std::size_t last = path.size() - 1;
  std::size_t k = 0;
  for (Eigen::Index i = 0; i < q.n; ++i) {
    const double t = p.times[q.offset + i] - tau;
    if (t <= path[0].t) {
      p.qx[i] = path[0].x;
      p.qy[i] = path[0].y;
    } else if (t >= path[last].t) {
      p.qx[i] = path[last].x;
      p.qy[i] = path[last].y;
    } else {
      while (path[k + 1].t <= t) ++k;  // times increase: the segment only moves forward
      const double w = (t - path[k].t) * q.inv_dt[k];
      p.qx[i] = path[k].x + w * (path[k + 1].x - path[k].x);
      p.qy[i] = path[k].y + w * (path[k + 1].y - path[k].y);
    }
  }
}

/// The progress values for the delay tau (from the cache when it holds tau).
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
  slot->d.resize(p.d_size);
  slot->moving.resize(p.trials.size());
  for (std::size_t tq = 0; tq < p.trials.size(); ++tq) {
    const Prepared& q = p.trials[tq];
    const auto& path = q.trial->path;
    const auto t = p.times.segment(q.offset, q.n);
    Eigen::Index first = 0, end = q.n;
    while (first < end && t[first] - tau <= path.front().t) ++first;
    while (end > first && t[end - 1] - tau >= path.back().t) --end;
    slot->moving[tq] = {first, end};
    delayed_positions(p, q, tau);
    const auto qx = p.qx.head(q.n), qy = p.qy.head(q.n);
    auto low = p.e.head(q.n);
    low.setConstant(std::numeric_limits<double>::infinity());
    for (std::size_t k = 0; k < q.k; ++k) {
      auto d = slot->d.segment(q.d_offset + static_cast<Eigen::Index>(k) * q.n, q.n);
      d = ((qx - q.gx[k]).square() + (qy - q.gy[k]).square()).sqrt() - q.v0[k];
      low = low.min(d);
    }
    for (std::size_t k = 0; k < q.k; ++k) slot->d.segment(q.d_offset + static_cast<Eigen::Index>(k) * q.n, q.n) -= low;
  }
  slot->tau = tau;
  slot->used = p.clock;
  return *slot;
}

/// The posterior mean of trial tq at beta into p.nx, p.ny (first n values): w_k ∝ exp(-beta d_k).
/// The progress values of a trial are a samples x goals column-major block (one exponential pass).
/// Only the samples seen while the robot moves, and the first after it stops, need it.
void means(const Problem& p, std::size_t tq, const Problem::ProgressSlot& slot, double beta) {
  const Prepared& q = p.trials[tq];
  const auto [first, end] = slot.moving[tq];
  const Eigen::Index stop = std::min(q.n, end + 1), rows = stop - first;
  const auto goals = static_cast<Eigen::Index>(q.k);
  const Eigen::Map<const Eigen::ArrayXXd, 0, Eigen::OuterStride<>> d(slot.d.data() + q.d_offset + first, rows,
                                                                      goals, Eigen::OuterStride<>(q.n));
  auto w = p.w.topLeftCorner(rows, goals);
  w = (-beta * d).exp();
  auto den = p.e.head(rows);
  auto nx = p.nx.segment(first, rows), ny = p.ny.segment(first, rows);
  den = w.col(0);
  nx = w.col(0) * q.gx[0];
  ny = w.col(0) * q.gy[0];
  for (Eigen::Index k = 1; k < goals; ++k) {
    den += w.col(k);
    nx += w.col(k) * q.gx[static_cast<std::size_t>(k)];
    ny += w.col(k) * q.gy[static_cast<std::size_t>(k)];
  }
  den = den.inverse();
  nx *= den;
  ny *= den;
  p.nx.head(first).setConstant(q.cx);
  p.ny.head(first).setConstant(q.cy);
  if (stop < q.n) {  // the robot rests at its end: every later sample has the mean of sample `end`
    p.nx.segment(stop, q.n - stop).setConstant(p.nx[end]);
    p.ny.segment(stop, q.n - stop).setConstant(p.ny[end]);
  }
}

struct Likelihood {
  double loglik = 0;
  double sigma = 0;
  double phi = 0;
};

/// The profile log-likelihood at theta (beta, tau; sigma and phi in closed form).
Likelihood evaluate(const Problem& p, const Theta& th) {
  ++p.evaluations;
  const Problem::ProgressSlot& slot = progress_at(p, th[kTau]);
  double sxx = 0, sxy = 0, syy = 0;
  Eigen::Index m = 0;
  for (std::size_t tq = 0; tq < p.trials.size(); ++tq) {
    const Prepared& q = p.trials[tq];
    // The learning model's beta_k = beta0 exp(gamma exposure_k); gamma = 0 leaves beta as it is.
    means(p, tq, slot, th[kBeta] * std::exp(th[kGamma] * q.trial->exposure));
    auto rx = p.rx.head(q.n), ry = p.ry.head(q.n);
    rx = (p.px.segment(q.offset, q.n) - p.nx.head(q.n)) * q.inv_scale;
    ry = (p.py.segment(q.offset, q.n) - p.ny.head(q.n)) * q.inv_scale;
    if (p.noise == PadNoise::independent) {
      syy += rx.square().sum() + ry.square().sum();
      m += 2 * q.n;
    } else {
      // Pairs of consecutive samples within the trial, on each axis (conditional on the first).
      for (const auto* r : {&rx, &ry}) {
        const auto prev = r->head(q.n - 1), cur = r->tail(q.n - 1);
        sxx += prev.square().sum();
        sxy += (prev * cur).sum();
        syy += cur.square().sum();
      }
      m += 2 * (q.n - 1);
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

void check_settings(const ObserverFitSettings& s) {
  s.validate();
  if (s.fit_prior)
    throw UsageError(
        "the prior cannot be fitted to pointer traces: the observer of K targets starts from the uniform "
        "prior 1/K (fit beta and tau only)");
}

void check_trials(std::span<const PointerObservedTrial> trials, const std::string& unit) {
  if (trials.empty()) throw InvalidData(fmt::format("{}: no usable trial to fit the observer to", unit));
  for (const auto& tr : trials) {
    if (auto why = pointer_trial_problem(tr))
      throw InvalidData(fmt::format("trial {}: {}", tr.label.empty() ? tr.participant : tr.label, *why));
  }
}

void check_parameters(double beta, double tau) {
  validate(GoalObserver{beta, tau, 0.5});
}

}  // namespace

std::optional<std::string> pointer_trial_problem(const PointerObservedTrial& tr) {
  try {
    validate_path(tr.path);
    validate_goals(tr.layout);
    metrics::validate(tr.layout, 0, 0);
  } catch (const Error& e) {
    return std::string(e.what());
  }
  if (tr.target >= tr.layout.targets.size())
    return fmt::format("true target {} is not a target of the layout (K = {})", tr.target,
                       tr.layout.targets.size());
  if (tr.times.size() != tr.x.size() || tr.times.size() != tr.y.size())
    return fmt::format("the pointer trace has {} times but {} x and {} y values", tr.times.size(), tr.x.size(),
                       tr.y.size());
  if (tr.times.size() < 3)
    return fmt::format("the pointer trace has {} sample(s); at least 3 are needed to fit the observer",
                       tr.times.size());
  for (std::size_t i = 0; i < tr.times.size(); ++i) {
    if (!std::isfinite(tr.times[i]) || !std::isfinite(tr.x[i]) || !std::isfinite(tr.y[i]))
      return fmt::format("pointer sample {} is not finite (t = {}, x = {}, y = {})", i + 1, tr.times[i], tr.x[i],
                         tr.y[i]);
    if (i > 0 && !(tr.times[i] > tr.times[i - 1]))
      return fmt::format("pointer times must increase strictly: sample {} has t = {} after t = {}", i + 1,
                         tr.times[i], tr.times[i - 1]);
  }
  if (!(tr.times.back() - tr.times.front() > 0)) return std::string("the pointer trace has zero duration");
  return std::nullopt;
}

std::vector<metrics::MapPoint> pointer_observer_means(const PointerObservedTrial& trial, double beta,
                                                      double tau) {
  check_parameters(beta, tau);
  check_trials(std::span(&trial, 1), trial.label);
  const Problem p = prepare(std::span(&trial, 1), ObserverFitSettings{});
  const Prepared& q = p.trials.front();
  means(p, 0, progress_at(p, tau), beta);
  std::vector<metrics::MapPoint> out;
  for (Eigen::Index i = 0; i < q.n; ++i) out.push_back({p.nx[i], p.ny[i]});
  return out;
}

double pointer_observer_log_likelihood(std::span<const PointerObservedTrial> trials,
                                       const ObserverFitSettings& settings, double beta, double tau) {
  check_settings(settings);
  check_parameters(beta, tau);
  check_trials(trials, "the pointer log-likelihood");
  const Problem p = prepare(trials, settings);
  return evaluate(p, Theta{beta, tau, 0.0, 0.0}).loglik;
}

ObserverFit fit_pointer_observer(std::span<const PointerObservedTrial> trials,
                                 const ObserverFitSettings& settings, std::string unit,
                                 const std::optional<GoalPosteriorObserver>& start) {
  check_settings(settings);
  check_trials(trials, unit);
  std::vector<Theta> starts;
  const Box box = observer_box(settings, false);
  if (start) {
    check_parameters(start->beta, start->tau);
    if (!start->prior.empty())
      throw UsageError("the start of a pointer fit has the uniform prior (leave its prior empty)");
    starts.push_back(clamp(Theta{start->beta, start->tau, 0.0, 0.0}, box));
  }
  const Problem p = prepare(trials, settings);
  const Objective f = [&p](const Theta& x) { return evaluate(p, x).loglik; };
  const auto found = scan_maximum(f, box, Theta{1.0, 0.0, 0.0, 0.0}, observer_scan_plan(box), starts);
  const auto [top, cis] = settle(f, box, found, settings.level, kParams);
  ObserverFit fit;
  fit.unit = std::move(unit);
  fit.condition = trials.front().condition;
  fit.trials = trials.size();
  fit.samples = p.samples;
  const Likelihood at = evaluate(p, top.first);
  fit.log_likelihood = at.loglik;
  fit.sigma = at.sigma;
  fit.phi = at.phi;
  fit.prior_right = std::numeric_limits<double>::quiet_NaN();
  describe_estimates(fit, box, top.first, cis, settings.beta_max, settings.tau_max, kPointerWording);
  fit.evaluations = p.evaluations;
  return fit;
}

namespace {

/// Labels every trial; keeps the usable ones (sorted by condition, participant, iteration, with
/// their exposure counted) and names each bad one in out.issues.
std::vector<PointerObservedTrial> usable(std::vector<PointerObservedTrial>& trials, PointerStudyObserverFit& out) {
  std::vector<PointerObservedTrial> good;
  for (auto& tr : trials) {
    if (tr.label.empty())
      tr.label = tr.condition.empty() ? fmt::format("{}/{}", tr.participant, tr.iteration)
                                      : fmt::format("{}/{}/{}", tr.participant, tr.condition, tr.iteration);
    if (auto why = pointer_trial_problem(tr)) {
      out.issues.push_back({tr.label, *why + "; the trial is left out of the fit"});
      continue;
    }
    good.push_back(std::move(tr));
  }
  count_exposure(good);
  return good;
}

/// The trials' K range and how many distinct layouts they have.
void describe_layouts(const std::vector<PointerObservedTrial>& good, PointerStudyObserverFit& out) {
  std::set<std::vector<double>> layouts;
  for (const auto& tr : good) {
    const std::size_t k = tr.layout.targets.size();
    out.min_targets = out.min_targets == 0 ? k : std::min(out.min_targets, k);
    out.max_targets = std::max(out.max_targets, k);
    std::vector<double> l{tr.layout.start.x, tr.layout.start.y};
    for (const auto& g : tr.layout.targets) l.insert(l.end(), {g.x, g.y});
    layouts.insert(std::move(l));
  }
  out.layouts = layouts.size();
}

/// Fits each run of trials with the same key (participant and condition, or condition); `start`
/// gives a run's start, `name` its unit.
template <typename Key, typename Name, typename Start>
void fit_groups(const std::vector<PointerObservedTrial>& good, const ObserverFitSettings& settings, Key key,
                Name name, Start start, std::vector<ObserverFit>& fits, PointerStudyObserverFit& out,
                const char* what) {
  for (std::size_t i = 0; i < good.size();) {
    std::size_t j = i;
    while (j < good.size() && key(good[j]) == key(good[i])) ++j;
    const std::string unit = name(good[i]);
    try {
      auto fit = fit_pointer_observer(std::span(good.data() + i, j - i), settings, unit, start(good[i]));
      for (const auto& n : fit.notes) out.issues.push_back({unit, without_unit(n, unit)});
      fits.push_back(std::move(fit));
    } catch (const Error& e) {
      out.issues.push_back({unit, fmt::format("the {} fit failed: {}", what, e.what())});
    }
    i = j;
  }
}

// The pooled maximum lies near the participants' fits: their mean, weighted by samples, is a
// start besides the grid.
std::optional<GoalPosteriorObserver> pooled_start(const std::vector<ObserverFit>& participants,
                                                  const std::string& condition) {
  double w = 0, beta = 0, tau = 0;
  for (const auto& f : participants) {
    if (f.condition != condition) continue;
    const auto n = static_cast<double>(f.samples);
    w += n;
    beta += n * f.parameter("beta").estimate;
    tau += n * f.parameter("tau").estimate;
  }
  if (w > 0) return GoalPosteriorObserver{beta / w, tau / w, {}};
  return std::nullopt;
}

/// The learning test of each condition's pooled fit, on that condition's trials.
void learning_tests(const std::vector<PointerObservedTrial>& good, const ObserverFitSettings& settings,
                    PointerStudyObserverFit& out) {
  for (const auto& pooled : out.conditions) {
    const auto in = [&pooled](const PointerObservedTrial& t) { return t.condition == pooled.condition; };
    const auto first = std::find_if(good.begin(), good.end(), in);
    const auto last = std::find_if_not(first, good.end(), in);
    try {
      out.learning.push_back(test_pointer_learning(std::span(first, last), settings, pooled));
    } catch (const Error& e) {
      out.issues.push_back({pooled.unit, fmt::format("the learning test failed: {}", e.what())});
    }
  }
}

}  // namespace

LearningTest test_pointer_learning(std::span<const PointerObservedTrial> trials, const ObserverFitSettings& settings,
                                   const ObserverFit& pooled) {
  check_settings(settings);
  check_trials(trials, pooled.unit);
  const Problem p = prepare(trials, settings);
  const Objective f = [&p](const Theta& x) { return evaluate(p, x).loglik; };
  const Theta base{pooled.parameter("beta").estimate, pooled.parameter("tau").estimate, 0.0, 0.0};
  return learning_test(f, observer_box(settings, true), base, pooled, settings.level);
}

PointerStudyObserverFit fit_pointer_study(std::vector<PointerObservedTrial> trials,
                                          const ObserverFitSettings& settings) {
  check_settings(settings);
  PointerStudyObserverFit out;
  const std::vector<PointerObservedTrial> good = usable(trials, out);
  out.trials_used = good.size();
  describe_layouts(good, out);
  fit_groups(
      good, settings, [](const PointerObservedTrial& t) { return std::pair(t.condition, t.participant); },
      [](const PointerObservedTrial& t) { return t.participant; },
      [](const PointerObservedTrial&) { return std::optional<GoalPosteriorObserver>(); }, out.participants, out,
      "participant's");
  fit_groups(
      good, settings, [](const PointerObservedTrial& t) { return t.condition; },
      [](const PointerObservedTrial& t) { return t.condition.empty() ? std::string("all") : t.condition; },
      [&out](const PointerObservedTrial& t) { return pooled_start(out.participants, t.condition); },
      out.conditions, out, "pooled");
  if (settings.learning) learning_tests(good, settings, out);
  if (out.conditions.size() == 2)
    out.comparisons = compare_conditions(out.participants, out.conditions[0].condition,
                                         out.conditions[1].condition, settings.level);
  out.agreement = pointer_agreement(good, out.participants, settings, out.issues);
  return out;
}

}  // namespace feint::models

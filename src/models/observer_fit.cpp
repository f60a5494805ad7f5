// Maximum-likelihood fit of the goal-inference observer to pad traces
// (feint/models/observer_fit.hpp, docs/observer.md).
#include "feint/models/observer_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <functional>
#include <map>
#include <optional>
#include <numbers>
#include <tuple>

#include <Eigen/Dense>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/tools/minima.hpp>
#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::models {

namespace {

// Full parameter vector: beta (1/m), tau (s), logit of the prior, gamma (learning rate).
enum Param : std::size_t { kBeta = 0, kTau = 1, kPrior = 2, kGamma = 3 };
constexpr std::size_t kParams = 4;
using Theta = std::array<double, kParams>;
constexpr std::array<const char*, kParams> kNames = {"beta", "tau", "prior_right", "gamma"};
constexpr double kGammaMax = 1.0;   // |gamma| per earlier trial of the strategy
constexpr double kLogitMax = 8.0;   // prior in [3.4e-4, 0.99966]

double logistic(double z) noexcept {
  if (z >= 0) return 1.0 / (1.0 + std::exp(-z));
  const double e = std::exp(z);
  return e / (1.0 + e);
}

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

struct Box {
  Theta lo{}, hi{}, scale{};
  std::array<bool, kParams> free{};
};

Theta clamp(Theta th, const Box& b) {
  for (std::size_t j = 0; j < kParams; ++j) th[j] = std::clamp(th[j], b.lo[j], b.hi[j]);
  return th;
}

/// Nelder & Mead (1965) on the free coordinates (standard coefficients 1, 2, 1/2, 1/2), every point
/// projected into the box. Maximises f; returns the best point and its value.
std::pair<Theta, double> nelder_mead(const std::function<double(const Theta&)>& f, Theta start,
                                     const Box& box, const std::array<bool, kParams>& free,
                                     double step_factor, int max_evals) {
  std::vector<std::size_t> idx;
  for (std::size_t j = 0; j < kParams; ++j)
    if (free[j]) idx.push_back(j);
  start = clamp(start, box);
  const double f0 = f(start);
  if (idx.empty()) return {start, f0};
  const std::size_t d = idx.size();
  std::vector<Theta> x(d + 1, start);
  std::vector<double> v(d + 1, f0);
  int evals = 1;
  for (std::size_t k = 0; k < d; ++k) {
    const std::size_t j = idx[k];
    double step = box.scale[j] * step_factor;
    if (start[j] + step > box.hi[j]) step = -step;  // step into the box
    x[k + 1][j] = std::clamp(start[j] + step, box.lo[j], box.hi[j]);
    v[k + 1] = f(x[k + 1]);
    ++evals;
  }
  std::vector<std::size_t> order(d + 1);
  while (evals < max_evals) {
    for (std::size_t i = 0; i <= d; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] > v[b]; });
    const std::size_t best = order.front(), worst = order.back(), second = order[d - 1];
    // Converged: values within 1e-5 (relative 1e-10) and the simplex within 1e-4 of each scale
    // (the log-likelihood then is within ~1e-5 of its maximum: far below the 0.004 to which the
    // CI ends' deviance is solved).
    double spread = 0;
    for (std::size_t i = 0; i <= d; ++i)
      for (std::size_t j : idx) spread = std::max(spread, std::abs(x[i][j] - x[best][j]) / box.scale[j]);
    if (std::abs(v[best] - v[worst]) <= 1e-5 + 1e-10 * std::abs(v[best]) && spread < 1e-4) break;
    Theta centroid = x[best];
    for (std::size_t j : idx) {
      double s = 0;
      for (std::size_t i = 0; i <= d; ++i)
        if (i != worst) s += x[i][j];
      centroid[j] = s / static_cast<double>(d);
    }
    auto along = [&](double c) {
      Theta y = centroid;
      for (std::size_t j : idx) y[j] = centroid[j] + c * (x[worst][j] - centroid[j]);
      return clamp(y, box);
    };
    const Theta xr = along(-1.0);
    const double vr = f(xr);
    ++evals;
    if (vr > v[best]) {
      const Theta xe = along(-2.0);
      const double ve = f(xe);
      ++evals;
      if (ve > vr) { x[worst] = xe; v[worst] = ve; } else { x[worst] = xr; v[worst] = vr; }
      continue;
    }
    if (vr > v[second]) { x[worst] = xr; v[worst] = vr; continue; }
    const bool outside = vr > v[worst];
    const Theta xc = along(outside ? -0.5 : 0.5);
    const double vc = f(xc);
    ++evals;
    if (vc > std::max(vr, v[worst])) { x[worst] = xc; v[worst] = vc; continue; }
    for (std::size_t i = 0; i <= d; ++i) {  // shrink toward the best
      if (i == best) continue;
      for (std::size_t j : idx) x[i][j] = x[best][j] + 0.5 * (x[i][j] - x[best][j]);
      v[i] = f(x[i]);
      ++evals;
    }
  }
  std::size_t best = 0;
  for (std::size_t i = 1; i <= d; ++i)
    if (v[i] > v[best]) best = i;
  return {x[best], v[best]};
}

/// Maximises a 1-D concave-near-the-top function by successive parabolas through three points
/// spaced `h` around the warm start (a few evaluations when the warm start is close, as it is along a
/// profile); nullopt when the points are not concave (the caller falls back to Brent).
std::optional<std::pair<Theta, double>> parabolic_max(const std::function<double(const Theta&)>& f, Theta th,
                                                      std::size_t k, double h, const Box& box) {
  auto point = [&](double x) { Theta y = th; y[k] = std::clamp(x, box.lo[k], box.hi[k]); return y; };
  auto at = [&](double x) { const Theta y = point(x); return std::pair{y, f(y)}; };
  auto best = at(th[k]);
  for (int iter = 0; iter < 8; ++iter) {
    const double b = best.first[k];
    double a = std::max(box.lo[k], b - h), c = std::min(box.hi[k], b + h);
    std::array<std::pair<double, double>, 3> pt;
    if (b - h < box.lo[k]) {
      pt = {std::pair{b, best.second}, std::pair{b + h / 2, at(b + h / 2).second}, std::pair{b + h, at(b + h).second}};
    } else if (b + h > box.hi[k]) {
      pt = {std::pair{b - h, at(b - h).second}, std::pair{b - h / 2, at(b - h / 2).second}, std::pair{b, best.second}};
    } else {
      pt = {std::pair{a, at(a).second}, std::pair{b, best.second}, std::pair{c, at(c).second}};
    }
    const auto [x0, f0] = pt[0];
    const auto [x1, f1] = pt[1];
    const auto [x2, f2] = pt[2];
    const double d01 = (f1 - f0) / (x1 - x0), d12 = (f2 - f1) / (x2 - x1);
    const double curv = (d12 - d01) / (x2 - x0);  // half the second derivative
    if (!(curv < 0)) return std::nullopt;
    // Vertex of the parabola through the three points, kept within 3 h of the centre.
    const double xv = std::clamp((x0 + x1) / 2 - d01 / (2 * curv), b - 3 * h, b + 3 * h);
    auto cand = at(xv);
    for (const auto& q : pt)  // a known point beats the vertex: take it (its value is known too)
      if (q.second > cand.second) cand = {point(q.first), q.second};
    const double moved = std::abs(cand.first[k] - b);
    if (cand.second >= best.second) best = cand;
    if (moved < 0.05 * h) return best;
    h = std::max(moved, 0.1 * h);
  }
  return best;
}

/// Maximises over the free parameters other than `fixed` (kParams = none fixed), from `start`;
/// `h` is the step of the parabolic search (an SE of that parameter) when exactly one is free.
std::pair<Theta, double> maximise(const Problem& p, const Box& box, Theta start, std::size_t fixed,
                                  bool warm, const Theta& h = Theta{}) {
  auto f = [&](const Theta& th) { return evaluate(p, th).loglik; };
  std::array<bool, kParams> free = box.free;
  if (fixed < kParams) free[fixed] = false;
  std::size_t nfree = 0, only = 0;
  for (std::size_t j = 0; j < kParams; ++j)
    if (free[j]) { ++nfree; only = j; }
  if (nfree == 1) {
    if (warm && h[only] > 0) {
      if (auto r = parabolic_max(f, start, only, h[only], box)) return *r;
    }
    // Brent's method on the whole range.
    Theta th = start;
    auto g = [&](double v) { th[only] = v; return -f(th); };
    const auto r = boost::math::tools::brent_find_minima(g, box.lo[only], box.hi[only], 20);
    th[only] = r.first;
    return {th, -r.second};
  }
  if (warm) {
    // Cyclic parabolic searches over each free coordinate (the profile's remaining parameters are
    // only weakly correlated once the profiled one is fixed); Nelder-Mead if a parabola fails.
    bool ok = true;
    for (std::size_t j = 0; j < kParams; ++j) ok = ok && (!free[j] || h[j] > 0);
    if (ok) {
      Theta x = start;
      double fx = f(x);
      for (int cycle = 0; cycle < 8 && ok; ++cycle) {
        double moved = 0;
        for (std::size_t j = 0; j < kParams && ok; ++j) {
          if (!free[j]) continue;
          const auto r = parabolic_max(f, x, j, h[j], box);
          if (!r) { ok = false; break; }
          moved = std::max(moved, std::abs(r->first[j] - x[j]) / h[j]);
          x = r->first;
          fx = r->second;
        }
        if (ok && moved < 0.05) return {x, fx};
      }
    }
  }
  return nelder_mead(f, start, box, free, warm ? 0.2 : 0.5, 2000);
}

/// What the observed information at the maximum gives: the Wald SE and the conditional SE
/// (1 / sqrt(-H_jj)) of each free parameter (zeros where the Hessian is not negative definite), and
/// the ridge of the quadratic approximation: where the other parameters' maximum moves per unit of
/// parameter j, ridge[j][k] = cov(k, j) / cov(j, j).
struct StandardErrors {
  Theta wald{}, cond{};
  std::array<Theta, kParams> ridge{};
};

/// The observed information at the maximum by central differences (points kept in the box).
StandardErrors standard_errors(const Problem& p, const Box& box, const Theta& th, double l0) {
  std::vector<std::size_t> idx;
  for (std::size_t j = 0; j < kParams; ++j)
    if (box.free[j]) idx.push_back(j);
  const std::size_t d = idx.size();
  Eigen::MatrixXd H(d, d);
  Theta c = th;
  Theta h{};
  for (std::size_t a = 0; a < d; ++a) {
    const std::size_t j = idx[a];
    h[j] = 1e-3 * box.scale[j];
    c[j] = std::clamp(th[j], box.lo[j] + h[j], box.hi[j] - h[j]);  // room for the differences
  }
  const double fc = c == th ? l0 : evaluate(p, c).loglik;
  auto f = [&](std::size_t a, double sa, std::size_t b, double sb) {
    Theta y = c;
    y[idx[a]] += sa * h[idx[a]];
    if (b < d) y[idx[b]] += sb * h[idx[b]];
    return evaluate(p, y).loglik;
  };
  for (std::size_t a = 0; a < d; ++a) {
    H(a, a) = (f(a, 1, d, 0) - 2 * fc + f(a, -1, d, 0)) / (h[idx[a]] * h[idx[a]]);
    for (std::size_t b = a + 1; b < d; ++b) {
      H(a, b) = H(b, a) = (f(a, 1, b, 1) - f(a, 1, b, -1) - f(a, -1, b, 1) + f(a, -1, b, -1)) /
                          (4 * h[idx[a]] * h[idx[b]]);
    }
  }
  StandardErrors out;
  const Eigen::MatrixXd info = -H;
  Eigen::LLT<Eigen::MatrixXd> llt(info);
  if (llt.info() != Eigen::Success) return out;
  const Eigen::MatrixXd cov = llt.solve(Eigen::MatrixXd::Identity(static_cast<Eigen::Index>(d), static_cast<Eigen::Index>(d)));
  for (std::size_t a = 0; a < d; ++a) {
    out.wald[idx[a]] = std::sqrt(cov(a, a));
    out.cond[idx[a]] = 1 / std::sqrt(info(a, a));
    for (std::size_t b = 0; b < d; ++b)
      if (b != a) out.ridge[idx[a]][idx[b]] = cov(b, a) / cov(a, a);
  }
  return out;
}

/// Grid start, then Nelder-Mead. (A premature stop would show in the profile, which never finds a
/// higher value than the maximum: see profile_interval.)
std::pair<Theta, double> global_max(const Problem& p, const Box& box, Theta base,
                                    const std::optional<Theta>& start) {
  Theta best = base;
  double vbest = -std::numeric_limits<double>::infinity();
  // tau in the outer loop: the positions along the path are computed once per tau.
  for (double t : {0.0, 0.25, 0.6, 1.2}) {
    for (double b : {0.1, 0.3, 1.0, 3.0, 10.0}) {
      Theta th = base;
      if (box.free[kBeta]) th[kBeta] = std::min(b, box.hi[kBeta]);
      if (box.free[kTau]) th[kTau] = std::min(t, box.hi[kTau]);
      const double v = evaluate(p, th).loglik;
      if (v > vbest) { vbest = v; best = th; }
    }
  }
  // A start near the maximum (a pooled fit's, from its participants' fits) that beats the grid
  // needs a smaller first simplex.
  double step = 0.5;
  if (start) {
    const Theta th = clamp(*start, box);
    const double v = evaluate(p, th).loglik;
    if (v > vbest) { vbest = v; best = th; step = 0.1; }
  }
  auto f = [&](const Theta& th) { return evaluate(p, th).loglik; };
  auto r = nelder_mead(f, best, box, box.free, step, 3000);
  return r;
}

struct Interval {
  double low = 0, high = 0;
  bool low_at_bound = false, high_at_bound = false;
  bool hull = false;  // the profile fell below the cut-off again beyond a first crossing
};

/// Profile-likelihood interval of parameter j around the maximum (th, lmax). Each end solves
/// r(v) = +-z for the signed root deviance r(v) = sign(v - th_j) sqrt(2 (lmax - l_p(v))), which is
/// close to linear in v: secant steps from the Wald end, kept inside a bracket once one is known
/// (bisection otherwise), to |r - z| < 1e-3 (the deviance within ~0.004 of chi2_1(level)).
Interval profile_interval(const Problem& p, const Box& box, const Theta& th, double lmax, std::size_t j,
                          double level, const StandardErrors& ses) {
  const double z = std::sqrt(boost::math::quantile(boost::math::chi_squared(1.0), level));
  const Theta& wald = ses.wald;
  Theta step = ses.cond;
  for (std::size_t k = 0; k < kParams; ++k)
    if (!(step[k] > 0)) step[k] = 0.1 * box.scale[k];
  const double se = wald[j] > 0 ? wald[j] : 0.25 * box.scale[j];
  Interval out;
  for (int side : {-1, 1}) {
    const double bound = side < 0 ? box.lo[j] : box.hi[j];
    double& end = side < 0 ? out.low : out.high;
    bool& at_bound = side < 0 ? out.low_at_bound : out.high_at_bound;
    Theta warm = th;
    // s(v) = side * r(v): 0 at the maximum, increasing outward; the end is s = z.
    auto s_of = [&](double v) {
      Theta x = warm;
      x[j] = v;
      // Start the re-maximisation on the ridge: the others moved as the quadratic approximation
      // predicts from the last point (at most 3 conditional SEs), so that it needs fewer steps.
      for (std::size_t k = 0; k < kParams; ++k) {
        if (k == j || ses.ridge[j][k] == 0) continue;
        const double move = std::clamp(ses.ridge[j][k] * (v - warm[j]), -3 * step[k], 3 * step[k]);
        x[k] = std::clamp(warm[k] + move, box.lo[k], box.hi[k]);
      }
      const auto r = maximise(p, box, x, j, true, step);
      if (r.second > lmax) return 0.0;  // a higher maximum along the profile: inside the interval
      warm = r.first;
      return std::sqrt(2 * (lmax - r.second));
    };
    if (th[j] == bound) {
      end = bound;
      at_bound = true;
      continue;
    }
    // One search outward from a point inside (s < z) to the crossing s = z.
    auto search = [&](double from, double s_from) {
      double v_in = from;            // inside: s < z
      double v_out = std::nan("");   // outside: s >= z (once known)
      double v_prev = from, s_prev = s_from;
      double v = std::clamp(from + side * std::max(z - s_from, 0.1) * se, box.lo[j], box.hi[j]);
      for (int iter = 0; iter < 40; ++iter) {
        const double sv = s_of(v);
        if (sv < z) v_in = v; else v_out = v;
        if (std::abs(sv - z) < 1e-3) return v;
        if (std::isnan(v_out) && v == bound) { at_bound = true; return bound; }
        // Secant on (v_prev, s_prev), (v, sv); fall back to bisection of the bracket.
        double next = sv != s_prev ? v + (z - sv) * (v - v_prev) / (sv - s_prev) : std::nan("");
        v_prev = v;
        s_prev = sv;
        if (!std::isnan(v_out)) {
          const double lo = std::min(v_in, v_out), hi = std::max(v_in, v_out);
          if (!(next > lo && next < hi)) next = (v_in + v_out) / 2;
          if (hi - lo < 1e-9 * box.scale[j]) return (v_in + v_out) / 2;
        } else if (!(side * (next - v_in) > 0)) {
          next = v_in + side * 2 * std::max(std::abs(v_in - th[j]), se);  // keep going outward
        }
        v = std::clamp(next, box.lo[j], box.hi[j]);
      }
      return std::isnan(v_out) ? v_in : (v_in + v_out) / 2;
    };
    // The profile need not be unimodal (over tau it can be rough: the pad moves in steps). Probe
    // 0.5, 1 and 2 SE beyond each end; where the profile comes back below the cut-off, search on
    // from there: the interval reported is the hull of the region below the cut-off that was found.
    double from = th[j], s_from = 0;
    for (int round = 0; round < 6; ++round) {
      end = search(from, s_from);
      if (at_bound) break;
      bool reentry = false;
      for (double k : {0.5, 1.0, 2.0}) {
        const double v = std::clamp(end + side * k * se, box.lo[j], box.hi[j]);
        if (v == end) break;
        // One evaluation at the other parameters' last values bounds the profile from below (s is
        // at most this); only a near miss pays for the re-maximisation.
        Theta x = warm;
        x[j] = v;
        const double l_fixed = evaluate(p, x).loglik;
        const double s_fixed = l_fixed > lmax ? 0.0 : std::sqrt(2 * (lmax - l_fixed));
        const double sv = s_fixed < z || s_fixed > z + 1 ? s_fixed : s_of(v);
        if (sv < z) {
          from = v;
          s_from = sv;
          reentry = true;
          out.hull = true;
          break;
        }
      }
      if (!reentry) break;
    }
  }
  return out;
}

Box make_box(const ObserverFitSettings& s, bool gamma) {
  Box b;
  b.lo = {0.0, 0.0, -kLogitMax, -kGammaMax};
  b.hi = {s.beta_max, s.tau_max, kLogitMax, kGammaMax};
  b.scale = {1.0, 0.25, 0.5, 0.05};
  b.free = {true, true, s.fit_prior, gamma};
  return b;
}

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

/// The fit of the free parameters; CIs for all of them, or only for `ci_only` (the learning test
/// needs gamma's alone; the others get NaN ends).
ObserverFit fit_problem(const Problem& p, const ObserverFitSettings& settings, std::string unit, bool gamma,
                        Theta base, std::size_t ntrials, std::size_t ci_only = kParams,
                        const std::optional<Theta>& start = std::nullopt) {
  const Box box = make_box(settings, gamma);
  // The learning model starts from the pooled fit (gamma = 0), already near its maximum; beta0 and
  // gamma are strongly correlated, so Nelder-Mead is restarted until it stops improving.
  auto learning_max = [&] {
    auto f = [&](const Theta& x) { return evaluate(p, x).loglik; };
    auto r = nelder_mead(f, base, box, box.free, 0.5, 3000);
    for (int restart = 0; restart < 5; ++restart) {
      auto r2 = nelder_mead(f, r.first, box, box.free, 0.2, 3000);
      const bool better = r2.second > r.second + 1e-6;
      if (r2.second > r.second) r = r2;
      if (!better) break;
    }
    return r;
  };
  const auto [th, lmax] = gamma ? learning_max() : global_max(p, box, base, start);
  ObserverFit fit;
  fit.unit = std::move(unit);
  fit.trials = ntrials;
  fit.samples = p.samples;
  const Likelihood at = evaluate(p, th);
  fit.log_likelihood = at.loglik;
  fit.sigma = at.sigma;
  fit.phi = at.phi;
  fit.prior_right = box.free[kPrior] ? logistic(th[kPrior]) : settings.prior_right;
  const auto ses = standard_errors(p, box, th, lmax);
  for (std::size_t j = 0; j < kParams; ++j) {
    if (!box.free[j]) {
      if (j == kPrior) {
        fit.parameters.push_back({"prior_right", settings.prior_right, settings.prior_right,
                                  settings.prior_right, false, false});
      }
      continue;
    }
    Interval ci{std::nan(""), std::nan(""), false, false, false};
    if (ci_only == kParams || ci_only == j) {
      ci = profile_interval(p, box, th, lmax, j, settings.level, ses);
    }
    if (ci.hull) {
      fit.notes.push_back(fmt::format(
          "{}: the profile likelihood of {} is not unimodal; its CI is the hull of the region within the "
          "cut-off",
          fit.unit, kNames[j]));
    }
    fit.parameters.push_back(estimate_of(j, th, ci));
  }
  // Fixed prior: listed for completeness but not a fitted parameter.
  if (!box.free[kPrior]) {
    fit.parameters.erase(std::remove_if(fit.parameters.begin(), fit.parameters.end(),
                                        [](const ParameterEstimate& e) { return e.name == "prior_right"; }),
                         fit.parameters.end());
  }
  const double btol = 1e-3;
  if (th[kBeta] >= settings.beta_max - btol) {
    fit.notes.push_back(fmt::format(
        "{}: beta is at the upper bound {} (the pad follows whichever side the path leans to at once); "
        "beta is not identified above it, and its CI is closed at the bound",
        fit.unit, settings.beta_max));
  } else if (th[kBeta] <= btol) {
    fit.notes.push_back(fmt::format("{}: beta is at 0: the pad does not follow the robot's path (belief = "
                                    "prior); tau is then not identified",
                                    fit.unit));
  }
  if (th[kTau] >= settings.tau_max - btol) {
    fit.notes.push_back(fmt::format("{}: tau is at the upper bound {} s; its CI is closed at the bound",
                                    fit.unit, settings.tau_max));
  }
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
  ObserverFit fit = fit_problem(p, settings, std::move(unit), false,
                                Theta{1.0, 0.0, prior_logit(settings.prior_right), 0.0}, trials.size(), kParams,
                                from);
  if (!trials.empty()) fit.condition = trials.front().condition;
  return fit;
}

LearningTest test_learning(std::span<const ObservedTrial> trials, const ObserverFitSettings& settings,
                           const ObserverFit& pooled) {
  settings.validate();
  const Problem p = prepare(trials, settings);
  const Theta base{pooled.parameter("beta").estimate, pooled.parameter("tau").estimate,
                   prior_logit(pooled.observer().prior_right), 0.0};
  const ObserverFit with = fit_problem(p, settings, pooled.unit, true, base, trials.size(), kGamma);
  LearningTest lt;
  lt.condition = pooled.unit;
  lt.gamma = with.parameter("gamma");
  lt.beta0 = with.parameter("beta").estimate;
  lt.log_likelihood0 = pooled.log_likelihood;
  lt.log_likelihood1 = std::max(with.log_likelihood, pooled.log_likelihood);
  lt.statistic = 2 * (lt.log_likelihood1 - lt.log_likelihood0);
  lt.p_value = boost::math::cdf(boost::math::complement(boost::math::chi_squared(1.0), lt.statistic));
  return lt;
}

}  // namespace feint::models

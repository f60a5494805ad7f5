// The optimisers of the observer fit (observer_optimise.hpp, docs/observer.md "Estimation and
// CIs"): they see the log-likelihood only through the objective f.
#include "observer_optimise.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/tools/minima.hpp>

namespace feint::models::detail::observer {

Theta clamp(Theta th, const Box& b) {
  for (std::size_t j = 0; j < kParams; ++j) th[j] = std::clamp(th[j], b.lo[j], b.hi[j]);
  return th;
}

/// Nelder & Mead (1965) on the free coordinates (standard coefficients 1, 2, 1/2, 1/2), every point
/// projected into the box. Maximises f; returns the best point and its value.
std::pair<Theta, double> nelder_mead(const Objective& f, Theta start, const Box& box,
                                     const std::array<bool, kParams>& free, double step_factor, int max_evals) {
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
std::optional<std::pair<Theta, double>> parabolic_max(const Objective& f, Theta th, std::size_t k, double h,
                                                      const Box& box, double settle, double* curvature) {
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
    if (curvature) *curvature = 2 * curv;
    // Vertex of the parabola through the three points, kept within 3 h of the centre.
    const double xv = std::clamp((x0 + x1) / 2 - d01 / (2 * curv), b - 3 * h, b + 3 * h);
    auto cand = at(xv);
    for (const auto& q : pt)  // a known point beats the vertex: take it (its value is known too)
      if (q.second > cand.second) cand = {point(q.first), q.second};
    const double moved = std::abs(cand.first[k] - b);
    if (cand.second >= best.second) best = cand;
    if (moved < settle * h) return best;
    h = std::max(moved, 0.1 * h);
  }
  return best;
}

/// Maximises over the free parameters other than `fixed` (kParams = none fixed), from `start`;
/// `h` is the step of the parabolic search (an SE of that parameter) when exactly one is free.
std::pair<Theta, double> maximise(const Objective& f, const Box& box, const Theta& start, std::size_t fixed,
                                  bool warm, const Theta& h) {
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

/// The observed information at the maximum by central differences (points kept in the box).
StandardErrors standard_errors(const Objective& f, const Box& box, const Theta& th, double l0) {
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
  const double fc = c == th ? l0 : f(c);
  auto at = [&](std::size_t a, double sa, std::size_t b, double sb) {
    Theta y = c;
    y[idx[a]] += sa * h[idx[a]];
    if (b < d) y[idx[b]] += sb * h[idx[b]];
    return f(y);
  };
  for (std::size_t a = 0; a < d; ++a) {
    H(a, a) = (at(a, 1, d, 0) - 2 * fc + at(a, -1, d, 0)) / (h[idx[a]] * h[idx[a]]);
    for (std::size_t b = a + 1; b < d; ++b) {
      H(a, b) = H(b, a) = (at(a, 1, b, 1) - at(a, 1, b, -1) - at(a, -1, b, 1) + at(a, -1, b, -1)) /
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

/// Grid steps of SE/4 that a rough profile is scanned beyond an end (up to 100 SE, or the bound).
constexpr int kHullScanSteps = 400;

namespace {

/// Thrown by a profile search that meets a point higher than the maximum (caught in
/// profile_interval, which returns it): the CI of a maximum that is not the global one is void.
struct FoundHigher {
  Theta th;
  double value;
};

/// One end of a profile interval (side -1: low, +1: high) of parameter j. Each end solves
/// s(v) = z for s(v) = side * r(v), the signed root deviance r(v) = sign(v - th_j) sqrt(2 (lmax -
/// l_p(v))) seen outward; the secant search, the probes beyond an end and the hull scan share the
/// warm start of the re-maximisations and whether the end reached the parameter's bound.
class ProfileEnd {
 public:
  ProfileEnd(const Objective& f, const Box& box, const Theta& th, double lmax, std::size_t j,
             int side, double z, double se, const Theta& step, const StandardErrors& ses)
      : f_(f),
        box_(box),
        th_(th),
        lmax_(lmax),
        j_(j),
        side_(side),
        z_(z),
        se_(se),
        step_(step),
        ses_(ses),
        bound_(side < 0 ? box.lo[j] : box.hi[j]),
        warm_(th) {}

  /// The end; `hull` (shared by both ends of the interval) is set when the profile came back below
  /// the cut-off beyond a first crossing, and then makes either end scan on to its bound.
  double locate(bool& hull) {
    double end = hull_of_probes(hull);
    // A rough profile (it came back below the cut-off beyond an end): the probes reach only 2 SE
    // further, so scan on to the bound on a grid of SE/4, re-maximised at each point, and search on
    // from every point found below the cut-off: the hull then covers every region the grid meets.
    if (hull && !at_bound_) end = scan_to_bound(end);
    return end;
  }

  bool at_bound() const { return at_bound_; }

 private:
  // s(v): 0 at the maximum, increasing outward; the end is s = z.
  double s_of(double v) {
    Theta x = warm_;
    x[j_] = v;
    // Start the re-maximisation on the ridge: the others moved as the quadratic approximation
    // predicts from the last point (at most 3 conditional SEs), so that it needs fewer steps.
    for (std::size_t k = 0; k < kParams; ++k) {
      if (k == j_ || ses_.ridge[j_][k] == 0) continue;
      const double move =
          std::clamp(ses_.ridge[j_][k] * (v - warm_[j_]), -3 * step_[k], 3 * step_[k]);
      x[k] = std::clamp(warm_[k] + move, box_.lo[k], box_.hi[k]);
    }
    const auto r = maximise(f_, box_, x, j_, true, step_);
    if (r.second > lmax_ + kHigherTolerance) throw FoundHigher{r.first, r.second};
    if (r.second > lmax_) return 0.0;  // within the maximum's tolerance: inside the interval
    warm_ = r.first;
    return std::sqrt(2 * (lmax_ - r.second));
  }

  // One search outward from a point inside (s < z) to the crossing s = z: secant steps, kept inside
  // a bracket once one is known (bisection otherwise), to |s - z| < 1e-3.
  double search(double from, double s_from) {
    const double lo_j = box_.lo[j_], hi_j = box_.hi[j_];
    double v_in = from;           // inside: s < z
    double v_out = std::nan("");  // outside: s >= z (once known)
    double v_prev = from, s_prev = s_from;
    double v = std::clamp(from + side_ * std::max(z_ - s_from, 0.1) * se_, lo_j, hi_j);
    for (int iter = 0; iter < 40; ++iter) {
      const double sv = s_of(v);
      if (sv < z_)
        v_in = v;
      else
        v_out = v;
      if (std::abs(sv - z_) < 1e-3) return v;
      if (std::isnan(v_out) && v == bound_) {
        at_bound_ = true;
        return bound_;
      }
      // Secant on (v_prev, s_prev), (v, sv); fall back to bisection of the bracket.
      double next = sv != s_prev ? v + (z_ - sv) * (v - v_prev) / (sv - s_prev) : std::nan("");
      v_prev = v;
      s_prev = sv;
      if (!std::isnan(v_out)) {
        const double lo = std::min(v_in, v_out), hi = std::max(v_in, v_out);
        if (!(next > lo && next < hi)) next = (v_in + v_out) / 2;
        if (hi - lo < 1e-9 * box_.scale[j_]) return (v_in + v_out) / 2;
      } else if (!(side_ * (next - v_in) > 0)) {
        next = v_in + side_ * 2 * std::max(std::abs(v_in - th_[j_]), se_);  // keep going outward
      }
      v = std::clamp(next, lo_j, hi_j);
    }
    return std::isnan(v_out) ? v_in : (v_in + v_out) / 2;
  }

  // The profile need not be unimodal (over tau it can be rough: the pad moves in steps). Probe
  // 0.5, 1 and 2 SE beyond each end; where the profile comes back below the cut-off, search on
  // from there: the interval reported is the hull of the region below the cut-off that was found.
  double hull_of_probes(bool& hull) {
    double from = th_[j_], s_from = 0, end = from;
    for (int round = 0; round < 6; ++round) {
      end = search(from, s_from);
      if (at_bound_) break;
      if (!probe_beyond(end, from, s_from)) break;
      hull = true;
    }
    return end;
  }

  // The first probe beyond `end` below the cut-off, as the next search's start (from, s_from).
  bool probe_beyond(double end, double& from, double& s_from) {
    for (double k : {0.5, 1.0, 2.0}) {
      const double v = std::clamp(end + side_ * k * se_, box_.lo[j_], box_.hi[j_]);
      if (v == end) break;
      // One evaluation at the other parameters' last values bounds the profile from below (s is
      // at most this); only a near miss pays for the re-maximisation.
      Theta x = warm_;
      x[j_] = v;
      const double l_fixed = f_(x);
      if (l_fixed > lmax_ + kHigherTolerance) throw FoundHigher{x, l_fixed};
      const double s_fixed = l_fixed > lmax_ ? 0.0 : std::sqrt(2 * (lmax_ - l_fixed));
      const double sv = s_fixed < z_ || s_fixed > z_ + 1 ? s_fixed : s_of(v);
      if (sv < z_) {
        from = v;
        s_from = sv;
        return true;
      }
    }
    return false;
  }

  double scan_to_bound(double end) {
    double v = end;
    for (int k = 0; k < kHullScanSteps && v != bound_; ++k) {
      v = std::clamp(v + side_ * se_ / 4, box_.lo[j_], box_.hi[j_]);
      const double sv = s_of(v);
      if (sv < z_) {
        end = search(v, sv);
        if (at_bound_) break;
        v = end;
      }
    }
    return end;
  }

  const Objective& f_;
  const Box& box_;
  const Theta& th_;
  const double lmax_;
  const std::size_t j_;
  const int side_;
  const double z_, se_;
  const Theta& step_;
  const StandardErrors& ses_;
  const double bound_;
  Theta warm_;
  bool at_bound_ = false;
};

}  // namespace

/// Profile-likelihood interval of parameter j around the maximum (th, lmax). Each end solves
/// r(v) = +-z for the signed root deviance r(v) = sign(v - th_j) sqrt(2 (lmax - l_p(v))), which is
/// close to linear in v: secant steps from the Wald end, kept inside a bracket once one is known
/// (bisection otherwise), to |r - z| < 1e-3 (the deviance within ~0.004 of chi2_1(level)).
Interval profile_interval(const Objective& f, const Box& box, const Theta& th, double lmax, std::size_t j,
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
    if (th[j] == bound) {
      end = bound;
      at_bound = true;
      continue;
    }
    ProfileEnd pe(f, box, th, lmax, j, side, z, se, step, ses);
    try {
      end = pe.locate(out.hull);
    } catch (const FoundHigher& h) {
      out.higher = std::pair{h.th, h.value};
      return out;
    }
    at_bound = pe.at_bound();
  }
  return out;
}

namespace {

/// One point of the profile over the scanned parameter: its value v, the others' maximiser and
/// the log-likelihood there.
struct ScanPoint {
  double v;
  Theta th;
  double value;
};

class Scan {
 public:
  Scan(const Objective& f, const Box& box, const ScanPlan& plan) : f_(f), box_(box), plan_(plan), h_(plan.h) {}

  /// The profile at v from the warm start (its j set to v). Quick (on the grids): parabolas that
  /// settle to half a step, enough to rank the grid's points; otherwise (the refinement) to 5 %.
  /// At an anchor, coordinate k is also restarted from each of plan.restarts that starts higher.
  ScanPoint at(double v, Theta warm, bool quick) {
    warm[plan_.j] = std::clamp(v, box_.lo[plan_.j], box_.hi[plan_.j]);
    auto r = quick ? quick_max(warm) : maximise(f_, box_, warm, plan_.j, true, h_);
    const bool anchor = std::any_of(plan_.anchors.begin(), plan_.anchors.end(),
                                    [&](double a) { return std::abs(a - v) < plan_.coarse / 2; });
    if (anchor && box_.free[plan_.k]) {
      for (double restart : plan_.restarts) {
        Theta y = warm;
        y[plan_.k] = std::clamp(restart, box_.lo[plan_.k], box_.hi[plan_.k]);
        if (f_(y) <= r.second) continue;
        const auto r2 = maximise(f_, box_, y, plan_.j, true, h_);
        if (r2.second > r.second) r = r2;
      }
    }
    return {warm[plan_.j], r.first, r.second};
  }

  /// The coarse grid over j's range, each point started where the last two predict (linearly).
  std::vector<ScanPoint> coarse(const Theta& base) {
    const double lo = box_.lo[plan_.j], hi = box_.hi[plan_.j];
    const int n = std::max(1, static_cast<int>(std::ceil((hi - lo) / plan_.coarse - 1e-9)));
    std::vector<ScanPoint> out;
    for (int i = 0; i <= n; ++i) {
      const double v = std::min(hi, lo + i * plan_.coarse);
      Theta guess = out.empty() ? base : out.back().th;
      if (out.size() >= 2) {
        const ScanPoint &p1 = out[out.size() - 1], &p2 = out[out.size() - 2];
        for (std::size_t k = 0; k < kParams; ++k) {
          if (k == plan_.j || !box_.free[k]) continue;
          const double move = (p1.th[k] - p2.th[k]) * (v - p1.v) / (p1.v - p2.v);
          guess[k] = std::clamp(p1.th[k] + std::clamp(move, -3 * h_[k], 3 * h_[k]), box_.lo[k], box_.hi[k]);
        }
      }
      out.push_back(at(v, guess, true));
    }
    return out;
  }

  /// The fine grid inside every coarse interval near the best (see ScanPlan); each point started
  /// between its interval's ends' maximisers.
  std::vector<ScanPoint> fine(const std::vector<ScanPoint>& coarse) {
    std::vector<ScanPoint> pts;
    std::size_t best = 0;
    for (std::size_t i = 1; i < coarse.size(); ++i)
      if (coarse[i].value > coarse[best].value) best = i;
    for (std::size_t i = 0; i + 1 < coarse.size(); ++i) {
      const double top = std::max(coarse[i].value, coarse[i + 1].value);
      if (top < coarse[best].value - plan_.near && i != best && i + 1 != best) continue;
      const ScanPoint &a = coarse[i], &b = coarse[i + 1];
      const int m = static_cast<int>(std::ceil((b.v - a.v) / plan_.fine - 1e-9));
      for (int k = 1; k < m; ++k) {
        const double w = static_cast<double>(k) / m;
        Theta guess = a.th;
        for (std::size_t q = 0; q < kParams; ++q) guess[q] = a.th[q] + w * (b.th[q] - a.th[q]);
        pts.push_back(at(a.v + w * (b.v - a.v), guess, true));
      }
    }
    return pts;
  }

  /// Brent's method on the profile between lo and hi, from the warm start th; the best point seen.
  ScanPoint brent(double lo, double hi, const ScanPoint& from) {
    ScanPoint best = from;
    Theta warm = from.th;
    auto g = [&](double v) {
      const ScanPoint p = at(v, warm, false);
      warm = p.th;
      if (p.value > best.value) best = p;
      return -p.value;
    };
    std::uintmax_t iters = 40;
    boost::math::tools::brent_find_minima(g, lo, hi, 14, iters);
    return best;
  }

  /// The re-maximised parameters at p's value of j to within ~1e-6 of the profile: parabolas a
  /// fifth of a step wide (less bias from the profile's third derivative) until they move less
  /// than 0.2 % of that, twice over.
  ScanPoint polish(ScanPoint p) {
    for (int cycle = 0; cycle < 2; ++cycle) {
      for (std::size_t k = 0; k < kParams; ++k) {
        if (k == plan_.j || !box_.free[k]) continue;
        const auto r = parabolic_max(f_, p.th, k, 0.2 * h_[k], box_, 0.002);
        if (r && r->second > p.value) {
          p.th = r->first;
          p.value = r->second;
        }
      }
    }
    return p;
  }

 private:
  // Parabolas per re-maximised parameter until one moves less than half a step, the step the last
  // parabola's conditional SE (1 / sqrt(-l'')); the full search where a parabola is not concave.
  std::pair<Theta, double> quick_max(Theta x) {
    double fx = 0;
    for (std::size_t k = 0; k < kParams; ++k) {
      if (k == plan_.j || !box_.free[k]) continue;
      double curv = 0;
      const auto r = parabolic_max(f_, x, k, h_[k], box_, 0.5, &curv);
      if (!r) return maximise(f_, box_, x, plan_.j, true, h_);
      x = r->first;
      fx = r->second;
      h_[k] = std::clamp(1 / std::sqrt(-curv), 1e-4 * box_.scale[k], 0.5 * box_.scale[k]);
    }
    return {x, fx};
  }

  const Objective& f_;
  const Box& box_;
  const ScanPlan& plan_;
  Theta h_;
};

}  // namespace

std::pair<Theta, double> scan_maximum(const Objective& f, const Box& box, const Theta& base, const ScanPlan& plan,
                                      const std::vector<Theta>& starts) {
  Scan scan(f, box, plan);
  std::vector<ScanPoint> pts = scan.coarse(base);
  const std::vector<ScanPoint> fine = scan.fine(pts);
  pts.insert(pts.end(), fine.begin(), fine.end());
  for (const Theta& s : starts) pts.push_back(scan.at(s[plan.j], s, true));
  std::sort(pts.begin(), pts.end(), [](const ScanPoint& a, const ScanPoint& b) { return a.v < b.v; });
  double top = -std::numeric_limits<double>::infinity();
  for (const auto& p : pts) top = std::max(top, p.value);
  // The grid's local maxima near the best, highest first.
  std::vector<std::size_t> peaks;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const bool left = i == 0 || pts[i].value >= pts[i - 1].value;
    const bool right = i + 1 == pts.size() || pts[i].value >= pts[i + 1].value;
    if (left && right && pts[i].value >= top - plan.refine_within) peaks.push_back(i);
  }
  if (peaks.empty()) {  // only when every value is NaN: no point is better than another
    return {pts.front().th, pts.front().value};
  }
  std::sort(peaks.begin(), peaks.end(), [&](std::size_t a, std::size_t b) { return pts[a].value > pts[b].value; });
  if (peaks.size() > static_cast<std::size_t>(plan.max_refined)) peaks.resize(static_cast<std::size_t>(plan.max_refined));
  // Each side of a peak separately: two maxima can sit within one grid step, one on either side.
  ScanPoint best = pts[peaks.front()];
  for (std::size_t i : peaks) {
    for (std::size_t n : {i - 1, i + 1}) {
      if (n >= pts.size() || pts[n].v == pts[i].v) continue;  // (i - 1 wraps at i = 0)
      const ScanPoint r = scan.brent(std::min(pts[i].v, pts[n].v), std::max(pts[i].v, pts[n].v), pts[i]);
      if (r.value > best.value) best = r;
    }
  }
  best = scan.polish(best);
  return {best.th, best.value};
}

}  // namespace feint::models::detail::observer

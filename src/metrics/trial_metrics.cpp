#include "feint/metrics/trial_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "finite_score.hpp"
#include "time_scale.hpp"
#include "feint/io/number.hpp"

namespace feint::metrics {

std::string to_string(ConfusionNorm norm) { return norm == ConfusionNorm::speed ? "speed" : "raw"; }

std::optional<ConfusionNorm> parse_confusion_norm(std::string_view text) {
  const std::string s = io::to_lower(io::trim(text));
  if (s == "speed") return ConfusionNorm::speed;
  if (s == "raw") return ConfusionNorm::raw;
  return std::nullopt;
}

void MetricSettings::validate() const {
  auto fraction_ok = [](double f) { return std::isfinite(f) && f >= 0 && f < 1; };
  if (!fraction_ok(trim_start)) {
    throw UsageError(fmt::format("--trim-start: {} is outside [0, 1) (a fraction of the trial's "
                                 "duration)", trim_start));
  }
  if (!fraction_ok(trim_end)) {
    throw UsageError(fmt::format("--trim-end: {} is outside [0, 1) (a fraction of the trial's "
                                 "duration)", trim_end));
  }
  if (!(trim_start + trim_end < 1)) {
    throw UsageError(fmt::format("--trim-start + --trim-end = {} must be < 1 (nothing would be "
                                 "left of the trial)", trim_start + trim_end));
  }
  if (!(std::isfinite(belief_deadband) && belief_deadband >= 0 && belief_deadband < 0.5)) {
    throw UsageError(fmt::format("--belief-deadband: {} must be in [0, 0.5) (pad units: a lean "
                                 "from the middle smaller than this is no side)", belief_deadband));
  }
  if (!std::isfinite(deadband) || deadband < 0) {
    throw UsageError(fmt::format("--deadband: {} must be a finite number >= 0 (pad units)",
                                 deadband));
  }
  if (pad_speed && !(std::isfinite(*pad_speed) && *pad_speed > 0)) {
    throw UsageError(fmt::format("--pad-speed: {} must be a finite number > 0 (pad units per "
                                 "second)", *pad_speed));
  }
}

namespace detail {

// Integral of |g(x)| over [x0, x1] for g linear from g0 to g1: a trapezoid, or two triangles when
// g changes sign inside (metrics.md: exact, no quadrature).
inline double abs_linear_integral(double g0, double g1, double h) {
  if ((g0 >= 0 && g1 >= 0) || (g0 <= 0 && g1 <= 0)) return 0.5 * (std::fabs(g0) + std::fabs(g1)) * h;
  const double a0 = std::fabs(g0), a1 = std::fabs(g1);
  return 0.5 * h * (a0 * a0 + a1 * a1) / (a0 + a1);
}

// The belief-trace measures of docs/metrics.md, accumulated inside score_trace's two loops over
// the samples (no pass of their own: they cost a few operations per sample). Times are in
// score_trace's scaled unit (2^-k s since t0).
class BeliefAccumulator {
 public:
  BeliefAccumulator(double target, double delta, double first_pad)
      : defined_(target != 0.5), sigma_(target < 0.5 ? 1.0 : -1.0), target_(target),
        delta_(delta), lo_(first_pad), hi_(first_pad), ext_(first_pad) {}

  // Flips (whole trace): a hysteresis. Before the first move beyond delta the direction is unknown
  // and the lowest and highest positions so far are kept; then `ext_` is the extreme reached in
  // the current direction, and a move of more than delta back from it is a flip.
  void sample(double m) noexcept {
    if (dir_ > 0) {
      if (m > ext_) {
        ext_ = m;
      } else if (ext_ - m > delta_) {
        ++flips_;
        dir_ = -1;
        ext_ = m;
      }
    } else if (dir_ < 0) {
      if (m < ext_) {
        ext_ = m;
      } else if (m - ext_ > delta_) {
        ++flips_;
        dir_ = 1;
        ext_ = m;
      }
    } else {
      lo_ = std::min(lo_, m);
      hi_ = std::max(hi_, m);
      if (m - lo_ > delta_) {
        dir_ = 1;
        ext_ = m;
      } else if (hi_ - m > delta_) {
        dir_ = -1;
        ext_ = m;
      }
    }
  }

  // One segment clipped to the window: [lo, hi] with the pad going from m0 to m1 (linear).
  void window_segment(double lo, double hi, double m0, double m1) noexcept {
    const double l0 = sigma_ * (m0 - 0.5), l1 = sigma_ * (m1 - 0.5);  // lean toward the false side
    max_lean_ = std::max(max_lean_, std::max(l0, l1));
    const double h = hi - lo;
    if (!(h > 0)) return;
    area_ += 0.5 * sigma_ * ((m0 - target_) + (m1 - target_)) * h;  // exact: linear integrand
    const double g0 = l0 - delta_, g1 = l1 - delta_;                 // > 0: deceived
    if (g0 > 0 && g1 > 0) {
      deceived_ += h;
    } else if (g0 > 0 || g1 > 0) {  // one crossing inside: the part on the positive side
      deceived_ += h * (g0 > 0 ? g0 : g1) / std::fabs(g1 - g0);
    }
  }

  // Writes the five measures; `w(i)` is sample i's scaled time, [a, b] the window, 2^k the unit.
  template <class W>
  void finish(std::span<const double> pads, W w, double a, double b, int k, TrialScore& s) const {
    s.flips = flips_;
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    if (!defined_) {  // T = 1/2: no false side, every side-based measure is undefined
      s.signed_area = s.max_deviation = s.time_deceived = s.final_belief_time = nan;
      return;
    }
    // + 0.0: a lean of sigma * 0 is -0 for sigma = -1; a score is never written as "-0".
    s.signed_area = std::clamp(area_ / (b - a), -1.0, 1.0) + 0.0;
    s.max_deviation = max_lean_ + 0.0;
    s.time_deceived = std::clamp(deceived_ / (b - a), 0.0, 1.0);
    // Final correct belief (whole trace): r = -lean - delta > 0 on the true side beyond delta.
    // Scanned back from the end, so it costs the length of the final stretch only.
    const std::size_t n = pads.size();
    auto r = [&](std::size_t i) { return -sigma_ * (pads[i] - 0.5) - delta_; };
    if (!(r(n - 1) > 0)) {
      s.final_belief_time = nan;
      return;
    }
    std::size_t i = n - 1;
    while (i > 0 && r(i - 1) > 0) --i;
    if (i == 0) {
      s.final_belief_time = 0;  // on the true side from the first sample on
      return;
    }
    // r(i - 1) <= 0 < r(i): the crossing inside segment i - 1 (at its start when r(i - 1) == 0).
    const double r0 = r(i - 1), r1 = r(i);
    const double x = w(i - 1) + (w(i) - w(i - 1)) * (-r0 / (r1 - r0));
    s.final_belief_time = std::ldexp(x, k);
  }

 private:
  bool defined_;
  double sigma_, target_, delta_;
  double lo_, hi_, ext_;
  int dir_ = 0;
  int flips_ = 0;
  double area_ = 0, deceived_ = 0;
  double max_lean_ = -std::numeric_limits<double>::infinity();
};

}  // namespace detail

namespace {

// Throws unless the trace can be scored: as many pad positions as times, at least 2 samples, the
// target and every pad in [0, 1], the times finite and strictly increasing.
void check_trace(std::span<const double> times, std::span<const double> pads, double target) {
  const std::size_t n = times.size();
  if (pads.size() != n) {
    throw InvalidData(fmt::format("{} times but {} pad positions", n, pads.size()));
  }
  if (n < 2) throw InvalidData(fmt::format("{} sample(s); a trial needs at least 2", n));
  if (!(std::isfinite(target) && target >= 0 && target <= 1)) {
    throw InvalidData(fmt::format("target {} is outside [0, 1]", target));
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(times[i])) throw InvalidData(fmt::format("sample {}: time is not finite", i));
    if (!(std::isfinite(pads[i]) && pads[i] >= 0 && pads[i] <= 1)) {
      throw InvalidData(fmt::format("sample {}: pad {} is outside [0, 1]", i, pads[i]));
    }
    if (i > 0 && !(times[i] > times[i - 1])) {
      throw InvalidData(fmt::format("sample {}: time {} is not after {} (times must strictly "
                                    "increase)", i, times[i], times[i - 1]));
    }
  }
}

// The pad speed v the trial is scored with (the settings' overrides the trial's), checked; empty
// when unknown, which only the raw confusion allows.
std::optional<double> checked_pad_speed(std::optional<double> pad_speed,
                                        const MetricSettings& settings) {
  const std::optional<double> v = settings.pad_speed ? settings.pad_speed : pad_speed;
  if (v && !(std::isfinite(*v) && *v > 0)) {
    throw InvalidData(fmt::format("pad speed {} must be > 0 (pad units per second)", *v));
  }
  if (settings.norm == ConfusionNorm::speed && !v) {
    throw InvalidData("the pad speed is unknown: the 'speed' confusion normalisation needs it "
                      "(give --pad-speed V, a pad_speed column, or use --confusion-norm raw)");
  }
  return v;
}

// tau in seconds, checked (> 0 and finite).
double checked_duration(std::span<const double> times) {
  const double t0 = times[0];
  const double duration = times[times.size() - 1] - t0;
  if (!std::isfinite(duration)) {
    throw InvalidData(fmt::format("duration ({} - {} s) is not a finite number",
                                  times[times.size() - 1], t0));
  }
  if (!(duration > 0)) throw InvalidData(fmt::format("duration {} must be > 0", duration));
  return duration;
}

struct Directions {
  std::size_t rev_segment;  // the first segment against the first direction; n when none
  int reversals = 0;
  int overspeed_segments;  // -1 when v is unknown
};

// First pass over the segments (the whole trace): each one's direction (dead band eps) gives the
// first reversal and the reversals; the speeds give the overspeed segments; the belief
// accumulator sees every sample for its flips.
Directions scan_directions(std::span<const double> times, std::span<const double> pads,
                           double eps, std::optional<double> v,
                           detail::BeliefAccumulator& belief) {
  const std::size_t n = times.size();
  std::size_t rev_segment = n;
  int reversals = 0;
  int overspeed_segments = v ? 0 : -1;
  int first_dir = 0;
  int last_dir = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    belief.sample(pads[i + 1]);
    const double d = pads[i + 1] - pads[i];
    const int dir = d > eps ? 1 : (d < -eps ? -1 : 0);
    if (dir != 0) {
      if (first_dir == 0) first_dir = dir;
      if (dir == -first_dir && rev_segment == n) rev_segment = i;
      if (last_dir != 0 && dir != last_dir) ++reversals;
      last_dir = dir;
    }
    if (v) {
      const double speed = std::fabs(d) / (times[i + 1] - times[i]);
      if (speed > *v * (1 + kOverspeedTolerance)) ++overspeed_segments;
    }
  }
  return {rev_segment, reversals, overspeed_segments};
}

struct WindowIntegrals {
  double error = 0;   // integral of |T - mu| over [a, b]
  double moving = 0;  // M (speed) or the raw sum over [c, b]
};

// Second pass, over the segments inside the window [a, b] (scaled time): the exact error integral,
// the time-weighted movement after the first reversal, and the belief accumulator's window part.
WindowIntegrals integrate_window(const detail::ScaledTime& w, std::span<const double> pads,
                                 double target, double a, double b, std::size_t rev_segment,
                                 ConfusionNorm norm, std::optional<double> v,
                                 detail::BeliefAccumulator& belief) {
  const std::span<const double> times = w.times;
  const std::size_t n = times.size();
  auto mu_at = [&](std::size_t i, double x) {  // mu at w = x inside segment i
    const double x0 = w(i), x1 = w(i + 1);
    if (x <= x0) return pads[i];
    if (x >= x1) return pads[i + 1];
    return pads[i] + (pads[i + 1] - pads[i]) * ((x - x0) / (x1 - x0));
  };
  WindowIntegrals r;
  const double c = rev_segment < n ? std::max(a, w(rev_segment)) : b;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double x0 = w(i), x1 = w(i + 1);
    if (x1 <= a) continue;
    if (x0 >= b) break;
    const double lo = std::max(x0, a), hi = std::min(x1, b);
    const double m_lo = mu_at(i, lo), m_hi = mu_at(i, hi);
    if (hi > lo) r.error += detail::abs_linear_integral(target - m_lo, target - m_hi, hi - lo);
    belief.window_segment(lo, hi, m_lo, m_hi);
    if (rev_segment < n) {
      const double cs = std::max(x0, c), ce = std::min(x1, b);
      if (ce > cs) {
        // dt > 0, so the speed is never NaN; it may be +inf (dt near the smallest double), which
        // is full speed for 'speed' and makes the raw confusion infinite (rejected below).
        const double seg_speed = std::fabs(pads[i + 1] - pads[i]) / (times[i + 1] - times[i]);
        const double weight = 0.5 * (ce * ce - cs * cs);  // integral of w over [cs, ce]
        const double rate = norm == ConfusionNorm::speed ? std::min(1.0, seg_speed / *v)
                                                         : seg_speed;
        r.moving += rate * weight;
      }
    }
  }
  return r;
}

}  // namespace

TrialScore score_trace(std::span<const double> times, std::span<const double> pads, double target,
                       std::optional<double> pad_speed, const MetricSettings& settings) {
  check_trace(times, pads, target);
  const std::optional<double> v = checked_pad_speed(pad_speed, settings);
  const std::size_t n = times.size();
  const double duration = checked_duration(times);
  const detail::ScaledTime w = detail::scaled_time(times, duration);
  const double tau = w(n - 1);
  const double a = settings.trim_start * tau;
  const double b = (1 - settings.trim_end) * tau;

  TrialScore s;
  s.n_samples = n;
  s.duration = duration;
  s.final_pad = pads[n - 1];
  detail::BeliefAccumulator belief(target, settings.belief_deadband, pads[0]);
  const Directions dirs = scan_directions(times, pads, settings.deadband, v, belief);
  s.reversals = dirs.reversals;
  s.overspeed_segments = dirs.overspeed_segments;
  s.reversal_time = dirs.rev_segment < n ? times[dirs.rev_segment] - w.t0
                                         : std::numeric_limits<double>::quiet_NaN();

  const WindowIntegrals in =
      integrate_window(w, pads, target, a, b, dirs.rev_segment, settings.norm, v, belief);
  // Rounding can push a mean of values in [0, 1] an ulp outside; the true values cannot be.
  s.error = std::clamp(in.error / (b - a), 0.0, 1.0);
  if (settings.norm == ConfusionNorm::speed) {
    const double denom = 0.5 * (b * b - a * a);
    s.confusion = std::clamp(in.moving / denom, 0.0, 1.0);
  } else {
    // moving / tau in seconds: the 2^-k of the weights (squared) and of tau (once) leave one.
    s.confusion = std::ldexp(in.moving / tau, w.k);
  }
  belief.finish(pads, w, a, b, w.k, s);
  detail::reject_non_finite(s);
  return s;
}

TrialScore score_trial(const io::Trial& trial, const MetricSettings& settings) {
  try {
    return score_trace(trial.times, trial.pads, trial.target, trial.pad_speed, settings);
  } catch (const InvalidData& e) {
    throw InvalidData(fmt::format("{}:{}: {} (trial {})", trial.file, trial.line, e.what(),
                                  trial.label()));
  }
}

}  // namespace feint::metrics

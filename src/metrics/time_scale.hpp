// time_scale.hpp - sample times in a power-of-two unit (private to the metrics module; shared by
// the pad scorer, trial_metrics.cpp, and the pointer scorer, belief_point.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

namespace feint::metrics::detail {

// Sample i's time as w = t - t0 (the time weight of metrics.md), so that the result does not
// depend on where the clock started, in units of 2^-k s with 2^k <= tau < 2^(k+1): multiplying by a
// power of two is exact, so ordinary durations give bit for bit the seconds' result, while 1e-300 s
// or 1e263 s no longer underflow or overflow in the squared time weights (w^2 / 2).
struct ScaledTime {
  std::span<const double> times;
  double t0;
  int k;
  double s1, s2;  // 2^-k = s1 s2
  double operator()(std::size_t i) const noexcept { return (times[i] - t0) * s1 * s2; }
};

// `duration` = tau = times.back() - times.front(), finite and > 0.
inline ScaledTime scaled_time(std::span<const double> times, double duration) {
  const int k = std::ilogb(duration);
  // 2^-k as one or two factors (2^1074 for the smallest subnormal duration is not a double); a
  // multiplication, not std::ldexp, which is a library call in the hot loop.
  const int k1 = std::clamp(-k, -1000, 1000);
  return {times, times[0], k, std::ldexp(1.0, k1), std::ldexp(1.0, -k - k1)};
}

}  // namespace feint::metrics::detail

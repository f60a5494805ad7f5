// feint/metrics/trial_metrics.hpp - the two per-trial metrics of the seed paper (section VI):
// trimmed error (eq. 3) and time-weighted confusion (eq. 4), as fixed by docs/metrics.md (from the project spec).
//
// Trace: samples (t_i, mu_i), mu(t) piecewise linear between them, t0 = t_0, tau = t_{n-1} - t0.
// Window: a = t0 + f_s tau, b = t0 + (1 - f_e) tau.
//
//   error      E = 1/(b - a) * integral_a^b |T - mu(t)| dt          (exact: trapezoids, split where
//                                                                     T - mu changes sign)
//   confusion  counted on [c, b], c = max(a, t_rev), t_rev = start of the first segment moving
//              against the first movement (dead band eps); w(t) = t - t0;
//     speed:   M / D,  M = sum m_i (w(e_i)^2 - w(s_i)^2)/2,  m_i = min(1, |dmu_i|/dt_i / v),
//                      D = (w(b)^2 - w(a)^2)/2                       (in [0, 1])
//     raw:     1/tau * sum |dmu_i|/dt_i * (w(e_i)^2 - w(s_i)^2)/2    (the paper's eq. 4 literally)
//   No reversal: confusion = 0.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "feint/io/trace.hpp"

namespace feint::metrics {

/// How confusion is normalised (metrics.md): `speed` (default, in [0, 1]) or `raw` (eq. 4 as
/// printed, unbounded, for comparison with the paper).
enum class ConfusionNorm { speed, raw };

/// "speed" / "raw".
std::string to_string(ConfusionNorm norm);
/// Parses "speed" / "raw" (case-insensitive); nullopt otherwise.
std::optional<ConfusionNorm> parse_confusion_norm(std::string_view text);

/// Relative tolerance above the pad speed before a segment counts as overspeed (metrics.md).
inline constexpr double kOverspeedTolerance = 1e-6;

struct MetricSettings {
  double trim_start = 0.05;  // f_s: fraction of tau cut at the start, in [0, 1)
  double trim_end = 0.05;    // f_e: fraction of tau cut at the end, in [0, 1); f_s + f_e < 1
  double deadband = 1e-9;    // eps (pad units): |dmu| <= eps is "no direction"
  ConfusionNorm norm = ConfusionNorm::speed;
  /// Pad speed v (pad units per second) for every trial; overrides Trial::pad_speed.
  std::optional<double> pad_speed;

  /// Throws UsageError when a setting is out of range (each message names the option).
  void validate() const;
};

struct TrialScore {
  std::size_t n_samples = 0;
  double duration = 0;       // tau, seconds
  double error = 0;          // E in [0, 1]
  double confusion = 0;      // speed: [0, 1]; raw: pad units (unbounded)
  double reversal_time = 0;  // t_rev - t0 in seconds; NaN when the pad never reverses
  int reversals = 0;         // direction changes among the non-zero segment directions
  double final_pad = 0;      // mu_{n-1}
  /// Segments faster than v (1 + 1e-6), over the whole trace; -1 when v is unknown (raw norm).
  int overspeed_segments = 0;
};

/// Scores one trace. `pad_speed` is used only when `settings.pad_speed` is empty. Throws
/// InvalidData (message without file/line: the loader already checked them) when n < 2, a time is
/// not strictly increasing, a value is not finite or outside [0, 1], or v is needed but unknown
/// or not > 0.
TrialScore score_trace(std::span<const double> times, std::span<const double> pads, double target,
                       std::optional<double> pad_speed, const MetricSettings& settings);

/// Scores a loaded trial; errors are prefixed with the trial's file, line and label.
TrialScore score_trial(const io::Trial& trial, const MetricSettings& settings);

}  // namespace feint::metrics

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
//
// Belief-trace measures (docs/metrics.md "Belief-trace measures"; mousetrap-style), with the false
// side sigma = +1 when T < 1/2, -1 when T > 1/2 (undefined, so empty, when T = 1/2), the lean
// toward the false target g(t) = sigma (mu(t) - 1/2) and the belief dead band delta:
//   signed_area        1/(b - a) * integral_a^b sigma (mu(t) - T) dt        (exact trapezoids)
//   max_deviation      max over [a, b] of g(t)                               (in [-1/2, 1/2])
//   flips              direction changes of mu over the whole trace, a change counting only once
//                      the pad has moved more than delta back from its last extreme (hysteresis)
//   time_deceived      1/(b - a) * |{t in [a, b] : g(t) > delta}|            (crossings interpolated)
//   final_belief_time  the last time (s since t0) at which -g(t) rises above delta for good (the pad
//                      reaches the true side beyond the dead band and stays there to the end);
//                      empty when the trace ends inside the dead band or on the false side.
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
  /// delta (pad units) of the belief-trace measures: flips smaller than this are ignored, and the
  /// pad counts as on a side of 1/2 only beyond it (time_deceived, final_belief_time). In [0, 1/2).
  double belief_deadband = 0.05;
  ConfusionNorm norm = ConfusionNorm::raw;
  /// Pad speed v (pad units per second) for every trial; overrides Trial::pad_speed.
  std::optional<double> pad_speed;

  /// Throws UsageError when a setting is out of range (each message names the option).
  void validate() const;
};

/// A pointer trial's mousetrap measures (docs/pointer-measures.md "In the scores table"): distances
/// in layout scales, times in seconds since the trial's first sample.
struct PointerColumns {
  double auc = 0;              // AUC: signed area between the pointer's path and its direct path
  double mad = 0;              // MAD: signed maximum absolute deviation from the direct path
  double mad_time = 0;         // MAD_time
  int xpos_flips = 0;          // direction changes along x
  int ypos_flips = 0;          // direction changes along y
  double initiation_time = 0;  // last time before the pointer leaves its first position
  double idle_time = 0;        // time without movement
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
  // Belief-trace measures (see the top of this file). NaN = not defined (written empty): every one
  // but flips when T = 1/2; final_belief_time also when the pad does not end on the true side.
  double signed_area = 0;        // mean signed distance from T toward the false side, [-1, 1]
  double max_deviation = 0;      // largest lean toward the false target past 1/2, [-1/2, 1/2]
  int flips = 0;                 // direction changes larger than the belief dead band
  double time_deceived = 0;      // share of the window on the false side beyond the dead band
  double final_belief_time = 0;  // seconds since t0
  /// Logs of K targets and a pointer only (empty for pad trials).
  std::optional<PointerColumns> pointer;
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

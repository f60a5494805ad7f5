// feint/metrics/pointer_measures.hpp - pointer-trace (mouse-tracking) measures as the R package
// mousetrap (Kieslich, Henninger, Wulff, Haslbeck & Schulte-Mecklenbeck 2019) defines them in
// mt_measures, with the preprocessing it documents: mt_remap_symmetric, mt_align_start,
// mt_derivatives and mt_time_normalize, each with mousetrap's default arguments.
//
// A pointer trace is one trial's samples (t, x, y) (mousetrap's timestamps, xpos, ypos), t strictly
// increasing. The definitions, formulas and mousetrap's quirks that are kept on purpose are in
// docs/pointer-measures.md; the values agree with mousetrap 3.2.3.9000's own R code on its data set
// KH2017 (tests/golden/pointer/).
//
// Pipeline as mousetrap documents it for KH2017:
//   align_start(remap_symmetric(trace))  ->  pointer_measures(...)
//   time_normalize(...) for the 101-step traces that averages and AD over time are taken on.
#pragma once

#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

namespace feint::metrics {

/// One sample of a pointer trace: timestamp and position (mousetrap: timestamps, xpos, ypos).
struct PointerSample {
  double t = 0;
  double x = 0;
  double y = 0;
};

/// Where mt_remap_symmetric sends a trace's end point: x to the left (default) or right, y up
/// (default) or down, or leaves the axis alone (no).
enum class RemapX { left, right, no };
enum class RemapY { up, down, no };

/// mt_remap_symmetric: mirrors the whole trace in x when its last x lies on the wrong side of 0
/// (> 0 for left, < 0 for right), and in y likewise (< 0 for up, > 0 for down). Throws
/// InvalidData for a bad trace (see pointer_measures).
std::vector<PointerSample> remap_symmetric(std::span<const PointerSample> trace,
                                           RemapX remap_x = RemapX::left,
                                           RemapY remap_y = RemapY::up);

/// mt_align_start: shifts the trace so that its first sample is at (start_x, start_y).
std::vector<PointerSample> align_start(std::span<const PointerSample> trace, double start_x = 0,
                                       double start_y = 0);

/// mt_time_normalize: `nsteps` samples at equally spaced times from the first to the last
/// timestamp, x and y (and t) interpolated linearly as R's approx() does. nsteps >= 2 (UsageError).
std::vector<PointerSample> time_normalize(std::span<const PointerSample> trace, int nsteps = 101);

/// mt_deviations: each sample's orthogonal projection on the direct path (the straight line from
/// the first to the last sample) and its signed distance from it (positive above the path, see
/// docs/pointer-measures.md). When the first and last samples coincide the projection is the
/// start itself (mousetrap's fallback), so the deviations are distances from the start.
struct PointerDeviations {
  std::vector<double> x_ideal, y_ideal, dev_ideal;
};
PointerDeviations pointer_deviations(std::span<const PointerSample> trace);

/// mt_derivatives with its defaults: per sample, the distance from the previous sample, the
/// velocity dist / dt, and the acceleration (|v_{i+1}| - |v_i|) / dt_i; the first entry of each is
/// 0 and the last acceleration is NaN (mousetrap's NA: it has no following velocity).
struct PointerDerivatives {
  std::vector<double> dist, vel, acc;
};
PointerDerivatives pointer_derivatives(std::span<const PointerSample> trace);

/// mt_measures' arguments (its defaults; hover measures only with a hover threshold).
struct PointerMeasureSettings {
  /// A change of direction counts as a flip only when the movements on both sides of it exceed
  /// this distance (0: every change counts). >= 0.
  double flip_threshold = 0;
  /// When set, hovers / hover_time count the periods without movement longer than this. >= 0.
  std::optional<double> hover_threshold;
  /// Whether the phase before the first movement counts as a hover (mousetrap's default: yes).
  bool hover_incl_initial = true;
  /// Distance from the start that counts as the movement's initiation. >= 0.
  double initiation_threshold = 0;

  /// Throws UsageError when a threshold is negative or not finite.
  void validate() const;
};

/// mt_measures' per-trial measures, mousetrap's names in the comments. Times are in the trace's
/// timestamps (not since its first sample), as mousetrap reports them.
struct PointerMeasures {
  double xpos_max = 0, xpos_min = 0, ypos_max = 0, ypos_min = 0;
  double mad = 0;            // MAD: signed maximum absolute deviation from the direct path
  double mad_time = 0;       // MAD_time: first time it is reached
  double md_above = 0;       // MD_above: largest deviation (above the path)
  double md_above_time = 0;  // MD_above_time
  double md_below = 0;       // MD_below: smallest deviation (below the path)
  double md_below_time = 0;  // MD_below_time
  double ad = 0;             // AD: mean deviation over the samples
  double auc = 0;            // AUC: signed area between the trace and the direct path
  int xpos_flips = 0, ypos_flips = 0;          // direction changes along x / y
  int xpos_reversals = 0, ypos_reversals = 0;  // crossings of x = 0 / y = 0
  double rt = 0;                               // RT: last timestamp
  double initiation_time = 0;        // last timestamp before the initiation threshold is crossed
  double idle_time = 0;              // time without movement (see docs for mousetrap's three cases)
  std::optional<double> hover_time;  // with a hover threshold only
  std::optional<int> hovers;         // with a hover threshold only (can be -1: see docs)
  double total_dist = 0;             // total_dist: path length
  double vel_max = 0, vel_max_time = 0, vel_min = 0, vel_min_time = 0;
  double acc_max = 0, acc_max_time = 0, acc_min = 0, acc_min_time = 0;
};

/// mt_measures on one trace (with mt_derivatives' columns, as when mt_derivatives ran first).
/// Throws InvalidData when the trace has fewer than 2 samples, a non-finite value, timestamps that
/// do not increase strictly, or a negative first timestamp (on which mt_measures stops too);
/// UsageError for bad settings.
PointerMeasures pointer_measures(std::span<const PointerSample> trace,
                                 const PointerMeasureSettings& settings = {});

/// The measures as (mousetrap's column name, value), in mt_measures' column order; hover_time and
/// hovers only when they were computed.
std::vector<std::pair<std::string_view, double>> mousetrap_columns(const PointerMeasures& m);

namespace detail {

/// Throws InvalidData unless the trace has >= 2 samples, finite values and strictly increasing t.
void check_pointer_trace(std::span<const PointerSample> trace);

/// mousetrap's count_changes: sign changes between runs of same-signed non-zero steps of `pos`;
/// with a threshold > 0 only runs whose summed movement exceeds it take part.
int count_flips(std::span<const double> pos, double threshold);

}  // namespace detail

}  // namespace feint::metrics

// Scoring a trial of a log of K targets and a pointer (docs/many-targets.md "Studies of K targets"):
// error and confusion as a belief point, in the scores table's columns, and the pointer trace's
// mousetrap measures in the columns after them (docs/pointer-measures.md "In the scores table").
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/metrics/belief_point.hpp"
#include "feint/metrics/pointer_measures.hpp"
#include "feint/metrics/trial_layout.hpp"
#include "score_detail.hpp"

namespace feint::metrics::detail {

namespace {

// The pointer trace in the frame the measures are read in: the robot's start at the origin,
// distances in layout scales (so that trials of layouts drawn per round compare), time since the
// trial's first sample (as mousetrap's importer makes it); then mousetrap's preprocessing for
// KH2017, align_start(remap_symmetric(.)), with its defaults.
PointerMeasures measures_of(const io::Trial& t, const Layout& layout) {
  const double s = layout_scale(layout);
  std::vector<PointerSample> trace(t.times.size());
  for (std::size_t i = 0; i < trace.size(); ++i) {
    trace[i] = {t.times[i] - t.times.front(), (t.belief_x[i] - layout.start.x) / s,
                (t.belief_y[i] - layout.start.y) / s};
  }
  return pointer_measures(align_start(remap_symmetric(trace)), PointerMeasureSettings{});
}

}  // namespace

const std::vector<std::string>& pointer_score_columns() {
  static const std::vector<std::string> cols = {"auc",        "mad",        "mad_time",       "xpos_flips",
                                                "ypos_flips", "initiation_time", "idle_time"};
  return cols;
}

// final_pad and the pad's belief-trace measures are not defined for a point (written empty; flips
// 0); `target` is the true target's index.
TrialScore score_pointer_trial(const io::Trial& t, const MetricSettings& m) {
  const Layout layout = trial_layout(t);
  std::vector<MapPoint> points(t.belief_x.size());
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = {t.belief_x[i], t.belief_y[i]};
  BeliefPointScore b;
  PointerMeasures mt;
  try {
    b = score_belief_points(t.times, points, layout, t.target_index, t.pad_speed, m);
    mt = measures_of(t, layout);
  } catch (const InvalidData& e) {
    throw InvalidData(fmt::format("{}:{}: {} (trial {})", t.file, t.line, e.what(), t.label()));
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  TrialScore s;
  s.n_samples = b.n_samples;
  s.duration = b.duration;
  s.error = b.error;
  s.confusion = b.confusion;
  s.reversal_time = b.reversal_time;
  s.reversals = b.reversals;
  s.final_pad = nan;
  s.overspeed_segments = b.overspeed_segments;
  s.signed_area = s.max_deviation = s.time_deceived = s.final_belief_time = nan;
  s.flips = 0;
  s.pointer = PointerColumns{mt.auc, mt.mad, mt.mad_time, mt.xpos_flips, mt.ypos_flips, mt.initiation_time,
                             mt.idle_time};
  return s;
}

}  // namespace feint::metrics::detail

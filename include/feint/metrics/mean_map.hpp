// feint/metrics/mean_map.hpp - the data of the map of a study of K targets and a pointer
// (docs/figures.md "The map"): the start, the targets, and per strategy and version the mean robot
// path and the mean pointer (the participants' belief as a point) over normalised time.
//
// Two cases, decided by the trials themselves:
//  - one fixed layout (every trial has the same start and targets): the map in metres, with one
//    mean robot path and one mean pointer per true target;
//  - layouts drawn per round: positions differ per trial, so each trial is first mapped by the
//    similarity transform that puts its start at (0, 0) and its true target at (0, 1), mirrored
//    so that its nearest decoy by bearing lies to the left (canonical_frame); the means are taken
//    there, and the decoys of the trials are drawn as faint points.
// Paths are time-normalised as mousetrap does (time_normalize, kMapPoints points from the first to
// the last sample) and averaged point by point.
//
// The analysis reads the logs once for it (mean_map, into analysis::FigureData::map); plot draws
// the MeanMap (feint/plot/map_figure.hpp) and reads no file.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "feint/io/scores.hpp"
#include "feint/io/trace.hpp"
#include "feint/metrics/layout.hpp"

namespace feint::metrics {

/// Normalised times of a mean path: u = 0, 1/100, ..., 1 (mousetrap's 101 steps).
inline constexpr std::size_t kMapPoints = 101;

/// The similarity transform of one trial into the canonical frame: p -> mirror(R (p - start) / L)
/// with L = |true target - start| and R the rotation that turns the true target's direction to +y.
/// With d = true target - start and v = p - start:
///   x = s (v.x d.y - v.y d.x) / |d|^2,   y = (v.x d.x + v.y d.y) / |d|^2,
/// s = -1 when `mirrored`, else +1. So start -> (0, 0), true target -> (0, 1), distances shrink by
/// L, angles are kept. `mirrored` is set when the trial's nearest decoy by bearing (the decoy whose
/// direction from the start is closest to the true target's, lowest index on ties) would land at
/// x > 0: it then lies to the left, as mousetrap's mt_remap_symmetric puts every trace's end on
/// the left, so that feints toward it add up instead of cancelling.
struct CanonicalFrame {
  MapPoint start;
  MapPoint direction;  ///< true target - start
  bool mirrored = false;
  MapPoint operator()(MapPoint p) const noexcept;
};
/// Throws InvalidData when `true_target` is not a target of the layout or sits at the start.
CanonicalFrame canonical_frame(const Layout& layout, std::size_t true_target);

/// One trial as the map needs it (times strictly increasing, at least 2 samples; pointer and robot
/// positions in metres, one per time; robot empty when the log has no robot path).
struct MapTrial {
  std::string strategy, variant;
  Layout layout;
  std::size_t true_target = 0;
  std::vector<double> times;
  std::vector<double> pointer_x, pointer_y;
  std::vector<double> robot_x, robot_y;
};

/// A trial of a log of K targets (io::PointerTraceReader) as a MapTrial: its layout as the log
/// wrote it (trial_layout), its true target, belief and robot path. The trial's vectors are moved.
MapTrial map_trial(io::Trial&& trial);

/// A path at kMapPoints normalised times: time_normalize of (times, x, y).
/// Throws InvalidData for sizes that differ or a trace time_normalize refuses.
std::vector<MapPoint> normalised_path(const std::vector<double>& times,
                                      const std::vector<double>& x, const std::vector<double>& y);

/// The mean paths of the trials with one true target (fixed layout), or of all trials of a panel
/// (canonical frame: true_target is then that of no particular layout, 0).
struct MapMean {
  std::size_t true_target = 0;
  std::size_t trials = 0;  ///< trials the mean pointer rests on
  /// Of them, the trials with a robot path (the mean robot path rests on these).
  std::size_t robot_trials = 0;
  std::vector<MapPoint> pointer;  ///< kMapPoints points
  std::vector<MapPoint> robot;    ///< kMapPoints points; empty when robot_trials == 0
};

/// One strategy and version.
struct MapPanel {
  std::string strategy, variant;
  std::size_t trials = 0;
  std::vector<MapMean> means;  ///< fixed layout: per true target, ascending; canonical: one
  /// Canonical frame: the decoys of the panel's trials, in trial order (empty for a fixed layout).
  std::vector<MapPoint> decoys;
};

/// The map's data: what the figure draws, as plain values.
struct MeanMap {
  bool canonical = false;  ///< layouts drawn per round: everything is in the canonical frame
  /// Fixed: the study's layout (m). Canonical: start (0, 0) and the true target (0, 1) only.
  Layout layout;
  std::size_t targets = 0;  ///< K (the largest seen)
  std::size_t layouts = 0;  ///< distinct layouts among the trials
  std::size_t trials = 0;
  std::size_t mirrored = 0;      ///< canonical: trials mirrored (nearest decoy brought to the left)
  std::vector<MapPanel> panels;  ///< by strategy, then version (sorted)
};

/// Averages trials one at a time. Memory: per (strategy, version, true target) two sums of
/// kMapPoints points in metres and in the canonical frame, and the canonical decoys.
class MapAccumulator {
 public:
  /// Throws InvalidData for a trial whose sizes differ, that time_normalize refuses, or whose true
  /// target is not a target of its layout (nothing is added then).
  void add(const MapTrial& trial);
  /// The map: canonical when the trials had more than one layout.
  MeanMap data() const;

 private:
  struct Sums {
    std::size_t n = 0, n_robot = 0;
    std::vector<MapPoint> pointer = std::vector<MapPoint>(kMapPoints);
    std::vector<MapPoint> robot = std::vector<MapPoint>(kMapPoints);
  };
  using Key = std::tuple<std::string, std::string, std::size_t>;  // strategy, version, target
  std::map<Key, Sums> metres_;
  std::map<Key, Sums> canonical_;  // target always 0
  std::map<std::pair<std::string, std::string>, std::vector<MapPoint>> decoys_;
  std::set<std::vector<double>> layouts_;  // distinct (start, targets), as read
  Layout first_;
  std::size_t trials_ = 0, mirrored_ = 0, targets_ = 0;
};

/// The map of the scored trials of `log_files` (as io::expand_inputs returns them): the logs are
/// streamed once through io::PointerTraceReader with `options` (trials the reader rejects are
/// skipped: the scorer has judged them), and a trial is averaged when `scored` has a record of
/// its (participant, condition, iteration), so that the map rests on the trials the tables rest
/// on. nullopt when the logs are not of K targets and a pointer (io::is_pointer_log of the first
/// file; no file, or `-`): a pad study has no map. A MeanMap with trials == 0 when no scored trial
/// was found in the logs. Throws what the reader throws (IoError, InvalidData, UsageError) and
/// InvalidData for a trial MapAccumulator::add refuses.
std::optional<MeanMap> mean_map(const std::vector<std::string>& log_files, io::TraceOptions options,
                                const io::ScoresTable& scored);

}  // namespace feint::metrics

// feint/metrics/layout.hpp - where the robot starts and where its K >= 2 targets stand on the
// study's map (docs/many-targets.md "Layouts").
//
// The seed paper's study has two targets in a row above the start; its closing words ask for "a
// multi-target environment with targets placed randomly on the map". A Layout is one round's map:
// the robot's start and the targets, in metres. It is either fixed for the study or drawn per round
// from a region with a minimum spacing (draw_layout, seeded, so a study is reproducible).
//
// The two-target layout of the paper (paper_layout) is the default everywhere; its target 0 is the
// left target (pad 0) and target 1 the right one (pad 1).
#pragma once

#include <cstddef>
#include <vector>

#include "feint/rng.hpp"

namespace feint::metrics {

/// A point on the study's map (metres; x to the right, y away from the participant).
struct MapPoint {
  double x = 0;
  double y = 0;
};

/// One round's map: the robot's start and its K >= 2 targets (target k is "target k" in the logs).
struct Layout {
  MapPoint start;
  std::vector<MapPoint> targets;
};

/// The rectangle targets are drawn from, and the spacing rules every layout must keep.
struct LayoutRegion {
  double x_min = -3.0;
  double x_max = 3.0;
  double y_min = 2.0;
  double y_max = 5.0;
  double min_spacing = 1.0;         // least distance between two targets (m), > 0
  double min_start_distance = 1.0;  // least distance between the start and a target (m), > 0
};

/// The paper's layout: start (0, 0), targets (-d/2, h) (left, pad 0) and (d/2, h) (right, pad 1).
/// Throws UsageError unless d > 0 and both are finite.
Layout paper_layout(double target_distance = 4.0, double target_height = 4.0);

/// Distance between two points (std::hypot: no overflow or underflow in the squares).
double distance(MapPoint a, MapPoint b) noexcept;

/// The layout's scale: the largest distance between two of its targets (at K = 2, the distance
/// between the two targets, which the 1-D pad maps to 1). Scores of belief points are in this unit.
/// 0 when the layout has fewer than two targets.
double layout_scale(const Layout& layout) noexcept;

/// The target nearest to `p` (the lowest index among equally near ones). The layout must have a
/// target.
std::size_t nearest_target(const Layout& layout, MapPoint p) noexcept;

/// Throws UsageError saying what to change when: K < 2; a coordinate is not finite; two targets
/// are closer than `min_spacing` (names both targets and their distance); a target is closer than
/// `min_start_distance` to the start. Two targets at one point, or a target at the start, are
/// refused even with a minimum of 0 (a layout's points are distinct). The minimums must be finite
/// and >= 0 (UsageError otherwise).
void validate(const Layout& layout, double min_spacing, double min_start_distance);

/// Throws UsageError saying what to change when the region is empty (x_min > x_max or
/// y_min > y_max; a zero width is a line of targets and allowed), not finite, or a spacing is not
/// positive.
void validate(const LayoutRegion& region);

/// K targets drawn uniformly from `region` by rejection: each draw is x = x_min + (x_max - x_min) u1,
/// y = y_min + (y_max - y_min) u2 with u1, u2 the next two Rng::uniform() values, and is kept when
/// it keeps min_spacing to the targets before it and min_start_distance to `start`. A target that
/// fails max(1, max_tries / 10) draws in a row starts the layout over (the targets before it may
/// have left no room). At most `max_tries` draws in all: a region too small for K targets is a
/// UsageError that says so, never a hang. The region is checked first (validate, then Oler's bound
/// K <= 2 A / (sqrt(3) m^2) + P / (2 m) + 1 for points m apart in a rectangle of area A and
/// perimeter P, and whether any point of it is far enough from the start), so an impossible request
/// fails at once. The same (seed, region, k, start, max_tries) give the same layout on any machine.
Layout draw_layout(Rng& rng, const LayoutRegion& region, std::size_t k, MapPoint start = {},
                   std::size_t max_tries = 100000);

}  // namespace feint::metrics

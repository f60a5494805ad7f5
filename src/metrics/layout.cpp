#include "feint/metrics/layout.hpp"
#include "feint/metrics/trial_layout.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::metrics {

namespace {

bool finite(MapPoint p) noexcept { return std::isfinite(p.x) && std::isfinite(p.y); }

// A measured distance for a message: two decimals, unless that would print it as the minimum it
// falls short of (0.999 against 1 reads "1.00 m ... less than 1 m"); then every digit.
std::string metres(double d, double minimum) {
  if (d < minimum && std::round(d * 100) / 100 >= minimum) return fmt::format("{}", d);
  return fmt::format("{:.2f}", d);
}

void check_minimum(const char* name, double value) {
  if (!(std::isfinite(value) && value >= 0)) {
    throw UsageError(fmt::format("{} {} must be a finite number >= 0 (metres)", name, value));
  }
}

void check_spacing(const Layout& layout, double min_spacing) {
  const auto& g = layout.targets;
  for (std::size_t i = 0; i < g.size(); ++i) {
    for (std::size_t j = i + 1; j < g.size(); ++j) {
      const double d = distance(g[i], g[j]);
      if (d == 0) {
        throw UsageError(fmt::format("targets {} and {} are at the same point ({}, {}): move them "
                                     "apart (a layout's targets are distinct)",
                                     i, j, g[i].x, g[i].y));
      }
      if (d < min_spacing) {
        throw UsageError(fmt::format("targets {} and {} are {} m apart, less than the minimum "
                                     "spacing {} m: move them apart or lower min_spacing",
                                     i, j, metres(d, min_spacing), min_spacing));
      }
    }
  }
}

void check_start_distance(const Layout& layout, double min_start_distance) {
  for (std::size_t k = 0; k < layout.targets.size(); ++k) {
    const double d = distance(layout.start, layout.targets[k]);
    if (d == 0) {
      throw UsageError(fmt::format("target {} is at the start (0.00 m from it; at least {} m): "
                                   "move the target or the start", k, min_start_distance));
    }
    if (d < min_start_distance) {
      throw UsageError(fmt::format("target {} is {} m from the start, less than the minimum {} m: "
                                   "move it away from the start or lower min_start_distance",
                                   k, metres(d, min_start_distance), min_start_distance));
    }
  }
}

std::string region_text(const LayoutRegion& r) {
  return fmt::format("[{}, {}] x [{}, {}] m", r.x_min, r.x_max, r.y_min, r.y_max);
}

// Refuses at once what no number of draws can give: more targets than Oler's bound lets points
// min_spacing apart into the rectangle (Oler 1961: N <= 2A/sqrt(3) + P/2 + 1 for points at
// distance >= 1 in a compact convex set; exact for a segment), or a region every point of which
// is too close to the start.
void check_room(const LayoutRegion& r, std::size_t k, MapPoint start) {
  const double w = r.x_max - r.x_min, h = r.y_max - r.y_min, m = r.min_spacing;
  const double most = 2 * w * h / (std::sqrt(3.0) * m * m) + (w + h) / m + 1;
  if (static_cast<double>(k) > most * (1 + 1e-12)) {
    throw UsageError(fmt::format(
        "the region {} is too small for K = {} targets at least {} m apart (at most {} fit, by "
        "Oler's bound): enlarge the region, lower min_spacing or use fewer targets",
        region_text(r), k, m, static_cast<long long>(std::floor(most * (1 + 1e-12)))));
  }
  const double far_x = std::max(std::fabs(r.x_min - start.x), std::fabs(r.x_max - start.x));
  const double far_y = std::max(std::fabs(r.y_min - start.y), std::fabs(r.y_max - start.y));
  if (std::hypot(far_x, far_y) < r.min_start_distance) {
    throw UsageError(fmt::format(
        "every point of the region {} is closer than min_start_distance {} m to the start ({}, "
        "{}): move the region away from the start or lower min_start_distance",
        region_text(r), r.min_start_distance, start.x, start.y));
  }
}

}  // namespace

Layout paper_layout(double target_distance, double target_height) {
  if (!(std::isfinite(target_distance) && target_distance > 0)) {
    throw UsageError(fmt::format("target distance {} must be a finite number > 0 (metres)",
                                 target_distance));
  }
  if (!std::isfinite(target_height)) {
    throw UsageError(fmt::format("target height {} must be a finite number (metres)",
                                 target_height));
  }
  const double half = target_distance / 2;
  return {{0, 0}, {{-half, target_height}, {half, target_height}}};
}

double distance(MapPoint a, MapPoint b) noexcept { return std::hypot(b.x - a.x, b.y - a.y); }

double layout_scale(const Layout& layout) noexcept {
  double s = 0;
  const auto& g = layout.targets;
  for (std::size_t i = 0; i < g.size(); ++i) {
    for (std::size_t j = i + 1; j < g.size(); ++j) s = std::max(s, distance(g[i], g[j]));
  }
  return s;
}

std::size_t nearest_target(const Layout& layout, MapPoint p) noexcept {
  std::size_t best = 0;
  for (std::size_t k = 1; k < layout.targets.size(); ++k) {
    if (distance(p, layout.targets[k]) < distance(p, layout.targets[best])) best = k;
  }
  return best;
}

void validate(const Layout& layout, double min_spacing, double min_start_distance) {
  check_minimum("min_spacing", min_spacing);
  check_minimum("min_start_distance", min_start_distance);
  const std::size_t k = layout.targets.size();
  if (k < 2) {
    throw UsageError(fmt::format("K = {}: a layout needs at least two targets (add a target)", k));
  }
  if (!finite(layout.start)) {
    throw UsageError(fmt::format("the start ({}, {}) is not a finite point: give its x and y in "
                                 "metres", layout.start.x, layout.start.y));
  }
  for (std::size_t i = 0; i < k; ++i) {
    const MapPoint g = layout.targets[i];
    if (!finite(g)) {
      throw UsageError(fmt::format("target {} ({}, {}) is not a finite point: give its x and y in "
                                   "metres", i, g.x, g.y));
    }
  }
  check_spacing(layout, min_spacing);
  check_start_distance(layout, min_start_distance);
}

void validate(const LayoutRegion& r) {
  for (const auto& [name, value] : {std::pair<const char*, double>{"x_min", r.x_min},
                                    {"x_max", r.x_max}, {"y_min", r.y_min}, {"y_max", r.y_max}}) {
    if (!std::isfinite(value)) {
      throw UsageError(fmt::format("region: {} {} is not a finite number (metres)", name, value));
    }
  }
  if (r.x_min > r.x_max || r.y_min > r.y_max) {
    throw UsageError(fmt::format("region: {} is empty: give x_min <= x_max and y_min <= y_max",
                                 region_text(r)));
  }
  if (!(std::isfinite(r.x_max - r.x_min) && std::isfinite(r.y_max - r.y_min))) {
    throw UsageError(fmt::format("region: {} is too wide to draw from (its width or height is not "
                                 "a finite number)", region_text(r)));
  }
  if (!(std::isfinite(r.min_spacing) && r.min_spacing > 0)) {
    throw UsageError(fmt::format("region: min_spacing {} must be a finite number > 0 (metres): "
                                 "without it two targets may stand on one spot", r.min_spacing));
  }
  if (!(std::isfinite(r.min_start_distance) && r.min_start_distance > 0)) {
    throw UsageError(fmt::format("region: min_start_distance {} must be a finite number > 0 "
                                 "(metres): without it a target may stand on the start",
                                 r.min_start_distance));
  }
}

Layout draw_layout(Rng& rng, const LayoutRegion& region, std::size_t k, MapPoint start,
                   std::size_t max_tries) {
  validate(region);
  if (k < 2) {
    throw UsageError(fmt::format("K = {}: a layout needs at least two targets (ask for K >= 2)", k));
  }
  if (!finite(start)) {
    throw UsageError(fmt::format("the start ({}, {}) is not a finite point: give its x and y in "
                                 "metres", start.x, start.y));
  }
  if (max_tries == 0) throw UsageError("max_tries 0: drawing a layout needs at least one draw");
  check_room(region, k, start);

  const std::size_t restart_after = std::max<std::size_t>(1, max_tries / 10);
  Layout layout{start, {}};
  layout.targets.reserve(k);
  std::size_t failed_in_a_row = 0;
  for (std::size_t draws = 0; draws < max_tries; ++draws) {
    const double u1 = rng.uniform();
    const double u2 = rng.uniform();
    const MapPoint p{region.x_min + (region.x_max - region.x_min) * u1,
                     region.y_min + (region.y_max - region.y_min) * u2};
    const bool keeps = distance(p, start) >= region.min_start_distance &&
                       std::all_of(layout.targets.begin(), layout.targets.end(), [&](MapPoint g) {
                         return distance(p, g) >= region.min_spacing;
                       });
    if (keeps) {
      layout.targets.push_back(p);
      failed_in_a_row = 0;
      if (layout.targets.size() == k) return layout;
    } else if (++failed_in_a_row == restart_after) {
      layout.targets.clear();
      failed_in_a_row = 0;
    }
  }
  throw UsageError(fmt::format(
      "could not draw K = {} targets at least {} m apart and {} m from the start in the region {} "
      "within {} draws: the region is too small for {} targets at that spacing; enlarge it, lower "
      "min_spacing or min_start_distance, or use fewer targets",
      k, region.min_spacing, region.min_start_distance, region_text(region), max_tries, k));
}

}  // namespace feint::metrics

namespace feint::metrics {

Layout trial_layout(const io::Trial& t) {
  Layout layout;
  layout.start = {t.start_x, t.start_y};
  for (std::size_t k = 0; k < t.targets_x.size(); ++k) layout.targets.push_back({t.targets_x[k], t.targets_y[k]});
  return layout;
}

}  // namespace feint::metrics

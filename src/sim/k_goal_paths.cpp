// Deceptive paths among K targets (feint/sim/k_goal_paths.hpp, docs/deceptive-paths.md "Paths").
#include "feint/sim/k_goal_paths.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <utility>

#include "feint/error.hpp"

namespace feint::sim {

namespace {

Point at(const metrics::Layout& layout, std::size_t k) {
  return {layout.targets[k].x, layout.targets[k].y};
}
double dist(Point a, Point b) noexcept { return std::hypot(a.x - b.x, a.y - b.y); }

/// A strategy's frame: origin S, unit forward axis toward the centroid of some targets, unit
/// lateral axis to its right; reach = |centroid - S|.
struct Frame {
  Point origin, forward, lateral;
  double reach = 0;
};

Frame frame_of(const metrics::Layout& layout, const std::vector<std::size_t>& targets) {
  double sx = 0, sy = 0;
  for (std::size_t k : targets) {
    sx += layout.targets[k].x;
    sy += layout.targets[k].y;
  }
  const auto n = static_cast<double>(targets.size());
  const Point origin{layout.start.x, layout.start.y};
  const double dx = sx / n - origin.x, dy = sy / n - origin.y;
  const double reach = std::hypot(dx, dy);
  if (!(reach > 0)) {
    throw UsageError(
        "the targets' centroid is at the start: the paths have no forward direction; "
        "move the start or the targets");
  }
  const Point f{dx / reach, dy / reach};
  return {origin, f, {f.y, -f.x}, reach};
}

/// Frame coordinates (lateral x, forward y) of a map point, and back.
Point local(const Frame& fr, Point p) {
  const double dx = p.x - fr.origin.x, dy = p.y - fr.origin.y;
  return {dx * fr.lateral.x + dy * fr.lateral.y, dx * fr.forward.x + dy * fr.forward.y};
}
Point to_map(const Frame& fr, double x, double y) {
  return {fr.origin.x + x * fr.lateral.x + y * fr.forward.x,
          fr.origin.y + x * fr.lateral.y + y * fr.forward.y};
}

void check_index(const metrics::Layout& layout, std::size_t k, const char* what) {
  if (k >= layout.targets.size()) {
    throw UsageError(fmt::format("{} {} is out of range: the layout has {} targets (0 to {})", what,
                                 k, layout.targets.size(), layout.targets.size() - 1));
  }
}

void check_decoy(const metrics::Layout& layout, std::size_t true_target, std::size_t d) {
  check_index(layout, d, "decoy");
  if (d == true_target) {
    throw UsageError(fmt::format("decoy {} is the true target: a decoy must be another target", d));
  }
}

// A usable layout: >= 2 finite targets, distinct and away from the start, so that every direction
// and frame is defined.
void check_layout(const metrics::Layout& layout) {
  models::validate_goals(layout);
  const auto& g = layout.targets;
  for (std::size_t i = 0; i < g.size(); ++i) {
    if (metrics::distance(layout.start, g[i]) == 0) {
      throw UsageError(fmt::format("target {} is at the start: move it away", i));
    }
    for (std::size_t j = i + 1; j < g.size(); ++j) {
      if (metrics::distance(g[i], g[j]) == 0) {
        throw UsageError(
            fmt::format("targets {} and {} are at the same point: move them apart", i, j));
      }
    }
  }
}

// The checks every path needs: the layout, the true target and decoys in range, valid settings.
void check_inputs(const metrics::Layout& layout, std::size_t true_target,
                  const KGoalPathSettings& s) {
  check_layout(layout);
  check_index(layout, true_target, "true target");
  if (s.decoy) check_decoy(layout, true_target, *s.decoy);
  for (std::size_t d : s.switching_decoys) check_decoy(layout, true_target, d);
  validate(s.geometry);
  models::validate(s.observer, layout.targets.size());
}

double entropy_at(const metrics::Layout& layout, Point q, const models::GoalPosteriorObserver& o) {
  return models::entropy_bits(models::goal_posterior({layout.start.x, layout.start.y}, {q.x, q.y},
                                                     layout.targets, o.beta, o.prior));
}

// Golden-section search for the largest `f` on [a, b] (80 steps at most): the best point seen.
std::pair<double, double> golden_max(double a, double b, const std::function<double(double)>& f) {
  const double r = (std::sqrt(5.0) - 1) / 2;
  double c = b - r * (b - a), d = a + r * (b - a);
  double fc = f(c), fd = f(d);
  for (int it = 0; it < 80 && b - a > 1e-13; ++it) {
    if (fc >= fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - r * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + r * (b - a);
      fd = f(d);
    }
  }
  return fc >= fd ? std::pair{c, fc} : std::pair{d, fd};
}

// The angle in [lo, hi] where `entropy` is largest: a grid of n + 1 angles ((n - i) lo + i hi) / n,
// then golden section between the best one's neighbours. Grid angles within 1e-12 bits of the
// largest entropy tie and the one nearest 0 (the neutral direction) wins, so that a flat posterior,
// or a symmetric layout, gives that direction exactly; the refinement replaces it only when it
// gains more than 1e-12 bits.
double flattest_angle(double lo, double hi, const std::function<double(double)>& entropy) {
  constexpr int n = 720;
  constexpr double kTie = 1e-12;
  auto angle = [&](int i) {
    return (static_cast<double>(n - i) * lo + static_cast<double>(i) * hi) / n;
  };
  std::vector<double> h(n + 1);
  for (int i = 0; i <= n; ++i) h[static_cast<std::size_t>(i)] = entropy(angle(i));
  const double top = *std::max_element(h.begin(), h.end());
  int best = -1;
  for (int i = 0; i <= n; ++i) {
    if (h[static_cast<std::size_t>(i)] < top - kTie) continue;
    if (best < 0 || std::abs(angle(i)) < std::abs(angle(best))) best = i;
  }
  const auto [refined, gain] =
      golden_max(angle(std::max(best - 1, 0)), angle(std::min(best + 1, n)), entropy);
  return gain > top + kTie ? refined : angle(best);
}

// Drops a waypoint equal to the one before it (a degenerate leg of length 0).
std::vector<Point> without_repeats(const std::vector<Point>& pts) {
  std::vector<Point> out;
  for (const Point& p : pts) {
    if (out.empty() || p.x != out.back().x || p.y != out.back().y) out.push_back(p);
  }
  return out;
}

// The decoys switching visits in turn: the settings' list, or the decoy then the others by bearing.
std::vector<std::size_t> switching_sequence(const metrics::Layout& layout, std::size_t true_target,
                                            std::size_t decoy, const KGoalPathSettings& s) {
  if (!s.switching_decoys.empty()) return s.switching_decoys;
  std::vector<std::size_t> seq{decoy};
  for (std::size_t k : decoys_by_bearing(layout, true_target)) {
    if (k != decoy) seq.push_back(k);
  }
  return seq;
}

std::vector<Point> switching_corners(const metrics::Layout& layout, std::size_t true_target,
                                     const std::vector<std::size_t>& decoys, const Geometry& g) {
  std::vector<std::size_t> visited{true_target};
  visited.insert(visited.end(), decoys.begin(), decoys.end());
  const Frame fr = frame_of(layout, visited);
  double w = 0;  // the widest lateral offset among the targets visited
  for (std::size_t k : visited) w = std::max(w, std::abs(local(fr, at(layout, k)).x));
  std::vector<Point> pts;
  for (int j = 1; j <= g.zigzag_corners; ++j) {
    const std::size_t heads_for =
        (j % 2 == 1) ? decoys[static_cast<std::size_t>((j - 1) / 2) % decoys.size()]
                     : true_target;  // a decoy first, as the paper's false side
    const double x = w > 0 ? g.zigzag_width * (local(fr, at(layout, heads_for)).x / w) : 0.0;
    pts.push_back(to_map(fr, x, g.zigzag_height * fr.reach * j / g.zigzag_corners));
  }
  return pts;
}

// The main (version 1) path of one of the paper's strategies against `decoy`.
std::vector<Point> main_waypoints(const metrics::Layout& layout, std::size_t true_target,
                                  Strategy s, std::size_t decoy,
                                  const std::vector<std::size_t>& switching,
                                  const KGoalPathSettings& settings) {
  const Geometry& g = settings.geometry;
  std::vector<Point> pts{{layout.start.x, layout.start.y}};
  switch (s) {
    case Strategy::optimal:
      break;
    case Strategy::exaggerating: {
      const Frame fr = frame_of(layout, {true_target, decoy});
      const Point d = local(fr, at(layout, decoy));
      pts.push_back(to_map(fr, g.exaggeration_x * d.x, g.exaggeration_y * d.y));
      break;
    }
    case Strategy::switching: {
      const auto corners = switching_corners(layout, true_target, switching, g);
      pts.insert(pts.end(), corners.begin(), corners.end());
      break;
    }
    case Strategy::ambiguous:
      pts.push_back(ambiguous_point(layout, g.ambiguous_height, settings.observer));
      break;
  }
  pts.push_back(at(layout, true_target));
  return pts;
}

// The point of the arc of radius rho around S, between the outermost targets' bearings seen from S
// (angles from the frame's forward axis), where the observer's posterior is flattest; ties go to
// the forward axis (flattest_angle).
Point flattest_on_arc(const metrics::Layout& layout, const Frame& fr, double rho,
                      const models::GoalPosteriorObserver& observer) {
  double lo = 0, hi = 0;
  for (std::size_t k = 0; k < layout.targets.size(); ++k) {
    const Point p = local(fr, at(layout, k));
    const double phi = std::atan2(p.x, p.y);  // positive toward the lateral axis
    lo = k == 0 ? phi : std::min(lo, phi);
    hi = k == 0 ? phi : std::max(hi, phi);
  }
  auto point = [&](double phi) { return to_map(fr, rho * std::sin(phi), rho * std::cos(phi)); };
  return point(
      flattest_angle(lo, hi, [&](double a) { return entropy_at(layout, point(a), observer); }));
}

// Drops an interior waypoint that lies exactly on the straight line on from the one before (the
// same path with one corner fewer).
std::vector<Point> without_straight_corners(const std::vector<Point>& pts) {
  std::vector<Point> out;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!out.empty() && i + 1 < pts.size()) {
      const Point a = out.back(), b = pts[i], c = pts[i + 1];
      const double cross = (b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x);
      const double dot = (b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y);
      if (cross == 0 && dot > 0) continue;
    }
    out.push_back(pts[i]);
  }
  return out;
}

}  // namespace

std::vector<std::size_t> decoys_by_bearing(const metrics::Layout& layout, std::size_t true_target) {
  check_layout(layout);
  check_index(layout, true_target, "true target");
  const Point s{layout.start.x, layout.start.y}, g = at(layout, true_target);
  const double heading = std::atan2(g.y - s.y, g.x - s.x);
  std::vector<std::pair<double, std::size_t>> by_angle;
  for (std::size_t k = 0; k < layout.targets.size(); ++k) {
    if (k == true_target) continue;
    const Point d = at(layout, k);
    const double turn =
        std::remainder(std::atan2(d.y - s.y, d.x - s.x) - heading, 2 * std::numbers::pi);
    by_angle.emplace_back(std::abs(turn), k);
  }
  std::sort(by_angle.begin(), by_angle.end());  // by angle, then by index
  std::vector<std::size_t> out;
  for (const auto& e : by_angle) out.push_back(e.second);
  return out;
}

std::size_t nearest_bearing_decoy(const metrics::Layout& layout, std::size_t true_target) {
  return decoys_by_bearing(layout, true_target).front();
}

LastDeceptivePoint masters_ldp(const metrics::Layout& layout, std::size_t true_target,
                               std::optional<std::size_t> decoy) {
  check_layout(layout);
  check_index(layout, true_target, "true target");
  if (decoy) check_decoy(layout, true_target, *decoy);
  const Point s{layout.start.x, layout.start.y}, g = at(layout, true_target);
  LastDeceptivePoint best;
  bool found = false;
  for (std::size_t k = 0; k < layout.targets.size(); ++k) {
    if (k == true_target || (decoy && k != *decoy)) continue;
    const Point b = at(layout, k);
    // The rmp of Masters & Sardina: where cost differences to b and G* are equal on b -> G*.
    const double rmp = (dist(b, g) + dist(s, g) - dist(s, b)) / 2;
    if (!found || rmp < best.radius) best = {k, rmp, {}}, found = true;
  }
  const Point b = at(layout, best.decoy);
  const double len = dist(b, g);
  best.point = {g.x + best.radius * ((b.x - g.x) / len), g.y + best.radius * ((b.y - g.y) / len)};
  return best;
}

Point ambiguous_point(const metrics::Layout& layout, double ambiguous_height,
                      const models::GoalPosteriorObserver& observer) {
  check_layout(layout);
  models::validate(observer, layout.targets.size());
  if (!(ambiguous_height > 0 && ambiguous_height < 1)) {
    throw UsageError(
        fmt::format("geometry: ambiguous_height must be in (0, 1), got {}", ambiguous_height));
  }
  std::vector<std::size_t> all(layout.targets.size());
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = k;
  const Frame fr = frame_of(layout, all);
  return flattest_on_arc(layout, fr, ambiguous_height * fr.reach, observer);
}

std::vector<Point> k_goal_waypoints(const metrics::Layout& layout, std::size_t true_target,
                                    Strategy s, Variant v, const KGoalPathSettings& settings) {
  check_inputs(layout, true_target, settings);
  const std::size_t decoy = settings.decoy.value_or(nearest_bearing_decoy(layout, true_target));
  if (v == Variant::main) {
    return main_waypoints(layout, true_target, s, decoy,
                          switching_sequence(layout, true_target, decoy, settings), settings);
  }
  if (s == Strategy::optimal) throw UsageError("the optimal strategy has no version 2");
  // v2: the main path as if the decoy were the true target and the true target its decoy, turning
  // to the true target v2_turn_remaining metres before that path's end ("at the last moment").
  const auto as_if = main_waypoints(layout, decoy, s, true_target, {true_target}, settings);
  return turn_before_end(as_if, settings.geometry.v2_turn_remaining, at(layout, true_target));
}

std::vector<Point> deceptive_waypoints(const metrics::Layout& layout, std::size_t true_target,
                                       DeceptivePlan plan, const KGoalPathSettings& settings) {
  check_inputs(layout, true_target, settings);
  const LastDeceptivePoint ldp = masters_ldp(layout, true_target, settings.decoy);
  const Point s{layout.start.x, layout.start.y}, t = ldp.point, g = at(layout, true_target);
  const double to_t = dist(s, t);
  if (plan == DeceptivePlan::simulation || !(to_t > 0)) return without_repeats({s, t, g});
  // Dissimulation: first to the flattest point at ambiguous_height of the way to t, bearings
  // measured from the direction of t (ties, and a flat posterior, head straight for t).
  const Point ahead{(t.x - s.x) / to_t, (t.y - s.y) / to_t};
  const Frame fr{s, ahead, {ahead.y, -ahead.x}, to_t};
  const Point w =
      flattest_on_arc(layout, fr, settings.geometry.ambiguous_height * to_t, settings.observer);
  return without_straight_corners(without_repeats({s, w, t, g}));
}

std::vector<TrajectorySample> k_goal_trajectory(const metrics::Layout& layout,
                                                std::size_t true_target, Strategy s, Variant v,
                                                const KGoalPathSettings& settings) {
  return sample_polyline(k_goal_waypoints(layout, true_target, s, v, settings),
                         settings.geometry.speed, settings.geometry.sample_rate);
}

std::vector<TrajectorySample> deceptive_trajectory(const metrics::Layout& layout,
                                                   std::size_t true_target, DeceptivePlan plan,
                                                   const KGoalPathSettings& settings) {
  return sample_polyline(deceptive_waypoints(layout, true_target, plan, settings),
                         settings.geometry.speed, settings.geometry.sample_rate);
}

}  // namespace feint::sim

// The map figure: its colours, panels, legend, caption and alt text (see map_figure.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "feint/plot/map_figure.hpp"
#include "figure_detail.hpp"

namespace feint::plot {

using namespace figure_detail;

namespace {

constexpr std::size_t kHalfway = kMapPoints / 2;  // u = 0.5
/// At most this many decoy dots per panel (every k-th in trial order beyond it): an SVG of a big
/// study stays small, and the cloud looks the same.
constexpr std::size_t kMaxDecoyDots = 1500;
constexpr Colour kDecoyGrey{0.55, 0.55, 0.55};
/// A panel at most this much taller than wide: seven panels stay within a page at one column.
constexpr double kMaxAspect = 1.1;
constexpr Colour kBlack{0, 0, 0};
/// The robot's paths: the stimulus, under the response; each ends at its own target, so it needs no
/// colour of its own.
constexpr Colour kRobotGrey{0.6, 0.6, 0.6};

std::string panel_name(const MapPanel& p) {
  return fmt::format("{}{}", p.strategy.empty() ? "(none)" : p.strategy,
                     p.variant.empty() ? "" : "/" + p.variant);
}

std::string target_name(std::size_t k) { return fmt::format("T{}", k); }

std::string unit_words(const MeanMap& d) {
  return d.canonical ? "start-target distances" : "m";
}

// Points as small dots: a zero-length segment per point, which cairo strokes as a disc with
// round caps (markers are 4.6 pt wide, too big for a cloud).
Line dots(const std::vector<MapPoint>& points, Colour colour, double diameter, double opacity) {
  Line l;
  l.style = {colour, Dash::solid, Marker::none};
  l.line_width = diameter;
  l.opacity = opacity;
  for (const auto& p : points) {
    l.x.insert(l.x.end(), {p.x, p.x, std::numeric_limits<double>::quiet_NaN()});
    l.y.insert(l.y.end(), {p.y, p.y, std::numeric_limits<double>::quiet_NaN()});
  }
  return l;
}

Line markers(const std::vector<MapPoint>& points, Colour colour, Marker marker, bool filled) {
  Line l;
  l.style = {colour, Dash::solid, marker};
  l.connect = false;
  for (const auto& p : points) {
    l.x.push_back(p.x);
    l.y.push_back(p.y);
    l.filled.push_back(filled);
  }
  return l;
}

Line path(const std::vector<MapPoint>& points, Colour colour, Dash dash, double width) {
  Line l;
  l.style = {colour, dash, Marker::none};
  l.line_width = width;
  for (const auto& p : points) {
    l.x.push_back(p.x);
    l.y.push_back(p.y);
  }
  return l;
}

// A pointer's colour: its trials' true target's (the common frame's true target has the first).
Colour colour_of(const MeanMap& d, const MapMean& m) {
  return target_colour(d.canonical ? 0 : m.true_target);
}

// The limits of every panel (shared): the start, the targets and the mean paths, padded, and
// widened across or up so that one unit is as long on both axes within the plot heights the canvas
// allows (the plot area is at most 180 pt high) and a panel is not much taller than wide. The
// decoys do not widen it: a decoy many times farther than a true target near the start would shrink
// the paths to a dot; they are drawn where they fall inside.
struct Extent {
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  std::size_t columns = 1;
  bool contains(MapPoint p) const { return p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1; }
};

Extent map_extent(const MeanMap& d) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Extent e{inf, -inf, inf, -inf, 1};
  auto add = [&](MapPoint p) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
    e.x0 = std::min(e.x0, p.x);
    e.x1 = std::max(e.x1, p.x);
    e.y0 = std::min(e.y0, p.y);
    e.y1 = std::max(e.y1, p.y);
  };
  add(d.layout.start);
  for (const auto& t : d.layout.targets) add(t);
  for (const auto& p : d.panels) {
    for (const auto& m : p.means) {
      for (const auto& q : m.pointer) add(q);
      for (const auto& q : m.robot) add(q);
    }
  }
  const double pad = 0.12 * std::max({e.x1 - e.x0, e.y1 - e.y0, 1e-9});
  e.x0 -= pad;
  e.x1 += pad;
  e.y0 -= pad;
  e.y1 += pad;
  // The two-column figure's plot areas are at most this wide (the narrowest margins the canvas
  // draws: 4 pt page margins, an 18 pt left margin with its y label, 9 pt between columns, 8 pt
  // right of each); at that width the height (aspect x width) must stay under the canvas' 180 pt.
  e.columns = std::clamp<std::size_t>(d.panels.size(), 1, 4);
  const auto c = static_cast<double>(e.columns);
  const double widest = (kTwoColumnInches * 72 - 8 - 18 - (c - 1) * 9 - 8 * c) / c;
  const double max_aspect = std::min(170.0 / widest, kMaxAspect);
  if ((e.y1 - e.y0) / (e.x1 - e.x0) > max_aspect) {
    const double grow = ((e.y1 - e.y0) / max_aspect - (e.x1 - e.x0)) / 2;
    e.x0 -= grow;
    e.x1 += grow;
  }
  return e;
}

// The decoys a panel draws: those inside the map, at most kMaxDecoyDots of them.
std::vector<MapPoint> drawn_decoys(const MapPanel& p, const Extent& e) {
  std::vector<MapPoint> in;
  for (const auto& q : p.decoys) {
    if (e.contains(q)) in.push_back(q);
  }
  if (in.size() <= kMaxDecoyDots) return in;
  std::vector<MapPoint> out;
  const std::size_t stride = (in.size() + kMaxDecoyDots - 1) / kMaxDecoyDots;
  for (std::size_t i = 0; i < in.size(); i += stride) out.push_back(in[i]);
  return out;
}

// Ticks at one step on both axes (a map's grid is square).
std::vector<double> ticks_at(double lo, double hi, double step) {
  std::vector<double> t;
  for (auto k = static_cast<long long>(std::ceil(lo / step - 1e-9));
       static_cast<double>(k) * step <= hi + 1e-9 * step; ++k) {
    t.push_back(static_cast<double>(k) * step);
  }
  return t;
}

void set_axes(Panel& p, const Extent& e, const MeanMap& d) {
  const bool x_longer = e.x1 - e.x0 >= e.y1 - e.y0;
  // About three ticks on the longer axis: the panels are narrow (88 pt at one column).
  const auto t = x_longer ? detail::nice_ticks(e.x0, e.x1, 3) : detail::nice_ticks(e.y0, e.y1, 3);
  const double step = t.size() >= 2 ? t[1] - t[0] : 1.0;
  p.x.min = e.x0;
  p.x.max = e.x1;
  p.y.min = e.y0;
  p.y.max = e.y1;
  p.x.ticks = ticks_at(e.x0, e.x1, step);
  p.y.ticks = ticks_at(e.y0, e.y1, step);
  if (d.canonical) {
    p.x.label = "Across";
    p.y.label = "Along; true target at (0, 1)";
  } else {
    p.x.label = "x (m)";
    p.y.label = "y (m)";
  }
}

// Trials per panel: the total, or per true target in a fixed layout ("n = 20, 21, 19").
std::string panel_note(const MeanMap& d, const MapPanel& p) {
  if (d.canonical || p.means.size() < 2) return fmt::format("n = {}", p.trials);
  std::vector<std::string> n;
  for (const auto& m : p.means) n.push_back(fmt::format("{}", m.trials));
  return fmt::format("n = {}", fmt::join(n, ", "));
}

Panel map_panel(const MeanMap& d, const MapPanel& mp, const Extent& e) {
  Panel p;
  p.title = panel_name(mp);
  p.note = panel_note(d, mp);
  if (d.canonical) p.lines.push_back(dots(drawn_decoys(mp, e), kDecoyGrey, 1.6, 0.45));
  // Back to front: robot paths (wide, grey), pointers (narrow, in colour, with a white outline
  // where they cross a path), the time marks, and on top the landmarks: the start and the targets.
  for (const auto& m : mp.means) {
    if (!m.robot.empty()) p.lines.push_back(path(m.robot, kRobotGrey, Dash::solid, 2.2));
  }
  for (const auto& m : mp.means) {
    Line l = path(m.pointer, colour_of(d, m), Dash::solid, 1.3);
    l.halo = true;
    p.lines.push_back(std::move(l));
  }
  for (const auto& m : mp.means) {
    const Colour c = colour_of(d, m);
    if (!m.robot.empty())
      p.lines.push_back(markers({m.robot[kHalfway]}, kRobotGrey, Marker::diamond, true));
    p.lines.push_back(markers({m.pointer[kHalfway]}, c, Marker::diamond, true));
    p.lines.push_back(markers({m.pointer.front()}, c, Marker::square, false));
  }
  p.lines.push_back(markers({d.layout.start}, kBlack, Marker::triangle, true));
  for (std::size_t k = 0; k < d.layout.targets.size(); ++k) {
    p.lines.push_back(markers({d.layout.targets[k]}, target_colour(k), Marker::circle, true));
  }
  set_axes(p, e, d);
  return p;
}

std::vector<LegendEntry> map_legend(const MeanMap& d) {
  using K = LegendEntry::Kind;
  std::vector<LegendEntry> l;
  l.push_back(
      {K::marker, d.canonical ? "start (0, 0)" : "start", {kBlack, Dash::solid, Marker::triangle}});
  if (d.canonical) {
    l.push_back({K::marker, "true target (0, 1)", {target_colour(0), Dash::solid, Marker::circle}});
    l.push_back({K::marker, "decoys", {kDecoyGrey, Dash::solid, Marker::circle}});
  } else {
    for (std::size_t k = 0; k < d.layout.targets.size(); ++k) {
      l.push_back({K::marker, target_name(k), {target_colour(k), Dash::solid, Marker::circle}});
    }
  }
  l.push_back({K::line, "robot (mean path)", {kRobotGrey, Dash::solid, Marker::none}});
  // In a fixed layout the pointers take their true target's colour; the sample stands for them all.
  const Colour pointer = d.canonical ? target_colour(0) : kBlack;
  l.push_back(
      {K::line,
       d.canonical ? "pointer (mean belief)" : "pointer (mean belief; its true target's colour)",
       {pointer, Dash::solid, Marker::none}});
  l.push_back({K::marker, "pointer at the start", {pointer, Dash::solid, Marker::square}, true});
  l.push_back({K::marker, "half-way", {kBlack, Dash::solid, Marker::diamond}});
  return l;
}

double distance_to(MapPoint a, MapPoint b) { return std::hypot(a.x - b.x, a.y - b.y); }

}  // namespace

Colour target_colour(std::size_t k) noexcept {
  // Vermillion, bluish green, reddish purple, sky blue, black: Okabe-Ito without the conditions'
  // blue and orange (and without yellow, too light for a line on white).
  static constexpr std::size_t colours[] = {6, 3, 7, 2, 0};
  return okabe_ito(colours[k % 5]);
}

Figure map_figure(const MeanMap& d) {
  Figure f;
  f.legend = map_legend(d);
  const Extent e = map_extent(d);
  for (const auto& mp : d.panels) f.panels.push_back(map_panel(d, mp, e));
  f.columns = e.columns;
  f.max_columns_narrow = 2;
  f.shared_axes = true;
  f.aspect = (e.y1 - e.y0) / (e.x1 - e.x0);  // equal units across and up
  return f;
}

std::string map_caption(const MeanMap& d) {
  std::size_t robot = 0, decoys = 0, inside = 0;
  const Extent e = map_extent(d);
  for (const auto& p : d.panels) {
    for (const auto& m : p.means) robot += m.robot_trials;
    decoys += p.decoys.size();
    for (const auto& q : p.decoys) inside += e.contains(q) ? 1 : 0;
  }
  std::string s = fmt::format(
      "The study's map, one panel per strategy and version: the mean robot path (wide, grey) and "
      "the "
      "mean pointer, the participants' belief as a point (narrow, in colour, from the hollow "
      "square: where "
      "it was at the trial's first sample). Each trial's paths are time-normalised as mousetrap "
      "does (101 "
      "points from its first to its last sample) and averaged point by point; diamonds mark "
      "half-way "
      "(normalised time 0.5) on both. n: the trials each mean rests on ({} trials in all",
      d.trials);
  s += robot == d.trials ? ")."
                         : fmt::format("; the robot's path was logged in {} of them).", robot);
  if (d.canonical) {
    s += fmt::format(
        " The targets were placed per round ({} layouts of {} targets), so positions in metres "
        "differ "
        "from trial to trial and are not averaged: each trial is moved, turned and scaled so that "
        "the "
        "start is at (0, 0) and its true target at (0, 1), and mirrored ({} of {} trials) so that "
        "its "
        "decoy nearest in bearing lies to the left. Axes in start-target distances. Grey dots: the "
        "decoys of the panel's trials in that frame ({} of {} fall within the map shown).",
        d.layouts, d.targets, d.mirrored, d.trials, inside, decoys);
  } else {
    s += fmt::format(
        " One fixed layout of {} targets (T0 to T{}), in metres, with one robot path and one "
        "pointer per "
        "true target: each robot path ends at its target, each pointer is in its true target's "
        "colour, and "
        "n counts the trials per true target.",
        d.targets, d.targets == 0 ? 0 : d.targets - 1);
  }
  return s;
}

std::string alt_text(const MeanMap& d) {
  std::vector<std::string> panels;
  double end_lo = std::numeric_limits<double>::infinity(), end_hi = 0;
  for (const auto& p : d.panels) {
    panels.push_back(panel_name(p));
    for (const auto& m : p.means) {
      const MapPoint target = d.canonical ? MapPoint{0, 1} : d.layout.targets.at(m.true_target);
      const double r = distance_to(m.pointer.back(), target);
      end_lo = std::min(end_lo, r);
      end_hi = std::max(end_hi, r);
    }
  }
  std::string s = fmt::format(
      "Map of the {}-target study, one panel per strategy and version ({}), with the mean robot "
      "path and the mean pointer of the trials over normalised time",
      d.targets, and_list(panels));
  s += d.canonical ? "; the layouts differ per round, so each trial is mapped so that the start is "
                     "at (0, 0) and the true target at (0, 1), its nearest decoy to the left."
                   : fmt::format(" on the study's fixed layout, per true target (T0 to T{}).",
                                 d.targets == 0 ? 0 : d.targets - 1);
  if (std::isfinite(end_lo)) {
    s += fmt::format(
        " At the end of the trial the mean pointer is {} to {} {} from the true target.",
        number(end_lo), number(end_hi), unit_words(d));
  }
  return s;
}

}  // namespace feint::plot

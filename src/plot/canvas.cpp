// Layout and drawing of plot::Figure with cairo (see canvas.hpp). One drawing code for every
// surface: only the surface constructor differs between PDF, SVG and PNG.
#include "feint/plot/canvas.hpp"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <fontconfig/fontconfig.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <stdexcept>

#include "feint/error.hpp"
#include "feint/io/output.hpp"

namespace feint::plot {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (auto& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

FileFormat parse_file_format(std::string_view name) {
  const std::string n = lower(name);
  if (n == "pdf") return FileFormat::pdf;
  if (n == "svg") return FileFormat::svg;
  if (n == "png") return FileFormat::png;
  throw UsageError(fmt::format("figure format '{}': expected pdf, svg or png", name));
}

FileFormat format_from_path(std::string_view path) {
  const auto dot = path.rfind('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash)) {
    throw UsageError(
        fmt::format("'{}': the figure's file name must end in .pdf, .svg or .png", path));
  }
  try {
    return parse_file_format(path.substr(dot + 1));
  } catch (const UsageError&) {
    throw UsageError(
        fmt::format("'{}': the figure's file name must end in .pdf, .svg or .png", path));
  }
}

std::string_view extension(FileFormat format) noexcept {
  switch (format) {
    case FileFormat::pdf:
      return "pdf";
    case FileFormat::svg:
      return "svg";
    case FileFormat::png:
      return "png";
  }
  return "pdf";
}

Width parse_width(std::string_view name) {
  const std::string n = lower(name);
  if (n == "one" || n == "1" || n == "one-column" || n == "onecolumn") return Width::one_column;
  if (n == "two" || n == "2" || n == "two-column" || n == "twocolumn") return Width::two_column;
  throw UsageError(fmt::format("width '{}': expected one (3.5 in) or two (7.16 in)", name));
}

double width_inches(Width width) noexcept {
  return width == Width::one_column ? kOneColumnInches : kTwoColumnInches;
}

Colour okabe_ito(std::size_t i) noexcept {
  static constexpr Colour k[] = {
      {0.0, 0.0, 0.0},                         // black
      {230 / 255.0, 159 / 255.0, 0.0},         // orange
      {86 / 255.0, 180 / 255.0, 233 / 255.0},  // sky blue
      {0.0, 158 / 255.0, 115 / 255.0},         // bluish green
      {240 / 255.0, 228 / 255.0, 66 / 255.0},  // yellow
      {0.0, 114 / 255.0, 178 / 255.0},         // blue
      {213 / 255.0, 94 / 255.0, 0.0},          // vermillion
      {204 / 255.0, 121 / 255.0, 167 / 255.0}  // reddish purple
  };
  return k[i % 8];
}

Style series_style(std::size_t i) noexcept {
  // Blue, vermillion, bluish green, reddish purple, orange, sky blue, black: dark/light alternate
  // so neighbours differ in greyscale too.
  static constexpr std::size_t colours[] = {5, 6, 3, 7, 1, 2, 0};
  static constexpr Dash dashes[] = {Dash::solid, Dash::dashed, Dash::dotted, Dash::dash_dot};
  static constexpr Marker markers[] = {Marker::circle, Marker::square, Marker::triangle,
                                       Marker::diamond, Marker::cross};
  return {okabe_ito(colours[i % 7]), dashes[i % 4], markers[i % 5]};
}

Style condition_style(std::size_t i) noexcept {
  // Blue, orange, bluish green, reddish purple (Okabe-Ito indices 5, 1, 3, 7).
  static constexpr std::size_t colours[] = {5, 1, 3, 7};
  static constexpr Dash dashes[] = {Dash::solid, Dash::dashed, Dash::dotted, Dash::dash_dot};
  static constexpr Marker markers[] = {Marker::circle, Marker::square, Marker::triangle,
                                       Marker::diamond};
  return {okabe_ito(colours[i % 4]), dashes[i % 4], markers[i % 4]};
}

Colour strategy_colour(std::size_t i) noexcept {
  // Bluish green, yellow, dark grey, reddish purple, sky blue, vermillion: not the conditions'
  // blue and orange, and the first four of distinct lightness (greyscale).
  static constexpr Colour dark_grey{0.3, 0.3, 0.3};
  static constexpr std::size_t colours[] = {3, 4, 0, 7, 2, 6};
  const std::size_t k = colours[i % 6];
  return k == 0 ? dark_grey : okabe_ito(k);
}

namespace detail {

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(std::isfinite(lo) && std::isfinite(hi)) || hi < lo) return {};
  if (hi == lo) return {lo};
  // Of the round steps near (hi - lo) / target, the one whose tick count is closest to target
  // (at least 3 ticks when possible; ties go to more ticks).
  const double raw = (hi - lo) / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10 * mag;
  long long best = -1;
  for (double scale : {0.1, 1.0, 10.0}) {
    for (double m : {1.0, 2.0, 2.5, 5.0}) {
      const double st = m * mag * scale;
      const long long count = static_cast<long long>(std::floor(hi / st + 1e-9)) -
                              static_cast<long long>(std::ceil(lo / st - 1e-9)) + 1;
      const long long score = std::llabs(count - target) + (count < 3 ? 100 : 0);
      if (best < 0 || score < best || (score == best && st < step)) {
        best = score;
        step = st;
      }
    }
  }
  std::vector<double> ticks;
  const long long first = static_cast<long long>(std::ceil(lo / step - 1e-9));
  const long long last = static_cast<long long>(std::floor(hi / step + 1e-9));
  for (long long k = first; k <= last; ++k) ticks.push_back(static_cast<double>(k) * step);
  return ticks;
}

std::string tick_label(double value, double step) {
  int decimals = 0;
  if (step > 0 && std::isfinite(step)) {
    while (decimals < 6) {
      const double scaled = step * std::pow(10.0, decimals);
      if (std::fabs(scaled - std::round(scaled)) < 1e-6 * std::max(1.0, scaled)) break;
      ++decimals;
    }
  }
  std::string s = fmt::format("{:.{}f}", value, decimals);
  if (s.find_first_not_of("-0.") == std::string::npos && s[0] == '-') s.erase(0, 1);  // "-0"
  return s;
}

}  // namespace detail

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMargin = 4.0;
constexpr double kTick = 3.0;
constexpr double kMarker = 2.3;  // pt, half size

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (std::isfinite(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  bool empty() const { return lo > hi; }
};

// The axis' limits and ticks once the data are known.
struct Scale {
  double min = 0, max = 1;
  std::vector<double> ticks;
  std::vector<std::string> labels;
};

Scale make_scale(const Axis& axis, Range data) {
  Scale s;
  const bool categorical = !axis.categories.empty();
  for (const auto& [pos, name] : axis.categories) {
    data.add(pos - 0.5);
    data.add(pos + 0.5);
  }
  if (data.empty()) data = Range{0, 1};
  if (data.lo == data.hi) {
    data.lo -= 0.5;
    data.hi += 0.5;
  }
  const double pad = categorical ? 0.0 : 0.04 * (data.hi - data.lo);
  double lo = data.lo - pad, hi = data.hi + pad;
  // Never beyond the metric's range (the padding either).
  if (axis.bound_min) lo = std::max(lo, *axis.bound_min);
  if (axis.bound_max) hi = std::min(hi, *axis.bound_max);
  s.min = axis.min.value_or(lo);
  s.max = axis.max.value_or(hi);
  if (s.max <= s.min) s.max = s.min + 1;
  if (categorical) {
    for (const auto& [pos, name] : axis.categories) {
      s.ticks.push_back(pos);
      s.labels.push_back(name);
    }
    return s;
  }
  s.ticks = axis.ticks.empty() ? detail::nice_ticks(s.min, s.max) : axis.ticks;
  double step = 0;
  for (std::size_t i = 1; i < s.ticks.size(); ++i) {
    const double d = std::fabs(s.ticks[i] - s.ticks[i - 1]);
    if (d > 0) step = step == 0 ? d : std::min(step, d);
  }
  if (step == 0) step = 1;
  for (double t : s.ticks) {
    std::string l = detail::tick_label(axis.absolute_labels ? std::fabs(t) : t, step);
    if (axis.percent) l += "%";
    s.labels.push_back(std::move(l));
  }
  return s;
}

// A value clipped to an axis' bounds (the metric's range).
double clip(const Axis& a, double v) {
  if (std::isnan(v)) return v;
  if (a.bound_min) v = std::max(v, *a.bound_min);
  if (a.bound_max) v = std::min(v, *a.bound_max);
  return v;
}

// Whether a reference widens the axis: inside the data widened by kReferenceReach of their span,
// or inside the axis' fixed limits.
bool reference_on_axis(const Axis& a, const Range& data, double v) {
  if (a.min && a.max) return v >= *a.min && v <= *a.max;
  if (data.empty()) return true;
  const double reach = kReferenceReach * std::max(data.hi - data.lo, 1e-9);
  const double lo = a.min.value_or(data.lo - reach), hi = a.max.value_or(data.hi + reach);
  return v >= lo && v <= hi;
}

bool outside(const Scale& s, double v) { return v < s.min - 1e-12 || v > s.max + 1e-12; }

void data_ranges(const Panel& p, Range& x, Range& y) {
  for (const auto& l : p.lines) {
    for (std::size_t i = 0; i < l.x.size(); ++i) {
      x.add(l.x[i]);
      if (i < l.y.size()) y.add(l.y[i]);
      const bool intervals = l.band || l.error_bars != ErrorBars::none;
      if (!intervals) continue;
      const bool horizontal = l.error_bars == ErrorBars::horizontal;
      Range& r = horizontal ? x : y;
      const Axis& a = horizontal ? p.x : p.y;
      if (i < l.lo.size()) r.add(clip(a, l.lo[i]));
      if (i < l.hi.size()) r.add(clip(a, l.hi[i]));
    }
  }
  if (p.bars) {
    const Bars& b = *p.bars;
    Range& cat = b.horizontal ? y : x;
    Range& val = b.horizontal ? x : y;
    for (std::size_t k = 0; k < b.positions.size(); ++k) {
      cat.add(b.positions[k] - b.thickness / 2);
      cat.add(b.positions[k] + b.thickness / 2);
      double v = k < b.start.size() ? b.start[k] : 0.0;
      val.add(v);
      if (k < b.segments.size()) {
        for (double s : b.segments[k]) v += s;
      }
      val.add(v);
    }
  }
  for (double m : p.marks) x.add(m);
}

// The references that widen the axes (after the data are known).
void reference_ranges(const Panel& p, Range& x, Range& y) {
  const Range x0 = x, y0 = y;
  for (const auto& ref : p.refs) {
    if (ref.vertical ? reference_on_axis(p.x, x0, ref.value)
                     : reference_on_axis(p.y, y0, ref.value)) {
      (ref.vertical ? x : y).add(ref.value);
    }
  }
}

// cairo objects with their destructors.
struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};
using SurfacePtr = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using ContextPtr = std::unique_ptr<cairo_t, ContextDeleter>;

void check(cairo_status_t status, const char* what) {
  if (status != CAIRO_STATUS_SUCCESS) {
    throw std::runtime_error(fmt::format("cairo: {}: {}", what, cairo_status_to_string(status)));
  }
}

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void set_font(cairo_t* cr, double size, bool bold = false) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

double text_width(cairo_t* cr, const std::string& text) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, text.c_str(), &e);
  return e.x_advance;
}

// Draws `text` with its anchor at (x, y): ha 0 = left, 0.5 = centre, 1 = right; y is the
// vertical centre of lower-case-and-digits text (cap height / 2 above the baseline).
void draw_text(cairo_t* cr, const std::string& text, double x, double y, double ha,
               double angle = 0) {
  cairo_font_extents_t fe;
  cairo_font_extents(cr, &fe);
  const double w = text_width(cr, text);
  cairo_save(cr);
  cairo_translate(cr, x, y);
  cairo_rotate(cr, angle);
  cairo_move_to(cr, -ha * w, 0.35 * fe.ascent);
  cairo_show_text(cr, text.c_str());
  cairo_restore(cr);
}

// Text over data: a white halo keeps it legible where a line crosses it.
void draw_text_halo(cairo_t* cr, const std::string& text, double x, double y, double ha) {
  cairo_font_extents_t fe;
  cairo_font_extents(cr, &fe);
  const double w = text_width(cr, text);
  cairo_save(cr);
  cairo_new_path(cr);
  cairo_move_to(cr, x - ha * w, y + 0.35 * fe.ascent);
  cairo_text_path(cr, text.c_str());
  cairo_pattern_t* colour = cairo_get_source(cr);
  cairo_pattern_reference(colour);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_set_line_width(cr, 2.2);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_stroke_preserve(cr);
  cairo_set_source(cr, colour);
  cairo_pattern_destroy(colour);
  cairo_fill(cr);
  cairo_restore(cr);
}

void set_colour(cairo_t* cr, const Colour& c, double alpha = 1.0) {
  cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha);
}

void set_dash(cairo_t* cr, Dash dash, double width) {
  const double w = std::max(width, 0.6);
  switch (dash) {
    case Dash::solid:
      cairo_set_dash(cr, nullptr, 0, 0);
      break;
    case Dash::dashed: {
      const double d[] = {4 * w, 2 * w};
      cairo_set_dash(cr, d, 2, 0);
      break;
    }
    case Dash::dotted: {
      const double d[] = {0.01, 1.8 * w};
      cairo_set_dash(cr, d, 2, 0);
      break;
    }
    case Dash::dash_dot: {
      const double d[] = {4 * w, 1.5 * w, 0.01, 1.5 * w};
      cairo_set_dash(cr, d, 4, 0);
      break;
    }
  }
}

void draw_marker(cairo_t* cr, Marker m, double x, double y, const Colour& c, bool filled,
                 double alpha = 1.0) {
  if (m == Marker::none) return;
  const double r = kMarker;
  cairo_new_path(cr);
  switch (m) {
    case Marker::none:
      return;
    case Marker::circle:
      cairo_arc(cr, x, y, r, 0, 2 * M_PI);
      break;
    case Marker::square:
      cairo_rectangle(cr, x - 0.85 * r, y - 0.85 * r, 1.7 * r, 1.7 * r);
      break;
    case Marker::triangle:
      cairo_move_to(cr, x, y - 1.15 * r);
      cairo_line_to(cr, x + r, y + 0.75 * r);
      cairo_line_to(cr, x - r, y + 0.75 * r);
      cairo_close_path(cr);
      break;
    case Marker::diamond:
      cairo_move_to(cr, x, y - 1.2 * r);
      cairo_line_to(cr, x + r, y);
      cairo_line_to(cr, x, y + 1.2 * r);
      cairo_line_to(cr, x - r, y);
      cairo_close_path(cr);
      break;
    case Marker::cross:
      cairo_move_to(cr, x - r, y - r);
      cairo_line_to(cr, x + r, y + r);
      cairo_move_to(cr, x - r, y + r);
      cairo_line_to(cr, x + r, y - r);
      set_dash(cr, Dash::solid, 1);
      cairo_set_line_width(cr, 1.0);
      set_colour(cr, c, alpha);
      cairo_stroke(cr);
      return;
  }
  if (filled) {
    set_colour(cr, c, alpha);
  } else {
    cairo_set_source_rgba(cr, 1, 1, 1, alpha);
  }
  cairo_fill_preserve(cr);
  set_dash(cr, Dash::solid, 1);
  cairo_set_line_width(cr, 0.8);
  set_colour(cr, c, alpha);
  cairo_stroke(cr);
}

// Sizes shared by every panel of a figure, so that their axes line up.
struct Layout {
  double width = 0, height = 0;
  std::size_t columns = 1, rows = 1;
  double legend_height = 0;
  std::vector<std::pair<std::size_t, std::size_t>> legend_rows;  // [first, end) entries
  std::vector<double> legend_entry_width;
  double cell_width = 0, cell_height = 0;
  double left = 0, right = 0, top = 0, bottom = 0;  // around each plot area
  double left_other = 0;                            // left margin of the columns after the first
  bool note_line = false;  // panel notes on their own line under the titles
  double plot_width = 0, plot_height = 0;
};

double legend_sample_width(const LegendEntry& e) {
  if (e.kind == LegendEntry::Kind::text) return -3.0;  // no sample, no gap
  return e.kind == LegendEntry::Kind::line || e.kind == LegendEntry::Kind::band ? 18.0 : 8.0;
}

Layout make_layout(cairo_t* cr, const Figure& f, Width width,
                   const std::vector<std::pair<Scale, Scale>>& scales) {
  Layout L;
  L.width = width_inches(width) * 72.0;
  const std::size_t n = std::max<std::size_t>(1, f.panels.size());
  std::size_t cols = std::max<std::size_t>(1, f.columns);
  if (width == Width::one_column)
    cols = std::min(cols, std::max<std::size_t>(1, f.max_columns_narrow));
  cols = std::min(cols, n);
  L.columns = cols;
  L.rows = (n + cols - 1) / cols;

  // Margins around the plot areas: room for the widest y tick label, labels and titles.
  set_font(cr, kTickFontSize);
  double ytick = 0;
  bool ylabel = false, xlabel = false, title = false, marks = false;
  for (std::size_t i = 0; i < f.panels.size(); ++i) {
    for (const auto& l : scales[i].second.labels) ytick = std::max(ytick, text_width(cr, l));
    ylabel = ylabel || !f.panels[i].y.label.empty();
    xlabel = xlabel || !f.panels[i].x.label.empty();
    // A note sits in the title's band: without that room it runs into the legend above.
    title = title || !f.panels[i].title.empty() || !f.panels[i].note.empty();
    marks = marks || !f.panels[i].marks.empty();
  }
  L.left = (ylabel ? kFontSize + 4 : 0) + ytick + kTick + 3;
  L.right = 8;
  L.top = (title ? kFontSize + 5 : 3) + (marks ? kFontSize + 1 : 0);
  L.bottom = kTick + 3 + kTickFontSize + (xlabel ? kFontSize + 5 : 2);
  // Legend: entries flow left to right, wrapping at the figure's width.
  set_font(cr, kFontSize);
  double x = 0;
  std::size_t row_start = 0;
  for (std::size_t i = 0; i < f.legend.size(); ++i) {
    const double w = legend_sample_width(f.legend[i]) + 3 + text_width(cr, f.legend[i].label) + 10;
    L.legend_entry_width.push_back(w);
    if (x > 0 && x + w - 10 > L.width - 2 * kMargin - L.left) {
      L.legend_rows.emplace_back(row_start, i);
      row_start = i;
      x = 0;
    }
    x += w;
  }
  if (!f.legend.empty()) L.legend_rows.emplace_back(row_start, f.legend.size());
  L.legend_height = L.legend_rows.empty() ? 0 : L.legend_rows.size() * kFontSize * 1.45 + 3;

  const double avail = L.width - 2 * kMargin;
  // Shared axes: the other columns need room for their tick labels only.
  L.left_other = f.shared_axes ? ytick + kTick + 3 + 6 : L.left;
  L.plot_width = (avail - L.left - (cols - 1) * L.left_other - cols * L.right) / cols;
  L.cell_width = L.plot_width + L.right + L.left_other;
  // Tall figures waste a page: a plot area is at most 2.5 in high (or as the figure says).
  L.plot_height = std::min(L.plot_width * f.aspect, std::min(f.max_plot_height, 180.0));
  // A panel's note goes beside its title when both fit, else on a line of its own below it.
  for (const auto& p : f.panels) {
    if (p.note.empty()) continue;
    set_font(cr, kFontSize, true);
    const double tw = text_width(cr, p.title);
    set_font(cr, kTickFontSize);
    if (tw + 6 + text_width(cr, p.note) > L.plot_width) L.note_line = true;
  }
  if (L.note_line) L.top += kTickFontSize + 3;
  L.cell_height = L.top + L.plot_height + L.bottom;
  L.height = kMargin + L.legend_height + L.rows * L.cell_height + kMargin;
  return L;
}

void draw_legend(cairo_t* cr, const Figure& f, const Layout& L) {
  set_font(cr, kFontSize);
  double y = kMargin + kFontSize * 0.725;
  for (const auto& [first, end] : L.legend_rows) {
    double x = kMargin + L.left;
    for (std::size_t i = first; i < end; ++i) {
      const LegendEntry& e = f.legend[i];
      const double sw = legend_sample_width(e);
      switch (e.kind) {
        case LegendEntry::Kind::band:
          set_colour(cr, e.style.colour, 0.2);
          cairo_rectangle(cr, x, y - 3.5, sw, 7);
          cairo_fill(cr);
          [[fallthrough]];
        case LegendEntry::Kind::line:
          set_colour(cr, e.style.colour);
          set_dash(cr, e.style.dash, 1.0);
          cairo_set_line_width(cr, 1.0);
          cairo_move_to(cr, x, y);
          cairo_line_to(cr, x + sw, y);
          cairo_stroke(cr);
          draw_marker(cr, e.style.marker, x + sw / 2, y, e.style.colour, !e.hollow);
          break;
        case LegendEntry::Kind::marker:
          draw_marker(cr, e.style.marker, x + sw / 2, y, e.style.colour, !e.hollow);
          break;
        case LegendEntry::Kind::box:
          set_colour(cr, e.style.colour);
          cairo_rectangle(cr, x, y - 3.5, 7, 7);
          cairo_fill(cr);
          break;
        case LegendEntry::Kind::text:
          break;
        case LegendEntry::Kind::asterisk:
          cairo_set_source_rgb(cr, 0, 0, 0);
          set_font(cr, kFontSize + 2, true);
          draw_text(cr, "*", x + sw / 2, y + 2, 0.5);
          set_font(cr, kFontSize);
          break;
      }
      cairo_set_source_rgb(cr, 0, 0, 0);
      if (e.kind == LegendEntry::Kind::text) {
        // A heading ("Strategy:") in bold, a remark in plain text.
        set_font(cr, kFontSize, !e.label.empty() && e.label.back() == ':');
        draw_text(cr, e.label, x, y, 0);
        set_font(cr, kFontSize);
      } else {
        draw_text(cr, e.label, x + sw + 3, y, 0);
      }
      x += L.legend_entry_width[i];
    }
    y += kFontSize * 1.45;
  }
}

// A panel's plot area on the page and its scales: maps data values to points.
struct PlotArea {
  const Scale& xs;
  const Scale& ys;
  double px = 0, py = 0, pw = 0, ph = 0;  // left, top, width, height
  double X(double v) const { return px + (v - xs.min) / (xs.max - xs.min) * pw; }
  double Y(double v) const { return py + ph - (v - ys.min) / (ys.max - ys.min) * ph; }
  // Interval ends just beyond the plot area: a one-sided interval reaches infinity.
  double clamped_x(double v) const { return std::clamp(X(v), px - 10, px + pw + 10); }
  double clamped_y(double v) const { return std::clamp(Y(v), py - 10, py + ph + 10); }
};

// Stacked bars: each segment filled in its colour, with a thin white outline between segments.
void draw_bars(cairo_t* cr, const Bars& b, const PlotArea& a) {
  for (std::size_t k = 0; k < b.positions.size() && k < b.segments.size(); ++k) {
    double v = k < b.start.size() ? b.start[k] : 0.0;
    const double c0 = b.positions[k] - b.thickness / 2, c1 = b.positions[k] + b.thickness / 2;
    for (std::size_t s = 0; s < b.segments[k].size(); ++s) {
      const double len = b.segments[k][s];
      if (!(len > 0)) continue;
      if (b.horizontal) {
        cairo_rectangle(cr, a.X(v), a.Y(c1), a.X(v + len) - a.X(v), a.Y(c0) - a.Y(c1));
      } else {
        cairo_rectangle(cr, a.X(c0), a.Y(v + len), a.X(c1) - a.X(c0), a.Y(v) - a.Y(v + len));
      }
      set_colour(cr, s < b.colours.size() ? b.colours[s] : okabe_ito(s));
      cairo_fill_preserve(cr);
      cairo_set_source_rgb(cr, 1, 1, 1);
      cairo_set_line_width(cr, 0.4);
      set_dash(cr, Dash::solid, 1);
      cairo_stroke(cr);
      v += len;
    }
  }
}

// The references on the axes as grey dashed lines (those beyond get an arrow, with the labels).
void draw_reference_lines(cairo_t* cr, const Panel& p, const PlotArea& a) {
  for (const auto& ref : p.refs) {
    if (outside(ref.vertical ? a.xs : a.ys, ref.value)) continue;  // an arrow at the edge, later
    cairo_set_source_rgb(cr, 0.4, 0.4, 0.4);
    cairo_set_line_width(cr, 0.7);
    const double d[] = {2.0, 2.0};
    cairo_set_dash(cr, d, 2, 0);
    if (ref.vertical) {
      cairo_move_to(cr, a.X(ref.value), a.py);
      cairo_line_to(cr, a.X(ref.value), a.py + a.ph);
    } else {
      cairo_move_to(cr, a.px, a.Y(ref.value));
      cairo_line_to(cr, a.px + a.pw, a.Y(ref.value));
    }
    cairo_stroke(cr);
  }
}

// The lines' confidence bands, under every line: one filled polygon per run of points with both
// bounds (a missing bound breaks the band).
void draw_bands(cairo_t* cr, const Panel& p, const PlotArea& a) {
  for (const auto& l : p.lines) {
    if (!l.band) continue;
    set_colour(cr, l.style.colour, 0.18 * l.opacity);
    std::size_t i = 0;
    while (i < l.x.size()) {
      std::size_t j = i;  // a run of points with both bounds
      while (j < l.x.size() && j < l.lo.size() && j < l.hi.size() && !std::isnan(l.lo[j]) &&
             !std::isnan(l.hi[j]) && std::isfinite(l.x[j]))
        ++j;
      if (j > i) {
        cairo_new_path(cr);
        for (std::size_t k = i; k < j; ++k) {
          cairo_line_to(cr, a.X(l.x[k]), a.clamped_y(clip(p.y, l.hi[k])));
        }
        for (std::size_t k = j; k-- > i;) {
          cairo_line_to(cr, a.X(l.x[k]), a.clamped_y(clip(p.y, l.lo[k])));
        }
        cairo_close_path(cr);
        cairo_fill(cr);
      }
      i = j + 1;
    }
  }
}

// A line through its finite points (a missing point breaks it), over a white halo if it asks.
void stroke_line(cairo_t* cr, const Line& l, const PlotArea& a) {
  cairo_set_line_width(cr, l.line_width);
  set_dash(cr, l.style.dash, l.line_width);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_new_path(cr);
  bool open = false;
  for (std::size_t i = 0; i < l.x.size() && i < l.y.size(); ++i) {
    if (!std::isfinite(l.y[i]) || !std::isfinite(l.x[i])) {
      open = false;
      continue;
    }
    if (open) {
      cairo_line_to(cr, a.X(l.x[i]), a.Y(l.y[i]));
    } else {
      cairo_move_to(cr, a.X(l.x[i]), a.Y(l.y[i]));
    }
    open = true;
  }
  if (l.halo) {
    cairo_save(cr);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_set_dash(cr, nullptr, 0, 0);
    cairo_set_line_width(cr, l.line_width + 2.0);
    cairo_stroke_preserve(cr);
    cairo_restore(cr);
  }
  cairo_stroke(cr);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
}

// A line's error bars with short caps, all in one stroke; the ends clipped to the axis' bounds.
void stroke_error_bars(cairo_t* cr, const Line& l, const Panel& p, const PlotArea& a) {
  cairo_set_line_width(cr, 0.8);
  set_dash(cr, Dash::solid, 1);
  for (std::size_t i = 0; i < l.x.size() && i < l.lo.size() && i < l.hi.size(); ++i) {
    if (std::isnan(l.lo[i]) || std::isnan(l.hi[i]) || !std::isfinite(l.y[i])) continue;
    if (l.error_bars == ErrorBars::vertical) {
      const double x = a.X(l.x[i]), y0 = a.clamped_y(clip(p.y, l.lo[i])),
                   y1 = a.clamped_y(clip(p.y, l.hi[i]));
      cairo_move_to(cr, x, y0);
      cairo_line_to(cr, x, y1);
      for (double yy : {y0, y1}) {
        cairo_move_to(cr, x - 1.8, yy);
        cairo_line_to(cr, x + 1.8, yy);
      }
    } else {
      const double y = a.Y(l.y[i]), x0 = a.clamped_x(clip(p.x, l.lo[i])),
                   x1 = a.clamped_x(clip(p.x, l.hi[i]));
      cairo_move_to(cr, x0, y);
      cairo_line_to(cr, x1, y);
      for (double xx : {x0, x1}) {
        cairo_move_to(cr, xx, y - 1.8);
        cairo_line_to(cr, xx, y + 1.8);
      }
    }
  }
  cairo_stroke(cr);
}

// One line of a panel: the line, its error bars, then its markers on top.
void draw_line(cairo_t* cr, const Line& l, const Panel& p, const PlotArea& a) {
  set_colour(cr, l.style.colour, l.opacity);
  if (l.connect) stroke_line(cr, l, a);
  if (l.error_bars != ErrorBars::none) stroke_error_bars(cr, l, p, a);
  for (std::size_t i = 0; i < l.x.size() && i < l.y.size(); ++i) {
    if (!std::isfinite(l.y[i]) || !std::isfinite(l.x[i])) continue;
    const bool filled = i < l.filled.size() ? l.filled[i] : true;
    draw_marker(cr, l.style.marker, a.X(l.x[i]), a.Y(l.y[i]), l.style.colour, filled, l.opacity);
  }
}

// The data, clipped to the plot area, from the back: bars, reference lines, bands, lines.
void draw_data(cairo_t* cr, const Panel& p, const PlotArea& a) {
  cairo_save(cr);
  cairo_rectangle(cr, a.px - 3, a.py - 3, a.pw + 6, a.ph + 6);
  cairo_clip(cr);
  if (p.bars) draw_bars(cr, *p.bars, a);
  draw_reference_lines(cr, p, a);
  draw_bands(cr, p, a);
  for (const auto& l : p.lines) draw_line(cr, l, p, a);
  cairo_restore(cr);
}

// A reference beyond the data: an arrow at the edge pointing towards it, with its label.
void draw_off_axis_reference(cairo_t* cr, const RefLine& ref, const PlotArea& a) {
  const bool high = ref.value > (ref.vertical ? a.xs.max : a.ys.max);
  const double s = 3.2;  // arrow half-width, pt
  cairo_new_path(cr);
  if (ref.vertical) {
    const double x = high ? a.px + a.pw - 1 : a.px + 1, y = a.py + 5, d = high ? 1 : -1;
    cairo_move_to(cr, x, y);
    cairo_line_to(cr, x - d * 2 * s, y - s);
    cairo_line_to(cr, x - d * 2 * s, y + s);
    cairo_close_path(cr);
    cairo_fill(cr);
    if (!ref.label.empty()) {
      draw_text_halo(cr, ref.label, x - d * (2 * s + 2), y, high ? 1 : 0);
    }
  } else {
    const double x = a.px + a.pw - s - 1, y = high ? a.py + 4 : a.py + a.ph - 4, d = high ? 1 : -1;
    cairo_move_to(cr, x, y);
    cairo_line_to(cr, x - s, y + d * 2 * s);
    cairo_line_to(cr, x + s, y + d * 2 * s);
    cairo_close_path(cr);
    cairo_fill(cr);
    if (!ref.label.empty()) {
      draw_text_halo(cr, ref.label + (high ? " (above)" : " (below)"), x - s - 2, y + d * s, 1);
    }
  }
}

// Reference labels, at the right end of the line, above it (unclipped, over the data).
void draw_reference_labels(cairo_t* cr, const Panel& p, const PlotArea& a) {
  set_font(cr, kTickFontSize);
  cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
  for (const auto& ref : p.refs) {
    if (outside(ref.vertical ? a.xs : a.ys, ref.value)) {
      draw_off_axis_reference(cr, ref, a);
      continue;
    }
    if (ref.label.empty()) continue;
    if (ref.vertical) {
      draw_text_halo(cr, ref.label, a.X(ref.value) + 2, a.py + 4, 0);
    } else {
      draw_text_halo(cr, ref.label, a.px + a.pw - 1, a.Y(ref.value) - 4.5, 1);
    }
  }
}

// Axes: the left and bottom spines with outward ticks (no box, no grid).
void draw_axes(cairo_t* cr, const PlotArea& a) {
  const double px = a.px, py = a.py, pw = a.pw, ph = a.ph;
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 0.6);
  set_dash(cr, Dash::solid, 1);
  cairo_move_to(cr, px, py);
  cairo_line_to(cr, px, py + ph);
  cairo_line_to(cr, px + pw, py + ph);
  cairo_stroke(cr);
  for (std::size_t i = 0; i < a.xs.ticks.size(); ++i) {
    const double x = a.X(a.xs.ticks[i]);
    if (x < px - 0.5 || x > px + pw + 0.5) continue;
    cairo_move_to(cr, x, py + ph);
    cairo_line_to(cr, x, py + ph + kTick);
    cairo_stroke(cr);
    draw_text(cr, a.xs.labels[i], x, py + ph + kTick + 2 + kTickFontSize * 0.5, 0.5);
  }
  for (std::size_t i = 0; i < a.ys.ticks.size(); ++i) {
    const double y = a.Y(a.ys.ticks[i]);
    if (y < py - 0.5 || y > py + ph + 0.5) continue;
    cairo_move_to(cr, px, y);
    cairo_line_to(cr, px - kTick, y);
    cairo_stroke(cr);
    draw_text(cr, a.ys.labels[i], px - kTick - 2, y, 1);
  }
}

// The panel's words around the plot area: note, axis labels, significance marks, title.
void draw_panel_labels(cairo_t* cr, const Panel& p, const PlotArea& a, const Layout& L, bool ylabel,
                       bool xlabel, double ylabel_x) {
  const double px = a.px, py = a.py, pw = a.pw, ph = a.ph;
  set_font(cr, kFontSize);
  const double note_room = L.note_line ? kTickFontSize + 3 : 0;
  if (!p.note.empty()) {  // beside the title, right-aligned, or under it
    set_font(cr, kTickFontSize);
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    const double marks_room = p.marks.empty() ? 0 : kFontSize + 1;
    if (L.note_line) {
      draw_text(cr, p.note, px, py - marks_room - kTickFontSize * 0.9, 0);
    } else {
      draw_text(cr, p.note, px + pw, py - marks_room - kFontSize * 0.75, 1);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    set_font(cr, kFontSize);
  }
  if (xlabel && !p.x.label.empty()) {
    draw_text(cr, p.x.label, px + pw / 2, py + ph + kTick + 3 + kTickFontSize + kFontSize * 0.75,
              0.5);
  }
  if (ylabel && !p.y.label.empty()) {
    draw_text(cr, p.y.label, ylabel_x, py + ph / 2, 0.5, -M_PI / 2);
  }
  if (!p.marks.empty()) {
    set_font(cr, kFontSize + 2, true);
    for (double m : p.marks) {
      if (m < a.xs.min || m > a.xs.max) continue;
      draw_text(cr, "*", a.X(m), py - kFontSize * 0.3, 0.5);
    }
  }
  if (!p.title.empty()) {
    set_font(cr, kFontSize, true);
    const double marks_room = p.marks.empty() ? 0 : kFontSize + 1;
    draw_text(cr, p.title, px, py - marks_room - note_room - kFontSize * 0.75, 0);
  }
}

// One panel, back to front: the clipped data, the references' labels over them, the axes, and
// the words around the plot area.
void draw_panel(cairo_t* cr, const Panel& p, const Scale& xs, const Scale& ys, double px, double oy,
                const Layout& L, bool ylabel, bool xlabel, double ylabel_x) {
  const PlotArea a{xs, ys, px, oy + L.top, L.plot_width, L.plot_height};
  draw_data(cr, p, a);
  draw_reference_labels(cr, p, a);
  draw_axes(cr, a);
  draw_panel_labels(cr, p, a, L, ylabel, xlabel, ylabel_x);
}

void draw(cairo_t* cr, const Figure& f, const Layout& L,
          const std::vector<std::pair<Scale, Scale>>& scales) {
  draw_legend(cr, f, L);
  // Small multiples in several rows with one y label: drawn once, centred on the rows (a long
  // label does not fit beside one short panel).
  bool one_ylabel = f.shared_axes && L.rows > 1 && !f.panels.empty();
  for (const auto& p : f.panels) one_ylabel = one_ylabel && p.y.label == f.panels[0].y.label;
  for (std::size_t i = 0; i < f.panels.size(); ++i) {
    const std::size_t col = i % L.columns, row = i / L.columns;
    const double px = kMargin + L.left + static_cast<double>(col) * L.cell_width;
    const double oy = kMargin + L.legend_height + static_cast<double>(row) * L.cell_height;
    const bool last_in_column = i + L.columns >= f.panels.size();
    draw_panel(cr, f.panels[i], scales[i].first, scales[i].second, px, oy, L,
               !one_ylabel && (!f.shared_axes || col == 0), !f.shared_axes || last_in_column,
               px - L.left + kFontSize * 0.6);
  }
  if (one_ylabel && !f.panels[0].y.label.empty()) {
    const double top = kMargin + L.legend_height + L.top;
    const double bottom = kMargin + L.legend_height +
                          static_cast<double>(L.rows - 1) * L.cell_height + L.top + L.plot_height;
    cairo_set_source_rgb(cr, 0, 0, 0);
    set_font(cr, kFontSize);
    draw_text(cr, f.panels[0].y.label, kMargin + kFontSize * 0.6, (top + bottom) / 2, 0.5,
              -M_PI / 2);
  }
}

// The scales of every panel: data ranges (intervals clipped to the axis' bounds), widened by the
// references near the data; small multiples share their scales, so that panels compare at a
// glance.
std::vector<std::pair<Scale, Scale>> make_scales(const Figure& figure) {
  std::vector<std::pair<Range, Range>> ranges;
  Range all_x, all_y;
  for (const auto& p : figure.panels) {
    Range x, y;
    data_ranges(p, x, y);
    ranges.emplace_back(x, y);
    for (double v : {x.lo, x.hi}) all_x.add(v);
    for (double v : {y.lo, y.hi}) all_y.add(v);
  }
  if (figure.shared_axes) {
    Range x = all_x, y = all_y;
    for (const auto& p : figure.panels) {
      Range px = all_x, py = all_y;
      reference_ranges(p, px, py);
      for (double v : {px.lo, px.hi}) x.add(v);
      for (double v : {py.lo, py.hi}) y.add(v);
    }
    all_x = x;
    all_y = y;
  } else {
    for (std::size_t i = 0; i < figure.panels.size(); ++i) {
      reference_ranges(figure.panels[i], ranges[i].first, ranges[i].second);
    }
  }
  std::vector<std::pair<Scale, Scale>> scales;
  for (std::size_t i = 0; i < figure.panels.size(); ++i) {
    const Range& x = figure.shared_axes ? all_x : ranges[i].first;
    const Range& y = figure.shared_axes ? all_y : ranges[i].second;
    scales.emplace_back(make_scale(figure.panels[i].x, x), make_scale(figure.panels[i].y, y));
  }
  return scales;
}

}  // namespace

std::vector<PanelAxes> axis_ranges(const Figure& figure) {
  const auto scales = make_scales(figure);
  std::vector<PanelAxes> out;
  for (std::size_t i = 0; i < scales.size(); ++i) {
    PanelAxes a;
    a.x = {scales[i].first.min, scales[i].first.max, scales[i].first.ticks};
    a.y = {scales[i].second.min, scales[i].second.max, scales[i].second.ticks};
    for (const auto& ref : figure.panels[i].refs) {
      if (outside(ref.vertical ? scales[i].first : scales[i].second, ref.value)) {
        a.off_axis.push_back(ref);
      }
    }
    out.push_back(std::move(a));
  }
  return out;
}

namespace {

// cairo and fontconfig keep font caches for the life of the process; releasing them at exit keeps
// leak checkers (the ASan build) quiet about memory that is not really lost.
void release_font_caches_at_exit() {
  static const bool registered = [] {
    std::atexit([] {
      cairo_debug_reset_static_data();
      FcFini();
    });
    return true;
  }();
  (void)registered;
}

}  // namespace

std::string render(const Figure& figure, Width width, FileFormat format) {
  release_font_caches_at_exit();
  const std::vector<std::pair<Scale, Scale>> scales = make_scales(figure);
  // Measure text on a scratch surface: the layout depends on label widths.
  SurfacePtr scratch(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1));
  ContextPtr measure(cairo_create(scratch.get()));
  cairo_font_options_t* opts = cairo_font_options_create();
  cairo_font_options_set_hint_metrics(opts, CAIRO_HINT_METRICS_OFF);
  cairo_font_options_set_hint_style(opts, CAIRO_HINT_STYLE_NONE);
  cairo_set_font_options(measure.get(), opts);
  const Layout L = make_layout(measure.get(), figure, width, scales);

  std::string bytes;
  SurfacePtr surface;
  const double dpi = 300.0;
  switch (format) {
    case FileFormat::pdf:
      surface.reset(
          cairo_pdf_surface_create_for_stream(append_to_string, &bytes, L.width, L.height));
      // pdflatex includes PDF up to version 1.5 without a warning.
      cairo_pdf_surface_restrict_to_version(surface.get(), CAIRO_PDF_VERSION_1_5);
      cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "feint");
      // No creation date (cairo writes the clock's by default): the same data give the same
      // bytes, so a report kept in git changes only when its numbers do.
      cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, "");
      break;
    case FileFormat::svg:
      surface.reset(
          cairo_svg_surface_create_for_stream(append_to_string, &bytes, L.width, L.height));
      break;
    case FileFormat::png:
      surface.reset(cairo_image_surface_create(CAIRO_FORMAT_ARGB32,
                                               static_cast<int>(std::ceil(L.width * dpi / 72)),
                                               static_cast<int>(std::ceil(L.height * dpi / 72))));
      break;
  }
  check(cairo_surface_status(surface.get()), "cannot create the surface");
  ContextPtr cr(cairo_create(surface.get()));
  cairo_set_font_options(cr.get(), opts);
  cairo_font_options_destroy(opts);
  if (format == FileFormat::png) {
    cairo_set_source_rgb(cr.get(), 1, 1, 1);
    cairo_paint(cr.get());
    cairo_scale(cr.get(), dpi / 72, dpi / 72);
  }
  draw(cr.get(), figure, L, scales);
  check(cairo_status(cr.get()), "drawing failed");
  cr.reset();
  if (format == FileFormat::png) {
    check(cairo_surface_write_to_png_stream(surface.get(), append_to_string, &bytes),
          "cannot write PNG");
  } else {
    cairo_surface_finish(surface.get());
    check(cairo_surface_status(surface.get()), "cannot finish the surface");
  }
  return bytes;
}

void render_to_file(const Figure& figure, Width width, const std::string& path) {
  io::write_file_atomically(path, render(figure, width, format_from_path(path)));
}

}  // namespace feint::plot

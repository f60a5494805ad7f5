// feint/plot/canvas.hpp - a small plotting layer over cairo: panels with axes at round-number
// ticks, lines with markers, confidence bands, error bars, reference lines, stacked bars and a
// legend, drawn by one code into PDF (for pdflatex's \includegraphics), SVG (for the web) and PNG.
//
// A Figure is a description (plain data); render() lays it out for a paper's one-column (3.5 in)
// or two-column (7.16 in) width. Text is 8 pt (tick labels 7 pt) at either width, so a figure's
// lettering matches the paper's whatever its size. Series differ in colour (Okabe & Ito's
// colour-blind-safe palette), line style and marker, so they survive greyscale printing.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace feint::plot {

enum class FileFormat { pdf, svg, png };

/// By the path's extension: .pdf, .svg, .png (case-insensitive). Throws UsageError otherwise.
FileFormat format_from_path(std::string_view path);
/// "pdf", "svg", "png" (case-insensitive). Throws UsageError otherwise.
FileFormat parse_file_format(std::string_view name);
std::string_view extension(FileFormat format) noexcept;

/// A paper's column widths (IEEE/ACM two-column layouts).
enum class Width { one_column, two_column };
inline constexpr double kOneColumnInches = 3.5;
inline constexpr double kTwoColumnInches = 7.16;
inline constexpr double kFontSize = 8.0;      ///< pt, labels, titles and legend
inline constexpr double kTickFontSize = 7.0;  ///< pt
/// "one" / "1" / "one-column", "two" / "2" / "two-column". Throws UsageError otherwise.
Width parse_width(std::string_view name);
double width_inches(Width width) noexcept;

struct Colour {
  double r = 0, g = 0, b = 0;  ///< in [0, 1]
};
/// Okabe & Ito (2008), "Color Universal Design": black, orange, sky blue, bluish green, yellow,
/// blue, vermillion, reddish purple; `i` wraps around. Series use okabe_ito(series_colour(i)).
Colour okabe_ito(std::size_t i) noexcept;

enum class Marker { none, circle, square, triangle, diamond, cross };
enum class Dash { solid, dashed, dotted, dash_dot };

struct Style {
  Colour colour;
  Dash dash = Dash::solid;
  Marker marker = Marker::circle;
};
/// The i-th series' style: colour, dash and marker all change with i (greyscale-safe); the
/// yellow of the palette is skipped (too light on white).
Style series_style(std::size_t i) noexcept;

/// The colour code of every figure: the i-th condition (in the study's order) is blue, solid,
/// circles; the second orange, dashed, squares (Okabe-Ito's blue and orange differ in lightness
/// too, so they survive greyscale); further conditions bluish green / dotted / triangles and
/// reddish purple / dash-dot / diamonds. No other series uses blue or orange.
Style condition_style(std::size_t i) noexcept;
/// The second palette, for strategies drawn as filled areas (stacked bars): bluish green, yellow,
/// dark grey, reddish purple, sky blue, vermillion; the first four differ in lightness too
/// (greyscale).
/// Figures that use it say so in the legend ("Strategy:").
Colour strategy_colour(std::size_t i) noexcept;

enum class ErrorBars { none, vertical, horizontal };

/// A series of points, joined or not, with optional markers, band and error bars. A NaN in y
/// breaks the line (a missing value).
struct Line {
  std::string label;  ///< legend text ("" = not in the legend)
  std::vector<double> x, y;
  /// Interval per point (same size as x): a shaded band (band = true) or error bars.
  std::vector<double> lo, hi;
  bool band = false;
  ErrorBars error_bars = ErrorBars::none;
  Style style;
  bool connect = true;
  double line_width = 1.0;  ///< pt
  double opacity = 1.0;
  /// A white outline under the line, so that it stands out over faint lines (means over
  /// participants).
  bool halo = false;
  /// Per point: filled (true) or hollow (false) marker; empty = all filled.
  std::vector<bool> filled;
};

/// A horizontal (vertical = false) or vertical reference line, dashed grey, with a label at its
/// end. A reference does not stretch the axis far beyond the data: it is drawn as a line when it
/// lies inside the data's range widened by kReferenceReach of its span (or inside the axis's
/// fixed min/max); otherwise as an arrow at the plot's edge pointing towards it, with its label.
struct RefLine {
  double value = 0;
  bool vertical = false;
  std::string label;
};
/// See RefLine: how far beyond the data (a fraction of the data's span) a reference still widens
/// the axis.
inline constexpr double kReferenceReach = 0.25;

/// Stacked bars on a categorical axis: bar k sits at `positions[k]` and its segments follow each
/// other along the value axis from `start[k]` (0 when empty).
struct Bars {
  bool horizontal = false;  ///< categories on the y axis, values along x
  std::vector<double> positions;
  std::vector<std::vector<double>> segments;  ///< [bar][segment], lengths >= 0
  std::vector<double> start;
  std::vector<Colour> colours;  ///< per segment
  double thickness = 0.7;       ///< in category units
};

struct Axis {
  std::string label;  ///< with units, e.g. "Error (pad units)"
  std::optional<double> min, max;
  /// The metric's range (e.g. [0, 1] for error and confusion): the fitted axis never goes beyond
  /// it, and bands and error bars are clipped to it. Unset = unbounded.
  std::optional<double> bound_min, bound_max;
  /// Tick positions; empty = round numbers chosen from the range.
  std::vector<double> ticks;
  /// Category names at positions (replaces numeric tick labels).
  std::vector<std::pair<double, std::string>> categories;
  bool percent = false;          ///< tick labels as "50%" (values in percent)
  bool absolute_labels = false;  ///< tick labels of |value| (diverging bars)
};

struct Panel {
  std::string title;
  Axis x, y;
  std::optional<Bars> bars;  ///< drawn first
  std::vector<Line> lines;   ///< drawn in order, bands below all lines
  std::vector<RefLine> refs;
  /// x positions marked with an asterisk at the top of the panel (e.g. significant iterations).
  std::vector<double> marks;
  /// A small note in the plot area's lower right corner (e.g. "n = 40 / 53").
  std::string note;
};

struct LegendEntry {
  enum class Kind { line, box, asterisk, band, marker, text };  ///< text: a heading, no sample
  Kind kind = Kind::line;
  std::string label;
  Style style;
  bool hollow = false;  ///< line, marker: hollow marker
};

struct Figure {
  std::vector<Panel> panels;
  std::size_t columns = 1;  ///< panels per row
  std::vector<LegendEntry> legend;
  double aspect = 0.62;  ///< plot-area height / width of one panel
  /// Panels are this fraction of their width at the one-column size when more than one column is
  /// drawn there (small multiples stay readable): columns at one-column width = min(columns, this).
  std::size_t max_columns_narrow = 2;
  /// Small multiples: the y label only left of the first column, the x label only under the
  /// last row, and the columns closer together.
  bool shared_axes = false;
  /// Upper bound of a plot area's height in pt (e.g. bar charts: a fixed height per bar).
  double max_plot_height = 180.0;
};

/// Draws `figure` at `width` in `format`; returns the file's bytes. Throws std::runtime_error when
/// cairo fails (a bug or out of memory).
std::string render(const Figure& figure, Width width, FileFormat format);

/// The limits and ticks render() draws a panel's axes with, and the references it draws as edge
/// arrows (outside the axis), so tests can check them.
struct AxisRange {
  double min = 0, max = 1;
  std::vector<double> ticks;
};
struct PanelAxes {
  AxisRange x, y;
  std::vector<RefLine> off_axis;  ///< references drawn as arrows at the edge
};
std::vector<PanelAxes> axis_ranges(const Figure& figure);

/// render() and an atomic write to `path` (IoError when it cannot be written).
void render_to_file(const Figure& figure, Width width, const std::string& path);

namespace detail {
/// Round-number ticks covering [lo, hi]: steps of 1, 2, 2.5 or 5 times a power of ten, about
/// `target` of them, all inside [lo, hi] (within rounding).
std::vector<double> nice_ticks(double lo, double hi, int target = 5);
/// A tick label: the fewest decimals that tell the ticks apart (0.25 -> "0.25", 5 -> "5").
std::string tick_label(double value, double step);
}  // namespace detail

}  // namespace feint::plot

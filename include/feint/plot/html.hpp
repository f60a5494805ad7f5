// feint/plot/html.hpp - a self-contained HTML page (the study report of `feint analyze`): inline
// CSS and inline SVG figures, no script, font, stylesheet or image fetched from anywhere, so the
// file opens from a USB stick with no network. Reads at laptop widths and prints on A4.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace feint::plot {

struct HtmlSection {
  std::string id;       ///< anchor (letters, digits, '-')
  std::string heading;  ///< plain text
  std::string html;     ///< the body, already HTML
};

struct HtmlReport {
  std::string title;     ///< plain text
  std::string subtitle;  ///< plain text
  std::vector<HtmlSection> sections;
  std::string footer;  ///< plain text
};

/// The Markdown that feint's table writers produce, as HTML: pipe tables (alignment from the
/// separator row, bold cells), paragraphs, **bold** and *emphasis*. Nothing else is interpreted.
std::string markdown_to_html(std::string_view markdown);

/// cairo's SVG made fit for inlining in a page beside others: the XML declaration removed, every
/// id (glyphs, clips) prefixed with `id_prefix` so figures do not share ids, the fixed size
/// replaced by a width of 100% (the viewBox keeps the aspect), and an accessible title.
std::string inline_svg(std::string_view svg, std::string_view id_prefix, std::string_view title);

/// The whole page: title, a contents list, the sections, the footer.
std::string render_html(const HtmlReport& report);

}  // namespace feint::plot

// The drawing layer: round-number ticks, file formats, every kind of figure rendered to PDF, SVG
// and PNG (the SVG parses as XML), and the self-contained HTML page.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "feint/error.hpp"
#include "feint/plot/canvas.hpp"
#include "feint/plot/html.hpp"

using namespace feint;
using namespace feint::plot;
namespace fs = std::filesystem;

TEST(Ticks, AreRoundNumbersInsideTheRange) {
  EXPECT_EQ(detail::nice_ticks(0, 1), (std::vector<double>{0, 0.25, 0.5, 0.75, 1}));
  const auto fine = detail::nice_ticks(0.3, 0.58);  // not just 0.3, 0.4, 0.5
  const std::vector<double> expected = {0.3, 0.35, 0.4, 0.45, 0.5, 0.55};
  ASSERT_EQ(fine.size(), expected.size());
  for (std::size_t i = 0; i < fine.size(); ++i) EXPECT_NEAR(fine[i], expected[i], 1e-12);
  const auto t = detail::nice_ticks(0.27, 0.59);
  ASSERT_FALSE(t.empty());
  for (double v : t) {
    EXPECT_GE(v, 0.27);
    EXPECT_LE(v, 0.59);
    EXPECT_NEAR(std::fmod(v * 1000, 50), 0, 1e-6) << v;  // multiples of 0.05
  }
  EXPECT_EQ(detail::nice_ticks(1, 20), (std::vector<double>{5, 10, 15, 20}));
  EXPECT_EQ(detail::nice_ticks(-100, 100), (std::vector<double>{-100, -50, 0, 50, 100}));
  EXPECT_EQ(detail::nice_ticks(0, 1, 4), (std::vector<double>{0, 0.25, 0.5, 0.75, 1}));
  EXPECT_TRUE(detail::nice_ticks(1, 0).empty());
}

TEST(Ticks, LabelsUseTheFewestDecimalsThatTellThemApart) {
  EXPECT_EQ(detail::tick_label(0.25, 0.25), "0.25");
  EXPECT_EQ(detail::tick_label(0.5, 0.25), "0.50");
  EXPECT_EQ(detail::tick_label(5, 5), "5");
  EXPECT_EQ(detail::tick_label(0.6000000000000001, 0.2), "0.6");
  EXPECT_EQ(detail::tick_label(-0.0, 0.1), "0.0");
}

TEST(Formats, FromTheFileExtension) {
  EXPECT_EQ(format_from_path("a/fig.PDF"), FileFormat::pdf);
  EXPECT_EQ(format_from_path("fig.svg"), FileFormat::svg);
  EXPECT_EQ(format_from_path("fig.png"), FileFormat::png);
  EXPECT_THROW(format_from_path("fig.jpg"), UsageError);
  EXPECT_THROW(format_from_path("dir.pdf/fig"), UsageError);
  EXPECT_EQ(parse_width("two"), Width::two_column);
  EXPECT_THROW(parse_width("three"), UsageError);
}

TEST(Palette, SeriesDifferInColourDashAndMarker) {
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t j = i + 1; j < 4; ++j) {
      const Style a = series_style(i), b = series_style(j);
      EXPECT_NE(a.dash, b.dash);
      EXPECT_NE(a.marker, b.marker);
      EXPECT_FALSE(a.colour.r == b.colour.r && a.colour.g == b.colour.g &&
                   a.colour.b == b.colour.b);
    }
  }
}

namespace {

Figure every_element() {
  Figure f;
  Panel p;
  Line l;
  l.label = "adaptive";
  l.style = series_style(0);
  l.band = true;
  l.x = {1, 2, 3, 4};
  l.y = {0.4, 0.5, std::nan(""), 0.45};
  l.lo = {0.3, 0.4, std::nan(""), -INFINITY};
  l.hi = {0.5, 0.6, std::nan(""), 0.5};
  l.filled = {true, false, true, true};
  p.lines.push_back(l);
  Line e = l;
  e.band = false;
  e.error_bars = ErrorBars::vertical;
  e.style = series_style(1);
  e.label = "random ≈ χ²";
  p.lines.push_back(e);
  p.refs.push_back({0.5, false, "R = 0.5"});
  p.marks = {2};
  p.x.label = "Iteration";
  p.y.label = "Error (pad units)";
  p.title = "title & <escaped>";
  f.panels.push_back(p);
  Panel b;
  Bars bars;
  bars.horizontal = true;
  bars.positions = {0, 1};
  bars.segments = {{10, 20, 70}, {50, 0, 50}};
  bars.start = {-20, -50};
  bars.colours = {okabe_ito(6), okabe_ito(0), okabe_ito(5)};
  b.bars = bars;
  b.y.categories = {{0, "trust"}, {1, "deception"}};
  b.x.percent = true;
  b.x.absolute_labels = true;
  f.panels.push_back(b);
  f.columns = 2;
  f.legend = {{LegendEntry::Kind::band, "adaptive", series_style(0), false},
              {LegendEntry::Kind::line, "random", series_style(1), true},
              {LegendEntry::Kind::box, "box", series_style(2), false},
              {LegendEntry::Kind::marker, "hollow", series_style(3), true},
              {LegendEntry::Kind::asterisk, "A ≠ B", {}, false}};
  return f;
}

bool have_xmllint() { return std::system("command -v xmllint >/dev/null 2>&1") == 0; }

}  // namespace

TEST(Render, PdfIsTheSameBytesForTheSameFigure) {
  const Figure f = every_element();
  const std::string first = render(f, Width::one_column, FileFormat::pdf);
  EXPECT_EQ(first.find("/CreationDate"), std::string::npos);  // no clock in the file
  EXPECT_EQ(render(f, Width::one_column, FileFormat::pdf), first);
}

TEST(Render, WritesPdfSvgAndPngAtBothWidths) {
  const Figure f = every_element();
  for (const auto w : {Width::one_column, Width::two_column}) {
    const std::string pdf = render(f, w, FileFormat::pdf);
    EXPECT_EQ(pdf.rfind("%PDF-1.5", 0), 0u);
    EXPECT_NE(pdf.find("%%EOF"), std::string::npos);
    const std::string svg = render(f, w, FileFormat::svg);
    EXPECT_NE(svg.find("<svg"), std::string::npos);
    // The page is exactly the paper's column width (in points).
    const double pt = width_inches(w) * 72;
    EXPECT_NE(svg.find("width=\"" + std::to_string(static_cast<int>(pt))), std::string::npos)
        << svg.substr(0, 300);
    const std::string png = render(f, w, FileFormat::png);
    EXPECT_EQ(png.substr(1, 3), "PNG");
  }
}

TEST(Render, SvgParsesAsXml) {
  if (!have_xmllint()) GTEST_SKIP() << "xmllint not installed (Debian: libxml2-utils): skipped";
  const fs::path p =
      fs::temp_directory_path() / ("feint-svg-" + std::to_string(::getpid()) + ".svg");
  std::ofstream(p, std::ios::binary) << render(every_element(), Width::one_column, FileFormat::svg);
  EXPECT_EQ(std::system(("xmllint --noout '" + p.string() + "'").c_str()), 0);
  fs::remove(p);
}

TEST(Render, FontIsTheSameSizeAtBothWidths) {
  // The layout differs, the lettering does not: the 8 pt glyphs of the SVG are identical.
  const std::string one = render(every_element(), Width::one_column, FileFormat::svg);
  const std::string two = render(every_element(), Width::two_column, FileFormat::svg);
  auto first_glyph = [](const std::string& s) {
    const auto a = s.find("<symbol");
    return s.substr(a, s.find("</symbol>", a) - a);
  };
  EXPECT_EQ(first_glyph(one), first_glyph(two));
}

TEST(Html, InlineSvgHasPrefixedIdsNoXmlDeclarationAndATitle) {
  const std::string svg = render(every_element(), Width::two_column, FileFormat::svg);
  ASSERT_NE(svg.find("id=\"glyph"), std::string::npos);
  const std::string in = inline_svg(svg, "f3-", "Error & co");
  EXPECT_EQ(in.find("<?xml"), std::string::npos);
  EXPECT_EQ(in.find("id=\"glyph"), std::string::npos);
  EXPECT_NE(in.find("id=\"f3-glyph"), std::string::npos);
  EXPECT_EQ(in.find("href=\"#glyph"), std::string::npos);
  EXPECT_NE(in.find("<title id=\"f3-title\">Error &amp; co</title>"), std::string::npos);
  EXPECT_EQ(in.find(" width=\"516"), std::string::npos);
  EXPECT_NE(in.find("viewBox"), std::string::npos);
}

TEST(Html, MarkdownTablesBecomeHtmlTables) {
  const std::string md =
      "**Caption**\n\n|  | **Error** |  |\n|---|---:|---|\n| **Iteration** | **Mean** | **p** |\n"
      "| **Condition: A** |  |  |\n| 1 | 0.4 < 0.5 | M≈R |\n\n*Note.* Text & more.\n";
  const std::string html = markdown_to_html(md);
  EXPECT_NE(html.find("<p><strong>Caption</strong></p>"), std::string::npos) << html;
  EXPECT_NE(html.find("<th colspan=\"2\"><strong>Error</strong></th>"), std::string::npos) << html;
  EXPECT_NE(html.find("<tr class=\"section\"><th colspan=\"3\"><strong>Condition: A</strong>"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("<td class=\"num\">0.4 &lt; 0.5</td>"), std::string::npos) << html;
  EXPECT_NE(html.find("<p><em>Note.</em> Text &amp; more.</p>"), std::string::npos) << html;
}

TEST(Html, PageIsSelfContained) {
  HtmlReport r;
  r.title = "Study <demo>";
  r.sections.push_back({"a", "A & B", "<p>x</p>"});
  r.footer = "feint";
  const std::string page = render_html(r);
  EXPECT_NE(page.find("<title>Study &lt;demo&gt;</title>"), std::string::npos);
  EXPECT_NE(page.find("<a href=\"#a\">A &amp; B</a>"), std::string::npos);
  EXPECT_NE(page.find("@media print"), std::string::npos);
  EXPECT_NE(page.find("size: A4"), std::string::npos);
  for (const char* fetch : {"<script", "<link", "@import", "url(", "http://", "https://", "src="}) {
    EXPECT_EQ(page.find(fetch), std::string::npos) << fetch;
  }
}

// The map figure of a K-target study (plot/map_figure.hpp): the markers where the layout puts them
// (equal aspect) in the PNG, the same bytes for the same data, and the caption and alt text. The
// map's data (the canonical frame, the means at normalised time, the logs read into them) are
// tested by hand in tests/analysis/test_map_data.cpp.
#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "feint/metrics/mean_map.hpp"
#include "feint/plot/map_figure.hpp"

using namespace feint;
using plot::MapPoint;

namespace {

metrics::MapTrial trial(const metrics::Layout& l, std::size_t target, std::vector<double> t,
                        std::vector<double> px, std::vector<double> py, std::vector<double> rx,
                        std::vector<double> ry) {
  metrics::MapTrial m;
  m.strategy = "exaggerating";
  m.variant = "main";
  m.layout = l;
  m.true_target = target;
  m.times = std::move(t);
  m.pointer_x = std::move(px);
  m.pointer_y = std::move(py);
  m.robot_x = std::move(rx);
  m.robot_y = std::move(ry);
  return m;
}

}  // namespace

namespace {

struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // 3 bytes per pixel
};

Image decode_png(const std::string& bytes) {
  struct Reader {
    const std::string* s;
    std::size_t at = 0;
  } reader{&bytes};
  auto read = [](void* closure, unsigned char* data, unsigned int length) {
    auto* r = static_cast<Reader*>(closure);
    if (r->at + length > r->s->size()) return CAIRO_STATUS_READ_ERROR;
    std::memcpy(data, r->s->data() + r->at, length);
    r->at += length;
    return CAIRO_STATUS_SUCCESS;
  };
  cairo_surface_t* s = cairo_image_surface_create_from_png_stream(read, &reader);
  Image img;
  img.width = cairo_image_surface_get_width(s);
  img.height = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      std::uint32_t p;
      std::memcpy(&p, data + y * stride + 4 * x, 4);  // ARGB32, native endian, opaque here
      img.rgb.insert(img.rgb.end(),
                     {static_cast<unsigned char>(p >> 16), static_cast<unsigned char>(p >> 8),
                      static_cast<unsigned char>(p)});
    }
  }
  cairo_surface_destroy(s);
  return img;
}

// The centre of the lowest blob of pixels of exactly `c` (the legend's sample is the one above).
MapPoint lowest_blob_centre(const Image& img, plot::Colour c) {
  const auto r = static_cast<int>(std::lround(c.r * 255)),
             g = static_cast<int>(std::lround(c.g * 255)),
             b = static_cast<int>(std::lround(c.b * 255));
  auto is = [&](int x, int y) {
    const unsigned char* p = &img.rgb[3 * (static_cast<std::size_t>(y) * img.width + x)];
    return std::abs(p[0] - r) <= 2 && std::abs(p[1] - g) <= 2 && std::abs(p[2] - b) <= 2;
  };
  int lowest = -1;
  for (int y = img.height - 1; y >= 0 && lowest < 0; --y) {
    for (int x = 0; x < img.width; ++x) {
      if (is(x, y)) {
        lowest = y;
        break;
      }
    }
  }
  // The blob: the matching pixels within 30 px (a marker is 19 px wide at 300 dpi) of its bottom.
  double sx = 0, sy = 0, n = 0;
  for (int y = std::max(0, lowest - 30); y <= lowest; ++y) {
    for (int x = 0; x < img.width; ++x) {
      if (is(x, y)) {
        sx += x;
        sy += y;
        ++n;
      }
    }
  }
  return n == 0 ? MapPoint{-1, -1} : MapPoint{sx / n, sy / n};
}

// A fixed layout of four targets; every trial goes to T0, so T1..T3 (green, purple, sky blue)
// appear only as their markers (and in the legend, above the map).
plot::MeanMap four_target_map() {
  const metrics::Layout l{{0, 0}, {{0, 4}, {-3, 2}, {2.5, 5}, {3, 1}}};
  metrics::MapAccumulator acc;
  acc.add(trial(l, 0, {0, 1, 2}, {0.5, -0.5, 0}, {2, 3, 4}, {0, -1, 0}, {0, 2, 4}));
  acc.add(trial(l, 0, {0, 2}, {0, 0}, {2, 4}, {0, 0}, {0, 4}));
  return acc.data();
}

}  // namespace

// The targets' markers are where the layout puts them: one scale across and up (equal aspect),
// y up, to a pixel, at both widths.
TEST(MapFigure, TargetMarkersSitWhereTheLayoutPutsThemAtEqualAspect) {
  const plot::MeanMap d = four_target_map();
  const plot::Figure f = plot::map_figure(d);
  for (const auto width : {plot::Width::one_column, plot::Width::two_column}) {
    const Image img = decode_png(plot::render(f, width, plot::FileFormat::png));
    std::vector<MapPoint> px;
    for (std::size_t k = 1; k <= 3; ++k)
      px.push_back(lowest_blob_centre(img, plot::target_colour(k)));
    const std::vector<MapPoint> map = {d.layout.targets[1], d.layout.targets[2],
                                       d.layout.targets[3]};
    // Pixels per metre from T1 -> T2 across; then everything else must follow from it.
    const double scale = (px[1].x - px[0].x) / (map[1].x - map[0].x);
    EXPECT_GT(scale, 10);
    for (std::size_t i = 1; i < 3; ++i) {
      EXPECT_NEAR(px[i].x - px[0].x, scale * (map[i].x - map[0].x), 1.0) << "target " << i + 1;
      EXPECT_NEAR(px[i].y - px[0].y, -scale * (map[i].y - map[0].y), 1.0) << "target " << i + 1;
    }
  }
}

// cairo numbers its SVG surfaces per process ("surface116"): that id aside, the bytes are equal.
// (Two runs of feint analyze, two processes, write identical files: tests/publish/test_map_report.)
std::string without_surface_id(std::string svg) {
  const auto at = svg.find("<g id=\"surface");
  if (at != std::string::npos) svg.erase(at, svg.find('"', at + 7) - at);
  return svg;
}

TEST(MapFigure, SameDataSameBytes) {
  const plot::Figure f = plot::map_figure(four_target_map());
  for (const auto format : {plot::FileFormat::pdf, plot::FileFormat::svg, plot::FileFormat::png}) {
    const std::string a = plot::render(f, plot::Width::two_column, format);
    const std::string b =
        plot::render(plot::map_figure(four_target_map()), plot::Width::two_column, format);
    EXPECT_TRUE(format == plot::FileFormat::svg ? without_surface_id(a) == without_surface_id(b)
                                                : a == b)
        << plot::extension(format);
  }
}

TEST(MapFigure, CaptionAndAltTextSayWhatIsDrawn) {
  const plot::MeanMap d = four_target_map();
  const std::string caption = plot::map_caption(d);
  EXPECT_NE(caption.find("One fixed layout of 4 targets (T0 to T3), in metres"), std::string::npos)
      << caption;
  EXPECT_NE(caption.find("(2 trials in all)."), std::string::npos) << caption;
  const std::string alt = plot::alt_text(d);
  EXPECT_NE(alt.find("exaggerating/main"), std::string::npos) << alt;
  // Trial A ends at (0, 4), B at (0, 4): the mean pointer ends on the true target T0.
  EXPECT_NE(alt.find("0.00 to 0.00 m from the true target"), std::string::npos) << alt;
}

// The map of a K-target study (plot/map_figure.hpp): the canonical frame by hand, the mean paths
// at normalised time by hand, the markers where the layout puts them (equal aspect) in the PNG,
// and the same bytes for the same data.
#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/plot/map_figure.hpp"

using namespace feint;
using plot::MapPoint;

namespace {

constexpr double kTol = 1e-12;

void expect_point(MapPoint got, double x, double y, const char* what) {
  EXPECT_NEAR(got.x, x, kTol) << what;
  EXPECT_NEAR(got.y, y, kTol) << what;
}

metrics::Layout layout(MapPoint start, std::vector<MapPoint> targets) {
  return metrics::Layout{start, std::move(targets)};
}

plot::MapTrial trial(const metrics::Layout& l, std::size_t target, std::vector<double> t,
                     std::vector<double> px, std::vector<double> py, std::vector<double> rx = {},
                     std::vector<double> ry = {}) {
  plot::MapTrial m;
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

// Start (1, 2), true target (4, 6): d = (3, 4), |d|^2 = 25, x = (v.x d.y - v.y d.x) / 25,
// y = (v.x d.x + v.y d.y) / 25. Decoy (5, 2): v = (4, 0) -> (16/25, 12/25), bearing atan(4/3) =
// 53.1 deg, on the right; decoy (-2, 6): v = (-3, 4) -> (-24/25, 7/25), bearing 73.7 deg. The
// nearest decoy by bearing is on the right: the frame mirrors x. Pointer (4, 2): v = (3, 0) ->
// (12/25, 9/25), mirrored (-0.48, 0.36).
TEST(MapFrame, HandExampleMirrorsTheNearestDecoyToTheLeft) {
  const auto l = layout({1, 2}, {{5, 2}, {4, 6}, {-2, 6}});
  const plot::CanonicalFrame f = plot::canonical_frame(l, 1);
  EXPECT_TRUE(f.mirrored);
  expect_point(f({1, 2}), 0, 0, "start");
  expect_point(f({4, 6}), 0, 1, "true target");
  expect_point(f({5, 2}), -0.64, 0.48, "nearest decoy");
  expect_point(f({-2, 6}), 0.96, 0.28, "other decoy");
  expect_point(f({4, 2}), -0.48, 0.36, "pointer");
}

// Start (0, 0), true target (0, 2): x = v.x / 2, y = v.y / 2. Decoy (-1, 2) -> (-0.5, 1), bearing
// 26.6 deg, already on the left (no mirror); decoy (3, 1) -> (1.5, 0.5); pointer (1, 1) -> (0.5,
// 0.5).
TEST(MapFrame, HandExampleWithTheNearestDecoyOnTheLeftIsNotMirrored) {
  const auto l = layout({0, 0}, {{-1, 2}, {3, 1}, {0, 2}});
  const plot::CanonicalFrame f = plot::canonical_frame(l, 2);
  EXPECT_FALSE(f.mirrored);
  expect_point(f({0, 2}), 0, 1, "true target");
  expect_point(f({-1, 2}), -0.5, 1, "nearest decoy");
  expect_point(f({3, 1}), 1.5, 0.5, "other decoy");
  expect_point(f({1, 1}), 0.5, 0.5, "pointer");
  EXPECT_THROW(plot::canonical_frame(l, 3), InvalidData);
}

// One fixed layout, two trials with true target 0. A: t = 0, 1, 2, pointer (0,0) (1,0) (1,2), with
// a robot path; B: t = 10, 14, pointer (2,2) -> (4,6), no robot path. At u = 0.25 A is at t = 0.5,
// (0.5, 0), B at t = 11, (2.5, 3): mean (1.5, 1.5). u = 0.5: (1, 0), (3, 4) -> (2, 2). u = 0.75:
// (1, 1), (3.5, 5) -> (2.25, 3). The robot's mean rests on A alone.
TEST(MapMeans, MeanAtNormalisedTimeIsTheHandAverage) {
  const auto l = layout({0, 0}, {{-2, 4}, {2, 4}});
  plot::MapAccumulator acc;
  acc.add(trial(l, 0, {0, 1, 2}, {0, 1, 1}, {0, 0, 2}, {0, -1, -2}, {0, 2, 4}));
  acc.add(trial(l, 0, {10, 14}, {2, 4}, {2, 6}));
  const plot::MapFigureData d = acc.data();
  EXPECT_FALSE(d.canonical);
  EXPECT_EQ(d.layouts, 1u);
  ASSERT_EQ(d.panels.size(), 1u);
  ASSERT_EQ(d.panels[0].means.size(), 1u);
  const plot::MapMean& m = d.panels[0].means[0];
  EXPECT_EQ(m.trials, 2u);
  EXPECT_EQ(m.robot_trials, 1u);
  ASSERT_EQ(m.pointer.size(), plot::kMapPoints);
  expect_point(m.pointer[0], 1, 1, "u = 0");
  expect_point(m.pointer[25], 1.5, 1.5, "u = 0.25");
  expect_point(m.pointer[50], 2, 2, "u = 0.5");
  expect_point(m.pointer[75], 2.25, 3, "u = 0.75");
  expect_point(m.pointer[100], 2.5, 4, "u = 1");
  expect_point(m.robot[50], -1, 2, "robot, u = 0.5 (trial A only)");
  EXPECT_TRUE(d.panels[0].decoys.empty());
}

// Two layouts: each trial goes to the canonical frame before the mean. Trial 1: start (0, 0),
// true target (0, 2), decoy (-1, 2) -> (-0.5, 1); pointer (0, 0) -> (0, 2), i.e. (0, 0) -> (0, 1).
// Trial 2: start (1, 1), true target (3, 1) (east), decoy (3, 2) (north: on the left) -> (-0.5, 1);
// pointer from the decoy (3, 2) to the target (3, 1), i.e. (-0.5, 1) -> (0, 1). At u = 0.5:
// (0, 0.5) and (-0.25, 1), mean (-0.125, 0.75).
TEST(MapMeans, LayoutsPerRoundAreAveragedInTheCanonicalFrame) {
  plot::MapAccumulator acc;
  acc.add(trial(layout({0, 0}, {{0, 2}, {-1, 2}}), 0, {0, 1}, {0, 0}, {0, 2}));
  acc.add(trial(layout({1, 1}, {{3, 2}, {3, 1}}), 1, {5, 9}, {3, 3}, {2, 1}));
  const plot::MapFigureData d = acc.data();
  EXPECT_TRUE(d.canonical);
  EXPECT_EQ(d.layouts, 2u);
  EXPECT_EQ(d.mirrored, 0u);
  EXPECT_EQ(d.targets, 2u);
  ASSERT_EQ(d.panels.size(), 1u);
  const plot::MapMean& m = d.panels[0].means.at(0);
  EXPECT_EQ(m.trials, 2u);
  EXPECT_EQ(m.robot_trials, 0u);
  EXPECT_TRUE(m.robot.empty());
  expect_point(m.pointer[0], -0.25, 0.5, "u = 0");
  expect_point(m.pointer[50], -0.125, 0.75, "u = 0.5");
  expect_point(m.pointer[100], 0, 1, "u = 1");
  ASSERT_EQ(d.panels[0].decoys.size(), 2u);
  expect_point(d.panels[0].decoys[0], -0.5, 1, "decoy of trial 1");
  expect_point(d.panels[0].decoys[1], -0.5, 1, "decoy of trial 2");
  expect_point(d.layout.targets.at(0), 0, 1, "the canonical true target");
}

TEST(MapMeans, ABadTrialIsRefusedAndAddsNothing) {
  const auto l = layout({0, 0}, {{-2, 4}, {2, 4}});
  plot::MapAccumulator acc;
  EXPECT_THROW(acc.add(trial(l, 0, {0, 1}, {0, 1, 2}, {0, 1})), InvalidData);  // sizes differ
  EXPECT_THROW(acc.add(trial(l, 0, {1, 1}, {0, 1}, {0, 1})), InvalidData);     // t not increasing
  EXPECT_THROW(acc.add(trial(l, 2, {0, 1}, {0, 1}, {0, 1})), InvalidData);     // no target 2
  EXPECT_EQ(acc.data().trials, 0u);
  EXPECT_TRUE(acc.data().panels.empty());
}

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
plot::MapFigureData four_target_map() {
  const auto l = layout({0, 0}, {{0, 4}, {-3, 2}, {2.5, 5}, {3, 1}});
  plot::MapAccumulator acc;
  acc.add(trial(l, 0, {0, 1, 2}, {0.5, -0.5, 0}, {2, 3, 4}, {0, -1, 0}, {0, 2, 4}));
  acc.add(trial(l, 0, {0, 2}, {0, 0}, {2, 4}, {0, 0}, {0, 4}));
  return acc.data();
}

}  // namespace

// The targets' markers are where the layout puts them: one scale across and up (equal aspect),
// y up, to a pixel, at both widths.
TEST(MapFigure, TargetMarkersSitWhereTheLayoutPutsThemAtEqualAspect) {
  const plot::MapFigureData d = four_target_map();
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
  const plot::MapFigureData d = four_target_map();
  const std::string caption = plot::map_caption(d);
  EXPECT_NE(caption.find("One fixed layout of 4 targets (T0 to T3), in metres"), std::string::npos)
      << caption;
  EXPECT_NE(caption.find("(2 trials in all)."), std::string::npos) << caption;
  const std::string alt = plot::alt_text(d);
  EXPECT_NE(alt.find("exaggerating/main"), std::string::npos) << alt;
  // Trial A ends at (0, 4), B at (0, 4): the mean pointer ends on the true target T0.
  EXPECT_NE(alt.find("0.00 to 0.00 m from the true target"), std::string::npos) << alt;
}

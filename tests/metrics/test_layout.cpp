// Layouts of K >= 2 targets (docs/many-targets.md "Layouts"): the paper's layout, distances and
// the scale, every rejection of validate with its message, and draw_layout: its documented draw
// order, reproducibility, the spacing invariants over many seeds, restarts, and the errors of a
// region too small for K targets (at once, or after a bounded number of draws).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/metrics/layout.hpp"
#include "feint/rng.hpp"

using feint::Rng;
using feint::UsageError;
using feint::metrics::distance;
using feint::metrics::draw_layout;
using feint::metrics::Layout;
using feint::metrics::layout_scale;
using feint::metrics::LayoutRegion;
using feint::metrics::MapPoint;
using feint::metrics::nearest_target;
using feint::metrics::paper_layout;
using feint::metrics::validate;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// The UsageError message of `f`, or "" when it does not throw one.
template <class F>
std::string usage_error(F f) {
  try {
    f();
  } catch (const UsageError& e) {
    return e.what();
  }
  return {};
}

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "message: " << (text)

std::string layout_error(const Layout& l, double spacing = 1, double start = 1) {
  return usage_error([&] { validate(l, spacing, start); });
}

std::string region_error(const LayoutRegion& r) {
  return usage_error([&] { validate(r); });
}

// Every invariant draw_layout promises: K targets, inside the region, spaced, away from the start.
void expect_keeps_rules(const Layout& l, const LayoutRegion& r, std::size_t k, MapPoint start) {
  ASSERT_EQ(l.targets.size(), k);
  EXPECT_EQ(l.start.x, start.x);
  EXPECT_EQ(l.start.y, start.y);
  for (std::size_t i = 0; i < k; ++i) {
    const MapPoint g = l.targets[i];
    EXPECT_TRUE(g.x >= r.x_min && g.x <= r.x_max && g.y >= r.y_min && g.y <= r.y_max)
        << "target " << i << " (" << g.x << ", " << g.y << ") outside the region";
    EXPECT_GE(distance(g, start), r.min_start_distance) << "target " << i;
    for (std::size_t j = i + 1; j < k; ++j) {
      EXPECT_GE(distance(g, l.targets[j]), r.min_spacing) << "targets " << i << ", " << j;
    }
  }
  EXPECT_NO_THROW(validate(l, r.min_spacing, r.min_start_distance));
}

}  // namespace

TEST(PaperLayout, TwoTargetsInARowAboveTheStart) {
  const Layout l = paper_layout();
  EXPECT_EQ(l.start.x, 0);
  EXPECT_EQ(l.start.y, 0);
  ASSERT_EQ(l.targets.size(), 2u);
  EXPECT_EQ(l.targets[0].x, -2);  // left, pad 0
  EXPECT_EQ(l.targets[0].y, 4);
  EXPECT_EQ(l.targets[1].x, 2);  // right, pad 1
  EXPECT_EQ(l.targets[1].y, 4);
  EXPECT_EQ(layout_scale(l), 4);
  const Layout m = paper_layout(3, 5);
  EXPECT_EQ(m.targets[0].x, -1.5);
  EXPECT_EQ(m.targets[1].y, 5);
  EXPECT_EQ(layout_scale(m), 3);
  EXPECT_NO_THROW(validate(l, 4, 1));
  EXPECT_CONTAINS(usage_error([] { paper_layout(0); }), "target distance 0 must be");
  EXPECT_CONTAINS(usage_error([] { paper_layout(-1); }), "target distance -1 must be");
  EXPECT_CONTAINS(usage_error([] { paper_layout(4, kNaN); }), "target height nan");
}

TEST(LayoutGeometry, DistanceScaleAndNearestTarget) {
  EXPECT_EQ(distance({1, 2}, {4, 6}), 5);
  EXPECT_DOUBLE_EQ(distance({0, 0}, {3e200, 4e200}), 5e200);     // no overflow in the squares
  EXPECT_DOUBLE_EQ(distance({0, 0}, {3e-200, 4e-200}), 5e-200);  // no underflow
  // K = 3: the largest of the three distances (3, 4, 5), wherever it is in the list.
  const Layout l{{0, -5}, {{0, 0}, {3, 0}, {0, 4}}};
  EXPECT_EQ(layout_scale(l), 5);
  EXPECT_EQ(layout_scale(Layout{{0, 0}, {{1, 1}}}), 0);
  EXPECT_EQ(nearest_target(l, {2.9, 0.2}), 1u);
  EXPECT_EQ(nearest_target(l, {0.1, 3}), 2u);
  EXPECT_EQ(nearest_target(l, {1.5, 0}), 0u);  // equally near 0 and 1: the lower index
}

TEST(LayoutValidate, SaysWhatToChange) {
  EXPECT_EQ(layout_error(paper_layout()), "");
  EXPECT_EQ(layout_error(Layout{{0, 0}, {{-2, 4}}}),
            "K = 1: a layout needs at least two targets (add a target)");
  EXPECT_CONTAINS(layout_error(Layout{{0, 0}, {}}), "K = 0: a layout needs at least two targets");
  EXPECT_EQ(layout_error(Layout{{0, 0}, {{0, 3}, {2, 3}, {0.4, 3}}}),
            "targets 0 and 2 are 0.40 m apart, less than the minimum spacing 1 m: move them apart "
            "or lower min_spacing");
  EXPECT_EQ(layout_error(Layout{{0, 0}, {{-2, 4}, {0, 0}}}),
            "target 1 is at the start (0.00 m from it; at least 1 m): move the target or the start");
  EXPECT_EQ(layout_error(Layout{{0, 0}, {{-2, 4}, {0.3, 0.4}}}),
            "target 1 is 0.50 m from the start, less than the minimum 1 m: move it away from the "
            "start or lower min_start_distance");
  // A distance that two decimals would round up to the minimum is printed in full.
  EXPECT_CONTAINS(layout_error(Layout{{0, 0}, {{0, 3}, {0.999, 3}}}), "0.999 m apart");
  // Exactly at the minimum is allowed; a hair below is not.
  EXPECT_EQ(layout_error(paper_layout(), 4), "");
  EXPECT_CONTAINS(layout_error(paper_layout(), 4.000001), "targets 0 and 1 are");
  EXPECT_CONTAINS(layout_error(paper_layout(), 1, 4.5), "target 0 is 4.47 m from the start");
}

TEST(LayoutValidate, PointsOnOneSpotAndNonFiniteValuesAreRefusedEvenWithoutMinimums) {
  EXPECT_EQ(layout_error(Layout{{0, 0}, {{1, 3}, {2, 3}, {1, 3}}}, 0, 0),
            "targets 0 and 2 are at the same point (1, 3): move them apart (a layout's targets "
            "are distinct)");
  EXPECT_CONTAINS(layout_error(Layout{{0, 0}, {{1, 3}, {0, 0}}}, 0, 0), "target 1 is at the start");
  EXPECT_CONTAINS(layout_error(Layout{{0, 0}, {{1, 3}, {kNaN, 3}}}), "target 1 (nan, 3) is not a "
                                                                     "finite point");
  EXPECT_CONTAINS(layout_error(Layout{{kInf, 0}, {{1, 3}, {2, 3}}}), "the start (inf, 0) is not");
  EXPECT_CONTAINS(layout_error(paper_layout(), -1), "min_spacing -1 must be a finite number >= 0");
  EXPECT_CONTAINS(layout_error(paper_layout(), 1, kNaN), "min_start_distance nan must be");
  // Minimums of 0 accept any distinct points.
  EXPECT_EQ(layout_error(Layout{{0, 0}, {{1e-9, 3}, {0, 3}}}, 0, 0), "");
}

TEST(RegionValidate, EveryRejection) {
  EXPECT_EQ(region_error({}), "");
  EXPECT_EQ(region_error({0, 0, 2, 5, 1, 1}), "");  // zero width: a line of targets
  EXPECT_EQ(region_error({3, -3, 2, 5, 1, 1}),
            "region: [3, -3] x [2, 5] m is empty: give x_min <= x_max and y_min <= y_max");
  EXPECT_CONTAINS(region_error({-3, 3, 5, 2, 1, 1}), "[-3, 3] x [5, 2] m is empty");
  EXPECT_CONTAINS(region_error({kNaN, 3, 2, 5, 1, 1}), "region: x_min nan is not a finite number");
  EXPECT_CONTAINS(region_error({-3, 3, 2, kInf, 1, 1}), "region: y_max inf is not a finite");
  EXPECT_CONTAINS(region_error({-1e308, 1e308, 2, 5, 1, 1}), "too wide to draw from");
  EXPECT_CONTAINS(region_error({-3, 3, 2, 5, 0, 1}), "region: min_spacing 0 must be a finite "
                                                     "number > 0");
  EXPECT_CONTAINS(region_error({-3, 3, 2, 5, kNaN, 1}), "region: min_spacing nan");
  EXPECT_CONTAINS(region_error({-3, 3, 2, 5, 1, -2}), "region: min_start_distance -2 must be");
}

TEST(DrawLayout, FollowsTheDocumentedDrawOrder) {
  // The first target is the first draw (nothing to keep away from but the start, which the
  // default region's y >= 2 always keeps): x = x_min + 6 u1, y = 2 + 3 u2.
  for (std::uint64_t seed : {1u, 42u, 20240607u}) {
    Rng rng(seed), ref(seed);
    const Layout l = draw_layout(rng, LayoutRegion{}, 3);
    const double u1 = ref.uniform(), u2 = ref.uniform();
    EXPECT_EQ(l.targets[0].x, -3.0 + 6.0 * u1);
    EXPECT_EQ(l.targets[0].y, 2.0 + 3.0 * u2);
  }
}

TEST(DrawLayout, SameSeedSameLayoutOtherSeedOtherLayout) {
  const LayoutRegion r{};
  Rng a(7), b(7), c(8);
  const Layout la = draw_layout(a, r, 5), lb = draw_layout(b, r, 5), lc = draw_layout(c, r, 5);
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_EQ(la.targets[k].x, lb.targets[k].x);
    EXPECT_EQ(la.targets[k].y, lb.targets[k].y);
  }
  EXPECT_EQ(a(), b());  // and the generators are left in the same state
  EXPECT_NE(la.targets[0].x, lc.targets[0].x);
}

TEST(DrawLayout, KeepsSpacingRegionAndStartDistanceOverManySeeds) {
  const LayoutRegion r{-3, 3, 2, 5, 1.2, 2.5};
  const MapPoint start{0, 0.5};
  for (std::size_t k = 2; k <= 8; ++k) {
    for (std::uint64_t seed = 0; seed < 300; ++seed) {
      Rng rng = Rng::stream(99, seed * 16 + k);
      expect_keeps_rules(draw_layout(rng, r, k, start), r, k, start);
      if (::testing::Test::HasFailure()) FAIL() << "K = " << k << ", seed " << seed;
    }
  }
}

TEST(DrawLayout, StartsOverWhenEarlierTargetsLeaveNoRoom) {
  // A line 3 m long, 1 m spacing, K = 3: a first target near the middle and a second one more
  // than 1 m from it leave no room for the third, so drawing target by target alone gets stuck.
  // Restarting the layout after max_tries / 10 failures in a row finds one every time.
  const LayoutRegion r{0, 3, 5, 5, 1, 1};
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    Rng rng(seed);
    Layout l;
    ASSERT_NO_THROW(l = draw_layout(rng, r, 3)) << "seed " << seed;
    expect_keeps_rules(l, r, 3, {});
  }
}

TEST(DrawLayout, TooSmallRegionIsRefusedAtOnceWithoutDrawing) {
  // Oler's bound for points 1 m apart in a 1 m x 1 m square: 2/sqrt(3) + 2 + 1 = 4.15: K = 5 never
  // fits, whatever the draws. The generator must be untouched (no draw was made).
  Rng rng(3), copy(3);
  const std::string m = usage_error([&] { draw_layout(rng, {0, 1, 2, 3, 1, 1}, 5); });
  EXPECT_EQ(m, "the region [0, 1] x [2, 3] m is too small for K = 5 targets at least 1 m apart (at "
               "most 4 fit, by Oler's bound): enlarge the region, lower min_spacing or use fewer "
               "targets");
  EXPECT_EQ(rng(), copy());
  // A line: the bound is exact (length / spacing + 1): 4 m holds 5 targets 1 m apart, not 6.
  EXPECT_CONTAINS(usage_error([&] { draw_layout(rng, {0, 4, 3, 3, 1, 1}, 6); }), "at most 5 fit");
  // Every point of the region too near the start.
  EXPECT_CONTAINS(usage_error([&] { draw_layout(rng, {-1, 1, 1, 2, 0.1, 3}, 2); }),
                  "every point of the region [-1, 1] x [1, 2] m is closer than min_start_distance "
                  "3 m to the start (0, 0)");
}

TEST(DrawLayout, RegionTooSmallAfterBoundedDrawsNeverHangs) {
  // 4 targets 1 m apart in a 1 m square need its four corners exactly: Oler allows it, uniform
  // draws never find it. draw_layout gives up after max_tries draws with a message.
  Rng rng(5);
  const std::string m = usage_error([&] { draw_layout(rng, {0, 1, 2, 3, 1, 1}, 4, {}, 20000); });
  EXPECT_EQ(m, "could not draw K = 4 targets at least 1 m apart and 1 m from the start in the "
               "region [0, 1] x [2, 3] m within 20000 draws: the region is too small for 4 targets "
               "at that spacing; enlarge it, lower min_spacing or min_start_distance, or use fewer "
               "targets");
  // Exactly max_tries draws (two uniforms each) were made.
  Rng ref(5);
  for (int i = 0; i < 2 * 20000; ++i) ref.uniform();
  EXPECT_EQ(rng(), ref());
}

TEST(DrawLayout, BadArgumentsAreUsageErrors) {
  Rng rng(1);
  EXPECT_CONTAINS(usage_error([&] { draw_layout(rng, {}, 1); }),
                  "K = 1: a layout needs at least two targets");
  EXPECT_CONTAINS(usage_error([&] { draw_layout(rng, {}, 0); }), "K = 0");
  EXPECT_CONTAINS(usage_error([&] { draw_layout(rng, {3, -3, 2, 5, 1, 1}, 3); }), "is empty");
  EXPECT_CONTAINS(usage_error([&] { draw_layout(rng, {}, 3, {kNaN, 0}); }), "the start (nan, 0)");
  EXPECT_CONTAINS(usage_error([&] { draw_layout(rng, {}, 3, {}, 0); }), "max_tries 0");
}

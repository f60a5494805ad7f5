// Error and confusion of a belief point on the map (docs/many-targets.md "Scores for a belief
// point"): the closed-form segment integral against hand values and quadrature, the K = 3 worked
// example with a sideways swing between decoys, the reduction to the 1-D scores (spec examples
// A-E and every trial of data/demo, projected onto two-target layouts), invariance under moving,
// turning and scaling the map, and every rejection.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/io/trace.hpp"
#include "feint/metrics/belief_point.hpp"
#include "feint/metrics/layout.hpp"
#include "feint/metrics/trial_metrics.hpp"
#include "feint/rng.hpp"

using feint::InvalidData;
using feint::UsageError;
using feint::metrics::BeliefPointScore;
using feint::metrics::ConfusionNorm;
using feint::metrics::Layout;
using feint::metrics::MapPoint;
using feint::metrics::MetricSettings;
using feint::metrics::pad_point;
using feint::metrics::paper_layout;
using feint::metrics::score_belief_points;
using feint::metrics::score_trace;
using feint::metrics::detail::mean_distance_to_origin;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kSqrt2 = std::sqrt(2.0);
const double kAsinh1 = std::log(1 + std::sqrt(2.0));  // asinh(1), written as its log form

MetricSettings settings(ConfusionNorm norm, double eps = 1e-9) {
  MetricSettings s;
  s.norm = norm;
  s.deadband = eps;
  return s;
}

BeliefPointScore score(const std::vector<double>& t, const std::vector<MapPoint>& p,
                       const Layout& layout, std::size_t k, std::optional<double> v,
                       const MetricSettings& s) {
  return score_belief_points(t, p, layout, k, v, s);
}

std::vector<MapPoint> project(const Layout& layout, const std::vector<double>& mu) {
  std::vector<MapPoint> p;
  for (double m : mu) p.push_back(pad_point(layout, m));
  return p;
}

// (1/L) integral of |p(u)| along the segment by composite 5-point Gauss-Legendre in long double,
// 400 panels: an independent value for segments that stay away from the origin.
double quadrature_mean(MapPoint p0, MapPoint p1) {
  static const long double x[5] = {0.0L, -0.538469310105683091036L, 0.538469310105683091036L,
                                   -0.906179845938663992798L, 0.906179845938663992798L};
  static const long double w[5] = {0.568888888888888888889L, 0.478628670499366468041L,
                                   0.478628670499366468041L, 0.236926885056189087514L,
                                   0.236926885056189087514L};
  const int panels = 400;
  long double sum = 0;
  for (int j = 0; j < panels; ++j) {
    for (int i = 0; i < 5; ++i) {
      const long double u = (j + 0.5L + 0.5L * x[i]) / panels;
      const long double px = p0.x + (static_cast<long double>(p1.x) - p0.x) * u;
      const long double py = p0.y + (static_cast<long double>(p1.y) - p0.y) * u;
      sum += w[i] * std::sqrt(px * px + py * py) / (2 * panels);
    }
  }
  return static_cast<double>(sum);
}

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "message: " << (text)

template <class E, class F>
std::string message_of(F f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "(no exception of the expected kind)";
}

// The K = 3 worked example of docs/many-targets.md: decoys at (-2, 4) and (2, 4), the true target
// (k* = 2) at (0, 2); scale 4 m. The pointer goes toward the target, back, out to decoy 0, swings
// across to decoy 1 (same distance from the target: no direction, but movement), then to the
// target and stays.
const Layout kThree{{0, 0}, {{-2, 4}, {2, 4}, {0, 2}}};
const std::vector<double> kThreeT{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
const std::vector<MapPoint> kThreeP{{0, 4}, {0, 3}, {0, 4},  {-2, 4}, {2, 4}, {0, 2},
                                    {0, 2}, {0, 2}, {0, 2}, {0, 2},  {0, 2}};

}  // namespace

TEST(MeanDistance, HandValues) {
  EXPECT_EQ(mean_distance_to_origin({0.3, 0.4}, {0.3, 0.4}), 0.5);  // a point that stays at 0.5
  // On a line through the origin: trapezoid; through the origin: two triangles.
  EXPECT_DOUBLE_EQ(mean_distance_to_origin({0, 1}, {0, 3}), 2);
  EXPECT_DOUBLE_EQ(mean_distance_to_origin({1, 0}, {-3, 0}), (1.0 + 9.0) / (2 * 4));
  EXPECT_DOUBLE_EQ(mean_distance_to_origin({-0.6, -0.8}, {0.6, 0.8}), 0.5);
  // Right triangle: the leg from (0, 1) to (1, 1), foot point at its start:
  // integral_0^1 sqrt(q^2 + 1) dq = (sqrt(2) + asinh(1)) / 2.
  EXPECT_NEAR(mean_distance_to_origin({0, 1}, {1, 1}), (kSqrt2 + kAsinh1) / 2, 1e-15);
  EXPECT_NEAR(mean_distance_to_origin({1, 1}, {0, 1}), (kSqrt2 + kAsinh1) / 2, 1e-15);
  // Foot point in the middle: from (-1/2, 1/2) to (1/2, 1/2), h = 1/2:
  // integral_{-1/2}^{1/2} sqrt(q^2 + 1/4) dq = sqrt(2)/4 + asinh(1)/4.
  EXPECT_NEAR(mean_distance_to_origin({-0.5, 0.5}, {0.5, 0.5}), (kSqrt2 + kAsinh1) / 4, 1e-15);
  // Foot point outside, both sides: q from 3/4 to 1 at h = 1 and its mirror.
  const double f = (std::sqrt(2.0) - 0.75 * 1.25 + std::log((1 + kSqrt2) / 2)) / 2 / 0.25;
  EXPECT_NEAR(mean_distance_to_origin({0.75, 1}, {1, 1}), f, 1e-14);
  EXPECT_NEAR(mean_distance_to_origin({-1, -1}, {-0.75, -1}), f, 1e-14);
}

TEST(MeanDistance, MatchesQuadratureOnRandomSegments) {
  feint::Rng rng(2024);
  double worst = 0;
  for (int n = 0; n < 2000; ++n) {
    const MapPoint p0{4 * rng.uniform() - 2, 4 * rng.uniform() - 2};
    const MapPoint p1{4 * rng.uniform() - 2, 4 * rng.uniform() - 2};
    const double dx = p1.x - p0.x, dy = p1.y - p0.y, len = std::hypot(dx, dy);
    if (std::fabs(p0.x * dy - p0.y * dx) / len < 0.05) continue;  // quadrature needs h away from 0
    const double ref = quadrature_mean(p0, p1);
    worst = std::max(worst, std::fabs(mean_distance_to_origin(p0, p1) - ref) / ref);
  }
  std::printf("[ quadrature ] random segments: largest relative difference %.3g\n", worst);
  EXPECT_LT(worst, 1e-14);
}

TEST(MeanDistance, ShortAndNearlyCollinearSegmentsLoseNoPrecision) {
  // 1e-9 long, 5 from the origin: the mean is the midpoint's distance up to L^2 / (8 h) ~ 1e-20;
  // (F(q1) - F(q0)) / L would lose 7 digits here.
  for (const MapPoint d : {MapPoint{-0.8e-9, 0.6e-9}, MapPoint{1e-9, 0}, MapPoint{0.6e-9, 0.8e-9}}) {
    const MapPoint p0{3, 4}, p1{3 + d.x, 4 + d.y};
    EXPECT_NEAR(mean_distance_to_origin(p0, p1), std::hypot(3 + d.x / 2, 4 + d.y / 2), 1e-15);
  }
  // h = 1e-8 beside a segment through the foot point: two triangles plus O(h^2 log(1/h)).
  EXPECT_EQ(mean_distance_to_origin({-1, 0}, {3, 0}), 1.25);
  EXPECT_NEAR(mean_distance_to_origin({-1, 1e-8}, {3, 1e-8}), 1.25, 1e-14);
  // A diagonal line through the origin (h is a rounding residue, not 0): the trapezoid.
  EXPECT_NEAR(mean_distance_to_origin({0.3 * 0.1, 0.7 * 0.1}, {0.3 * 0.9, 0.7 * 0.9}),
              std::hypot(0.3, 0.7) * 0.5, 1e-15);
}

TEST(BeliefPointK3, WorkedExampleWithASidewaysSwing) {
  const double error = (0.53125 + (3 * kSqrt2 + 2 * kAsinh1) / 4) / 9;
  const double moved = 5.125 + 2.25 * kSqrt2;  // M with v = 1 scale/s
  for (double eps : {0.0, 1e-9}) {
    const auto sp = score(kThreeT, kThreeP, kThree, 2, 1.0, settings(ConfusionNorm::speed, eps));
    const auto raw = score(kThreeT, kThreeP, kThree, 2, 1.0, settings(ConfusionNorm::raw, eps));
    EXPECT_NEAR(sp.error, error, 1e-15);
    EXPECT_NEAR(sp.error, 0.225844107254399, 1e-14);
    EXPECT_NEAR(raw.error, error, 1e-15);
    EXPECT_NEAR(sp.confusion, moved / 45, 1e-15);
    EXPECT_NEAR(raw.confusion, moved / 10, 1e-15);
    EXPECT_EQ(sp.reversal_time, 1);
    EXPECT_EQ(sp.reversals, 2);
    EXPECT_EQ(sp.overspeed_segments, 0);
    EXPECT_EQ(raw.overspeed_segments, 0);
    EXPECT_EQ(sp.n_samples, 11u);
    EXPECT_EQ(sp.duration, 10);
    EXPECT_EQ(sp.final_point.x, 0);
    EXPECT_EQ(sp.final_point.y, 2);
    EXPECT_EQ(sp.final_target, 2u);
  }
  // v = 0.5 scale/s: the swing (1 scale/s) and the last approach (sqrt(2)/2) outrun it and count
  // as full movement; 0.5 scale/s is exactly v, not overspeed. M = 0.75 + 2.5 + 3.5 + 4.5.
  const auto slow = score(kThreeT, kThreeP, kThree, 2, 0.5, settings(ConfusionNorm::speed));
  EXPECT_NEAR(slow.confusion, 0.25, 1e-15);
  EXPECT_EQ(slow.overspeed_segments, 2);
  // Without a pointer speed (raw): overspeed is unknown.
  EXPECT_EQ(score(kThreeT, kThreeP, kThree, 2, std::nullopt, settings(ConfusionNorm::raw))
                .overspeed_segments, -1);
}

TEST(BeliefPointK3, ANeverReversingTraceHasNoConfusionAndTheNearestTargetIsReported) {
  // Along the line y = 2 + x from near the true target (0, 2) past decoy 1 (2, 4): always away.
  const std::vector<double> t{0, 1, 2, 3};
  const std::vector<MapPoint> p{{0.5, 2.5}, {1, 3}, {2, 4}, {2.5, 4.5}};
  const auto s = score(t, p, kThree, 2, 1.0, settings(ConfusionNorm::speed));
  EXPECT_EQ(s.confusion, 0);
  EXPECT_TRUE(std::isnan(s.reversal_time));
  EXPECT_EQ(s.reversals, 0);
  EXPECT_EQ(s.final_target, 1u);
  // On a line through G*: r = sqrt(2) x / 4 with x linear in t, so the error is the 1-D trapezoid:
  // x is 0.575 at a = 0.15, 1 at t = 1, 2 at t = 2 and 2.425 at b = 2.85.
  const double x_area = (0.575 + 1) / 2 * 0.85 + 1.5 + (2 + 2.425) / 2 * 0.85;
  EXPECT_NEAR(s.error, kSqrt2 / 4 * x_area / 2.7, 1e-15);
}

TEST(BeliefPointK3, TheDeadBandIgnoresJitterOfTheDistance) {
  // Toward the true target (0, 2), a jitter of 1e-10 scales back, then on to it. With the default
  // dead band (1e-9 scales) the jitter has no direction: no reversal, no confusion. Without one it
  // is a reversal at t = 1, and the approach after it counts: c = 1, b = 2.85, movement
  // (1 + 4e-10) / 4 per second on [2, 2.85] and 1e-10 per second on [1, 2].
  const std::vector<double> t{0, 1, 2, 3};
  const std::vector<MapPoint> p{{0, 4}, {0, 3}, {0, 3 + 4e-10}, {0, 2}};
  const auto with = score(t, p, kThree, 2, std::nullopt, settings(ConfusionNorm::raw));
  EXPECT_EQ(with.confusion, 0);
  EXPECT_TRUE(std::isnan(with.reversal_time));
  EXPECT_EQ(with.reversals, 0);
  const auto without = score(t, p, kThree, 2, std::nullopt, settings(ConfusionNorm::raw, 0));
  EXPECT_EQ(without.reversal_time, 1);
  EXPECT_EQ(without.reversals, 2);
  const double moved = 1e-10 * (4 - 1) / 2 + (1 + 4e-10) / 4 * (2.85 * 2.85 - 4) / 2;
  EXPECT_NEAR(without.confusion, moved / 3, 1e-15);
}

namespace {

struct Example {
  const char* name;
  std::vector<double> t, mu;
  double target, v;
  double error, conf_speed, conf_raw, t_rev;
};

// The spec's worked examples (docs/metrics.md), with their exact values.
std::vector<Example> spec_examples() {
  std::vector<double> ten;
  for (int i = 0; i <= 10; ++i) ten.push_back(i);
  return {
      {"A", ten, {0.5, 0.75, 1, 1, 1, 1, 1, 1, 1, 1, 1}, 1, 0.25, 1.0 / 32, 0, 0, kNaN},
      {"B", ten, {0.5, 0.25, 0, 0, 0, 0, 0, 0.25, 0.5, 0.75, 1}, 1, 0.25, 115.0 / 144,
       217.0 / 360, 217.0 / 320, 6},
      {"C", ten, {0.5, 0.75, 0.5, 0.75, 0.5, 0.75, 0.5, 0.75, 0.5, 0.75, 0.5}, 0, 0.25,
       91.0 / 144, 119.0 / 120, 357.0 / 320, 1},
      {"D", {0, 0.5, 2, 3.5, 4}, {0.5, 0.5, 0.2, 0.6, 0.6}, 0.3, 0.5, 37.0 / 288, 11.0 / 36,
       11.0 / 40, 2},
      {"E", {0, 0.3, 1, 2, 4}, {0.5, 0.6, 0.4, 0.4, 0.9}, 1, 1, 25.0 / 54, 287.0 / 1440,
       287.0 / 800, 0.3},
  };
}

// The paper's layout, one with a target distance that is not a power of two, and a turned and
// moved one: the projection must give the 1-D scores on each.
std::vector<Layout> two_target_layouts() {
  return {paper_layout(), paper_layout(3, 5), Layout{{0.2, -0.3}, {{1.3, 2.7}, {-0.4, 5.1}}}};
}

// The layout for an example's target: T = 0 or 1 is target 0 or 1; any other T (example D's 0.3)
// is a third target at pad_point(T) on the line, so the scale (target 0 to target 1) is unchanged.
std::size_t add_target(Layout& layout, double target) {
  if (target == 0 || target == 1) return static_cast<std::size_t>(target);
  layout.targets.push_back(pad_point(layout, target));
  return layout.targets.size() - 1;
}

}  // namespace

TEST(BeliefPointReduction, SpecWorkedExamplesOnTwoTargetLayouts) {
  for (const auto& ex : spec_examples()) {
    for (Layout layout : two_target_layouts()) {
      SCOPED_TRACE(std::string(ex.name) + " on a layout with target 1 at x = " +
                   std::to_string(layout.targets[1].x));
      const std::size_t k = add_target(layout, ex.target);
      const auto p = project(layout, ex.mu);
      for (double eps : {0.0, 1e-9}) {
        const auto sp = score(ex.t, p, layout, k, ex.v, settings(ConfusionNorm::speed, eps));
        const auto raw = score(ex.t, p, layout, k, ex.v, settings(ConfusionNorm::raw, eps));
        EXPECT_NEAR(sp.error, ex.error, 1e-12);
        EXPECT_NEAR(raw.error, ex.error, 1e-12);
        EXPECT_NEAR(sp.confusion, ex.conf_speed, 1e-12);
        EXPECT_NEAR(raw.confusion, ex.conf_raw, 1e-12);
        if (std::isnan(ex.t_rev)) {
          EXPECT_TRUE(std::isnan(sp.reversal_time));
        } else {
          EXPECT_NEAR(sp.reversal_time, ex.t_rev, 1e-12);
        }
        EXPECT_EQ(sp.overspeed_segments, 0);
      }
    }
  }
}

TEST(BeliefPointReduction, EveryDemoTrialScoresAsThePad) {
  feint::io::TraceReader reader(
      feint::io::expand_inputs({std::string(FEINT_SOURCE_DIR) + "/data/demo/logs"}), {});
  feint::io::Trial trial;
  const auto layouts = two_target_layouts();
  std::vector<double> worst(layouts.size(), 0.0);
  std::size_t trials = 0;
  while (reader.next(trial)) {
    ++trials;
    ASSERT_TRUE(trial.target == 0 || trial.target == 1) << trial.label();
    ASSERT_TRUE(trial.pad_speed) << trial.label();
    const auto k = static_cast<std::size_t>(trial.target);
    for (auto norm : {ConfusionNorm::speed, ConfusionNorm::raw}) {
      const auto one = score_trace(trial.times, trial.pads, trial.target, trial.pad_speed,
                                   settings(norm));
      for (std::size_t j = 0; j < layouts.size(); ++j) {
        const auto p = project(layouts[j], trial.pads);
        const auto two = score_belief_points(trial.times, p, layouts[j], k, trial.pad_speed,
                                             settings(norm));
        worst[j] = std::max({worst[j], std::fabs(two.error - one.error),
                             std::fabs(two.confusion - one.confusion)});
        ASSERT_EQ(std::isnan(two.reversal_time), std::isnan(one.reversal_time)) << trial.label();
        if (!std::isnan(one.reversal_time)) {
          ASSERT_EQ(two.reversal_time, one.reversal_time) << trial.label();
        }
        ASSERT_EQ(two.reversals, one.reversals) << trial.label();
        ASSERT_EQ(two.overspeed_segments, one.overspeed_segments) << trial.label();
        // (A pad ending at exactly 0.5 is equally near both: no nearest target to compare.)
        if (one.final_pad != 0.5) {
          ASSERT_EQ(two.final_target, one.final_pad > 0.5 ? 1u : 0u) << trial.label();
        }
      }
    }
  }
  EXPECT_GT(trials, 1000u);
  for (std::size_t j = 0; j < layouts.size(); ++j) {
    std::printf("[ reduction ] %zu demo trials, layout %zu: largest |difference| %.3g\n", trials,
                j, worst[j]);
    EXPECT_LE(worst[j], 1e-12) << "layout " << j;
  }
}

namespace {

// A random K = 4 trace: points around the layout, uneven sampling.
void random_trace(feint::Rng& rng, std::vector<double>& t, std::vector<MapPoint>& p) {
  t = {0};
  p = {{8 * rng.uniform() - 4, 6 * rng.uniform()}};
  for (int i = 0; i < 30; ++i) {
    t.push_back(t.back() + 0.01 + rng.uniform());
    p.push_back({8 * rng.uniform() - 4, 6 * rng.uniform()});
  }
}

MapPoint move(MapPoint a, double c, double turn, MapPoint shift) {
  return {shift.x + c * (std::cos(turn) * a.x - std::sin(turn) * a.y),
          shift.y + c * (std::sin(turn) * a.x + std::cos(turn) * a.y)};
}

}  // namespace

TEST(BeliefPointInvariance, MovingTurningAndScalingTheMapChangesNoScore) {
  feint::Rng rng(11);
  const Layout base{{0, 0}, {{-3, 4}, {3, 4}, {0, 5.5}, {1, 2}}};
  for (int n = 0; n < 50; ++n) {
    std::vector<double> t;
    std::vector<MapPoint> p;
    random_trace(rng, t, p);
    const double c = 0.1 + 10 * rng.uniform(), turn = 6.283 * rng.uniform();
    const MapPoint shift{100 * rng.uniform() - 50, 100 * rng.uniform() - 50};
    Layout moved{move(base.start, c, turn, shift), {}};
    for (MapPoint g : base.targets) moved.targets.push_back(move(g, c, turn, shift));
    std::vector<MapPoint> q;
    for (MapPoint b : p) q.push_back(move(b, c, turn, shift));
    for (auto norm : {ConfusionNorm::speed, ConfusionNorm::raw}) {
      const auto s0 = score(t, p, base, n % 4, 0.7, settings(norm));
      const auto s1 = score(t, q, moved, n % 4, 0.7, settings(norm));
      EXPECT_NEAR(s1.error, s0.error, 1e-12 * s0.error);
      EXPECT_NEAR(s1.confusion, s0.confusion, 1e-12 * std::max(1.0, s0.confusion));
      EXPECT_EQ(s1.final_target, s0.final_target);
    }
  }
}

TEST(BeliefPointInvariance, ErrorMatchesQuadratureOverTheWholeTrace) {
  // Independent: b(t) by interpolation, |b - G*| / s integrated by Gauss-Legendre on each piece
  // between samples and window ends (pieces split where they pass G*'s foot point).
  feint::Rng rng(5);
  const Layout layout{{0, 0}, {{-3, 4}, {3, 4}, {0, 5.5}, {1, 2}}};
  const double s = feint::metrics::layout_scale(layout);
  double worst = 0;
  for (int n = 0; n < 20; ++n) {
    std::vector<double> t;
    std::vector<MapPoint> p;
    random_trace(rng, t, p);
    const MapPoint g = layout.targets[n % 4];
    const double a = t.back() * 0.05, b = t.back() * 0.95;
    long double integral = 0;
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
      const double lo = std::max(a, t[i]), hi = std::min(b, t[i + 1]);
      if (!(hi > lo)) continue;
      auto at = [&](double x) {
        const double f = (x - t[i]) / (t[i + 1] - t[i]);
        return MapPoint{(p[i].x + (p[i + 1].x - p[i].x) * f - g.x) / s,
                        (p[i].y + (p[i + 1].y - p[i].y) * f - g.y) / s};
      };
      integral += (hi - lo) * quadrature_mean(at(lo), at(hi));
    }
    const auto sc = score(t, p, layout, n % 4, std::nullopt, settings(ConfusionNorm::raw));
    const double ref = static_cast<double>(integral / (b - a));
    worst = std::max(worst, std::fabs(sc.error - ref) / ref);
  }
  std::printf("[ quadrature ] random traces: largest relative difference %.3g\n", worst);
  EXPECT_LT(worst, 1e-13);
}

TEST(BeliefPointValidation, BadTracesAreInvalidData) {
  const Layout l = paper_layout();
  auto bad = [&](std::vector<double> t, std::vector<MapPoint> p, std::size_t k = 1,
                 std::optional<double> v = 1.0, MetricSettings s = settings(ConfusionNorm::speed)) {
    return message_of<InvalidData>([&] { score(t, p, l, k, v, s); });
  };
  EXPECT_EQ(bad({0}, {{0, 4}}), "1 sample(s); a trial needs at least 2");
  EXPECT_EQ(bad({}, {}), "0 sample(s); a trial needs at least 2");
  EXPECT_EQ(bad({0, 1}, {{0, 4}}), "2 times but 1 belief points");
  EXPECT_EQ(bad({0, 1, 1}, {{0, 4}, {0, 4}, {0, 4}}),
            "sample 2: time 1 is not after 1 (times must strictly increase)");
  EXPECT_EQ(bad({0, 2, 1}, {{0, 4}, {0, 4}, {0, 4}}),
            "sample 2: time 1 is not after 2 (times must strictly increase)");
  EXPECT_EQ(bad({0, kNaN}, {{0, 4}, {0, 4}}), "sample 1: time is not finite");
  EXPECT_EQ(bad({0, 1}, {{0, 4}, {kNaN, 4}}), "sample 1: belief point (nan, 4) is not finite");
  EXPECT_EQ(bad({0, 1}, {{0, std::numeric_limits<double>::infinity()}, {0, 4}}),
            "sample 0: belief point (0, inf) is not finite");
  EXPECT_EQ(bad({-1e308, 1e308}, {{0, 4}, {0, 4}}), "duration (1e+308 - -1e+308 s) is not a "
                                                   "finite number");
  EXPECT_EQ(bad({0, 1}, {{0, 4}, {0, 4}}, 2),
            "true target 2 is not a target of the layout (K = 2: targets 0 to 1)");
  EXPECT_CONTAINS(bad({0, 1}, {{0, 4}, {0, 4}}, 1, std::nullopt), "the pointer speed is unknown");
  EXPECT_CONTAINS(bad({0, 1}, {{0, 4}, {0, 4}}, 1, 0.0), "pointer speed 0 must be > 0");
  EXPECT_CONTAINS(bad({0, 1}, {{0, 4}, {0, 4}}, 1, -2.0), "pointer speed -2 must be > 0");
  // A point that jumps 1e300 m in 1 ns after a reversal: the raw confusion is not a number.
  EXPECT_CONTAINS(bad({0, 1, 1 + 1e-9, 2}, {{0, 4}, {1, 4}, {1e300, 4}, {1e300, 4}}, 1,
                      std::nullopt, settings(ConfusionNorm::raw)),
                  "confusion is not a finite number");
}

TEST(BeliefPointValidation, BadLayoutsAndSettingsAreUsageErrors) {
  const std::vector<double> t{0, 1};
  const std::vector<MapPoint> p{{0, 4}, {1, 4}};
  const auto raw = settings(ConfusionNorm::raw);
  EXPECT_CONTAINS(message_of<UsageError>([&] { score(t, p, Layout{{0, 0}, {{1, 4}}}, 0, 1.0, raw); }),
                  "K = 1: a layout needs at least two targets");
  EXPECT_CONTAINS(message_of<UsageError>([&] {
                    score(t, p, Layout{{0, 0}, {{1, 4}, {1, 4}}}, 0, 1.0, raw);
                  }),
                  "targets 0 and 1 are at the same point (1, 4)");
  EXPECT_CONTAINS(message_of<UsageError>([&] {
                    score(t, p, Layout{{0, 0}, {{1, 4}, {kNaN, 4}}}, 0, 1.0, raw);
                  }),
                  "target 1 (nan, 4) is not a finite point");
  auto bad = raw;
  bad.trim_start = 0.7;
  bad.trim_end = 0.4;
  EXPECT_CONTAINS(message_of<UsageError>([&] { score(t, p, paper_layout(), 0, 1.0, bad); }),
                  "--trim-start + --trim-end");
  EXPECT_CONTAINS(message_of<UsageError>([] { pad_point(Layout{{0, 0}, {{1, 1}}}, 0.5); }),
                  "K = 1: a pad value is a point between targets 0 and 1");
}

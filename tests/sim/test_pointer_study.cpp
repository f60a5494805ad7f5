// Studies of K targets (docs/simulation.md "Studies of K targets"): the pointing participant
// against a known truth, and the layouts of the rounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "feint/error.hpp"
#include "feint/metrics/belief_point.hpp"
#include "feint/sim/k_goal_paths.hpp"
#include "feint/sim/options.hpp"
#include "feint/sim/pointer_participant.hpp"
#include "feint/sim/study.hpp"

using namespace feint;

namespace {

double error_of(const std::vector<sim::PointerSample>& p, const metrics::Layout& l, std::size_t k) {
  std::vector<double> t;
  std::vector<metrics::MapPoint> b;
  for (const auto& q : p) {
    t.push_back(q.t);
    b.push_back({q.x, q.y});
  }
  return metrics::score_belief_points(t, b, l, k, std::nullopt, {}).error;
}

}  // namespace

// An observer certain at once (beta 1e4, no delay, no noise): the pointer waits at the centroid
// until the first decision after the start (0.2 s), then runs straight to the true target at
// 0.8 layout scales per second. Its error is computed here from that description alone (the
// distance is linear between samples: trapezoids on the trimmed window are exact).
TEST(PointerStudy, CertainObserverHasTheErrorItsMotionImplies) {
  const metrics::Layout l = sim::row_layout(3, sim::Geometry{});
  sim::ObserverParams p;
  p.beta = 1e4;
  p.reaction_delay = 0;
  p.noise_sd = 0;
  p.move_threshold = 0;
  const auto path = sim::k_goal_trajectory(l, 2, sim::Strategy::optimal, sim::Variant::main);
  Rng rng(1);
  const auto pointer = sim::watch_pointer(path, l, p, rng);
  ASSERT_EQ(pointer.size(), path.size());
  // Distance to target 2 (2, 4) in layout scales (s = 4), from the centroid (0, 4): 0.5.
  std::vector<double> r;
  for (const auto& q : pointer) {
    const double expect = q.t <= 0.2 + 1e-9 ? 0.5 : std::max(0.0, 0.5 - 0.8 * (q.t - 0.2));
    r.push_back(expect);
  }
  // The last step lands on the target at the first sample it could reach it.
  for (std::size_t i = 0; i < pointer.size(); ++i) {
    EXPECT_NEAR(std::hypot(pointer[i].x - 2, pointer[i].y - 4) / 4, r[i], 1e-12) << "sample " << i;
  }
  const double tau = pointer.back().t, a = 0.05 * tau, b = 0.95 * tau;
  double integral = 0;
  for (std::size_t i = 1; i < pointer.size(); ++i) {
    const double t0 = pointer[i - 1].t, t1 = pointer[i].t;
    const double s = std::max(a, t0), e = std::min(b, t1);
    if (!(e > s)) continue;
    auto at = [&](double t) { return r[i - 1] + (r[i] - r[i - 1]) * (t - t0) / (t1 - t0); };
    integral += (at(s) + at(e)) / 2 * (e - s);
  }
  EXPECT_NEAR(error_of(pointer, l, 2), integral / (b - a), 1e-12);
  EXPECT_GT(integral, 0.01);  // not a trivial case
}

// With the study's observer, a feint toward a decoy leaves the pointer farther from the truth.
TEST(PointerStudy, DeceptiveStrategiesHaveHigherErrorThanOptimal) {
  const metrics::Layout l = sim::row_layout(3, sim::Geometry{});
  const sim::ObserverParams p = sim::goal_inference_observer();
  double optimal = 0, exaggerating = 0;
  Rng rng(7);
  for (int rep = 0; rep < 10; ++rep) {
    for (std::size_t k = 0; k < 3; ++k) {
      optimal += error_of(sim::watch_pointer(sim::k_goal_trajectory(l, k, sim::Strategy::optimal, sim::Variant::main),
                                             l, p, rng),
                          l, k);
      exaggerating += error_of(
          sim::watch_pointer(sim::k_goal_trajectory(l, k, sim::Strategy::exaggerating, sim::Variant::main), l, p, rng),
          l, k);
    }
  }
  EXPECT_LT(optimal / 30, exaggerating / 30 - 0.02) << optimal / 30 << " vs " << exaggerating / 30;
}

TEST(PointerStudy, RowLayoutOfTwoIsThePapers) {
  const auto a = sim::row_layout(2, sim::Geometry{});
  const auto b = metrics::paper_layout();
  ASSERT_EQ(a.targets.size(), 2U);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(a.targets[k].x, b.targets[k].x);
    EXPECT_EQ(a.targets[k].y, b.targets[k].y);
  }
}

TEST(PointerStudy, RandomLayoutsAreSeededPerParticipantAndRoundAndKeepTheirSpacing) {
  sim::StudySettings s;
  s.targets = 4;
  s.random_layout = true;
  s.seed = 11;
  EXPECT_TRUE(sim::is_pointer_study(s));
  const auto a = sim::round_layout(s, 3, 5);
  const auto again = sim::round_layout(s, 3, 5);
  const auto other = sim::round_layout(s, 3, 6);
  ASSERT_EQ(a.targets.size(), 4U);
  EXPECT_EQ(a.targets[0].x, again.targets[0].x);
  EXPECT_NE(a.targets[0].x, other.targets[0].x);
  EXPECT_NO_THROW(metrics::validate(a, s.region.min_spacing, s.region.min_start_distance));
  sim::StudySettings paper;
  EXPECT_FALSE(sim::is_pointer_study(paper));
}

TEST(PointerStudy, OptionsCheckTargetsAndLayout) {
  sim::StudyOptions o;
  o.targets = 1;
  EXPECT_THROW(sim::study_settings(o), UsageError);
  o.targets = 3;
  o.layout = "circle";
  EXPECT_THROW(sim::study_settings(o), UsageError);
  o.layout = "random";
  const auto s = sim::study_settings(o);
  EXPECT_EQ(s.targets, 3);
  EXPECT_TRUE(s.random_layout);
}

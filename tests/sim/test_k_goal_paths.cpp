// Deceptive paths among K targets (feint/sim/k_goal_paths.hpp): the paper's paths at K = 2 bit for
// bit, the K = 3 worked example of docs/deceptive-paths.md, Masters & Sardina's guarantees on
// random layouts, invariants, and refused input.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/metrics/layout.hpp"
#include "feint/models/deceptiveness.hpp"
#include "feint/models/deceptiveness_k.hpp"
#include "feint/models/goal_posterior.hpp"
#include "feint/rng.hpp"
#include "feint/sim/k_goal_paths.hpp"
#include "feint/sim/trajectory.hpp"
#include "feint/sim/trajectory_measures.hpp"

using namespace feint::sim;
using feint::metrics::Layout;

namespace {

constexpr Strategy kAll[] = {Strategy::exaggerating, Strategy::switching, Strategy::ambiguous,
                             Strategy::optimal};

Layout three_targets() { return {{0, 0}, {{-3, 4}, {0, 5}, {3, 4}}}; }

double entropy_at(const Layout& map, Point q, const feint::models::GoalPosteriorObserver& o = {}) {
  return feint::models::entropy_bits(feint::models::goal_posterior(
      {map.start.x, map.start.y}, {q.x, q.y}, map.targets, o.beta, o.prior));
}

// The paper's geometry and a changed one (every shape parameter moved off its default).
std::vector<Geometry> geometries() {
  Geometry changed;
  changed.target_distance = 6;
  changed.target_height = 3;
  changed.exaggeration_x = 1.3;
  changed.exaggeration_y = 0.45;
  changed.zigzag_width = 0.6;
  changed.zigzag_corners = 5;
  changed.zigzag_height = 0.7;
  changed.ambiguous_height = 0.6;
  changed.v2_turn_remaining = 1.1;
  changed.sample_rate = 60;
  changed.speed = 0.7;
  return {Geometry{}, changed};
}

}  // namespace

TEST(KGoalPaths, TwoTargetsGiveThePapersPathsBitForBit) {
  for (const Geometry& g : geometries()) {
    const Layout paper = feint::metrics::paper_layout(g.target_distance, g.target_height);
    KGoalPathSettings settings;
    settings.geometry = g;
    for (const Strategy s : kAll) {
      for (const Variant v : {Variant::main, Variant::v2}) {
        if (s == Strategy::optimal && v == Variant::v2) continue;
        for (const Target t : {Target::left, Target::right}) {
          const std::size_t k = t == Target::left ? 0 : 1;
          const auto want = waypoints(s, v, t, g);
          const auto got = k_goal_waypoints(paper, k, s, v, settings);
          const std::string at = fmt::format("{} {} {} d = {}", static_cast<int>(s),
                                             static_cast<int>(v), k, g.target_distance);
          ASSERT_EQ(got.size(), want.size()) << at;
          for (std::size_t i = 0; i < want.size(); ++i) {
            EXPECT_EQ(got[i].x, want[i].x) << at << " point " << i;
            EXPECT_EQ(got[i].y, want[i].y) << at << " point " << i;
          }
          const auto a = trajectory(s, v, t, g);
          const auto b = k_goal_trajectory(paper, k, s, v, settings);
          ASSERT_EQ(a.size(), b.size()) << at;
          for (std::size_t i = 0; i < a.size(); ++i) {
            ASSERT_TRUE(a[i].t == b[i].t && a[i].x == b[i].x && a[i].y == b[i].y)
                << at << " sample " << i;
          }
        }
      }
    }
  }
}

TEST(KGoalPaths, TwoTargetMeasuresOfThePapersStrategiesAgree) {
  // deceptiveness_k at K = 2 against models::deceptiveness on every strategy, version and target.
  const Geometry g;
  const Layout paper = feint::metrics::paper_layout();
  feint::models::DeceptivenessSettings two;
  for (const double beta : {0.3, 1.0, 5.0}) {
    two.observer.beta = beta;
    for (const Strategy s : kAll) {
      for (const Variant v : {Variant::main, Variant::v2}) {
        if (s == Strategy::optimal && v == Variant::v2) continue;
        for (const Target t : {Target::left, Target::right}) {
          const auto path = to_path(trajectory(s, v, t, g));
          const auto side =
              t == Target::left ? feint::models::GoalSide::left : feint::models::GoalSide::right;
          const auto a = feint::models::deceptiveness(path, side, two);
          const auto b = feint::models::deceptiveness_k(path, static_cast<std::size_t>(t), paper,
                                                        {beta, 0, {}});
          const std::string at = fmt::format("{} {} {} beta {}", static_cast<int>(s),
                                             static_cast<int>(v), static_cast<int>(t), beta);
          EXPECT_NEAR(a.legibility, b.legibility, 1e-14) << at;
          EXPECT_NEAR(a.time_deceived, b.time_deceived, 1e-14) << at;
          EXPECT_NEAR(a.last_deceptive_point, b.last_deceptive_point, 1e-14) << at;
          EXPECT_NEAR(a.cost_overhead, b.cost_overhead, 1e-15) << at;
          EXPECT_NEAR(a.final_belief, b.final_belief, 1e-15) << at;
        }
      }
    }
  }
}

TEST(KGoalPaths, MastersSardinaAtTwoTargetsGoUpTheMidlineToItsTop) {
  // Paper layout: rmp = (4 + sqrt 20 - sqrt 20) / 2 = 2, t = (0, 4); both plans are S -> t -> G*.
  const Layout paper = feint::metrics::paper_layout();
  const auto ldp = masters_ldp(paper, 1);
  EXPECT_EQ(ldp.decoy, 0u);
  EXPECT_EQ(ldp.radius, 2.0);
  EXPECT_EQ(ldp.point.x, 0.0);
  EXPECT_EQ(ldp.point.y, 4.0);
  for (const auto plan : {DeceptivePlan::simulation, DeceptivePlan::dissimulation}) {
    const auto w = deceptive_waypoints(paper, 1, plan);
    ASSERT_EQ(w.size(), 3u);
    EXPECT_EQ(w[1].x, 0.0);
    EXPECT_EQ(w[1].y, 4.0);
    EXPECT_EQ(w[2].x, 2.0);
    EXPECT_EQ(w[2].y, 4.0);
  }
}

TEST(KGoalPaths, ThreeTargetsWorkedExample) {
  // docs/deceptive-paths.md: targets (-3, 4), (0, 5), (3, 4), all 5 m from S = (0, 0).
  const Layout map = three_targets();
  const double r10 = std::sqrt(10.0);
  // True target 2: rmp = |b G*| / 2 (the start is equally far from all): 3 for target 0, sqrt 10 /
  // 2 for target 1, so g_b = 1 and t = the midpoint of targets 1 and 2.
  const auto ldp = masters_ldp(map, 2);
  EXPECT_EQ(ldp.decoy, 1u);
  EXPECT_NEAR(ldp.radius, r10 / 2, 1e-15);
  EXPECT_NEAR(ldp.point.x, 1.5, 1e-15);
  EXPECT_NEAR(ldp.point.y, 4.5, 1e-15);
  EXPECT_NEAR(masters_ldp(map, 2, 0).radius, 3.0, 1e-15);  // a decoy named: its own rmp
  const auto sim = deceptive_waypoints(map, 2, DeceptivePlan::simulation);
  ASSERT_EQ(sim.size(), 3u);
  EXPECT_NEAR(sim[1].x, 1.5, 1e-15);
  EXPECT_NEAR(sim[1].y, 4.5, 1e-15);
  EXPECT_EQ(sim[2].x, 3.0);
  EXPECT_EQ(sim[2].y, 4.0);
  // Decoys by bearing from S: target 1 is 36.87 degrees from target 2, target 0 is 73.74.
  EXPECT_EQ(decoys_by_bearing(map, 2), (std::vector<std::size_t>{1, 0}));
  EXPECT_EQ(nearest_bearing_decoy(map, 1), 0u);  // a tie (36.87 each side): the lower index
  // Exaggerating toward target 1 in the frame of the pair (1, 2): forward axis toward (1.5, 4.5).
  const auto ex = k_goal_waypoints(map, 2, Strategy::exaggerating, Variant::main);
  ASSERT_EQ(ex.size(), 3u);
  const double fx = 1.5 / (1.5 * r10), fy = 4.5 / (1.5 * r10);  // forward (1, 3) / sqrt 10
  const double xb = 0 * fy - 5 * fx, yb = 5 * fy;  // target 1's lateral and forward offsets
  EXPECT_NEAR(ex[1].x, 1.0 * xb * fy + 0.6 * yb * fx, 1e-15);
  EXPECT_NEAR(ex[1].y, -1.0 * xb * fx + 0.6 * yb * fy, 1e-15);
}

// The largest posterior entropy on the arc of radius rho around S between the outermost targets'
// bearings, by brute force (20001 bearings).
double flattest_by_scan(const Layout& map, double rho) {
  const double sx = map.start.x, sy = map.start.y;
  double cx = 0, cy = 0;
  for (const auto& g : map.targets) cx += g.x, cy += g.y;
  const double head = std::atan2(cy - static_cast<double>(map.targets.size()) * sy,
                                 cx - static_cast<double>(map.targets.size()) * sx);
  double lo = 1e9, hi = -1e9;
  for (const auto& g : map.targets) {
    const double b = std::remainder(std::atan2(g.y - sy, g.x - sx) - head, 2 * M_PI);
    lo = std::min(lo, b);
    hi = std::max(hi, b);
  }
  double best = 0;
  for (int i = 0; i <= 20000; ++i) {
    const double a = head + lo + (hi - lo) * i / 20000;
    best = std::max(best, entropy_at(map, {sx + rho * std::cos(a), sy + rho * std::sin(a)}));
  }
  return best;
}

TEST(KGoalPaths, AmbiguousAndDissimulationPointsAreTheFlattest) {
  // The ambiguous point, and dissimulation's first corner, beat a brute-force scan of their arcs.
  feint::Rng rng(77);
  const feint::metrics::LayoutRegion region;
  for (int trial = 0; trial < 12; ++trial) {
    const Layout map =
        trial == 0 ? three_targets() : feint::metrics::draw_layout(rng, region, 2 + trial % 4);
    const double n = static_cast<double>(map.targets.size());
    double cx = 0, cy = 0;
    for (const auto& g : map.targets) cx += g.x / n, cy += g.y / n;
    const double rho = 0.8 * std::hypot(cx - map.start.x, cy - map.start.y);
    const Point q = ambiguous_point(map, 0.8, {});
    EXPECT_NEAR(std::hypot(q.x - map.start.x, q.y - map.start.y), rho, 1e-12);
    EXPECT_GE(entropy_at(map, q), flattest_by_scan(map, rho) - 1e-9) << trial;

    const std::size_t star = static_cast<std::size_t>(trial) % map.targets.size();
    const Point t = masters_ldp(map, star).point;
    const auto dis = deceptive_waypoints(map, star, DeceptivePlan::dissimulation);
    ASSERT_GE(dis.size(), 3u);
    EXPECT_EQ(dis[dis.size() - 2].x, t.x);  // it passes through t
    EXPECT_EQ(dis[dis.size() - 2].y, t.y);
    const double to_t = std::hypot(t.x - map.start.x, t.y - map.start.y);
    // w, or the point of S -> t at that radius when w lay on the line and was dropped
    const Point w = dis.size() == 4 ? dis[1]
                                    : Point{map.start.x + 0.8 * (t.x - map.start.x),
                                            map.start.y + 0.8 * (t.y - map.start.y)};
    EXPECT_NEAR(std::hypot(w.x - map.start.x, w.y - map.start.y), 0.8 * to_t, 1e-12) << trial;
    EXPECT_GE(entropy_at(map, w), flattest_by_scan(map, 0.8 * to_t) - 1e-9) << trial;
  }
}

TEST(KGoalPaths, SimulationIsDeceptiveUpToTAndTruthfulAfter) {
  // Masters & Sardina with straight-line costs, uniform prior: every point closer to G* than rmp is
  // truthful; when the start is no nearer G* than g_b, the leg S -> t is never truthful (g_b at
  // least as probable). Checked point by point on random layouts with K = 2 .. 6.
  feint::Rng rng(4242);
  const feint::metrics::LayoutRegion region;
  int checked_first_leg = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const Layout map =
        feint::metrics::draw_layout(rng, region, 2 + static_cast<std::size_t>(trial % 5));
    for (std::size_t star = 0; star < map.targets.size(); ++star) {
      const auto ldp = masters_ldp(map, star);
      const auto w = deceptive_waypoints(map, star, DeceptivePlan::simulation);
      const Point s = w.front(), t = ldp.point, g = w.back();
      auto margin = [&](Point q) {  // max over decoys of p_k - p*
        const auto p = feint::models::goal_posterior({s.x, s.y}, {q.x, q.y}, map.targets, 1.5, {});
        double m = -1;
        for (std::size_t k = 0; k < p.size(); ++k) {
          if (k != star) m = std::max(m, p[k] - p[star]);
        }
        return m;
      };
      for (int i = 1; i < 200; ++i) {
        const double f = i / 200.0;
        EXPECT_LT(margin({t.x + f * (g.x - t.x), t.y + f * (g.y - t.y)}), 0.0)
            << trial << " " << star;
      }
      const double sg = std::hypot(g.x - s.x, g.y - s.y);
      const double sb = std::hypot(map.targets[ldp.decoy].x - s.x, map.targets[ldp.decoy].y - s.y);
      if (sg < sb) continue;
      ++checked_first_leg;
      for (int i = 1; i < 200; ++i) {
        const double f = i / 200.0;
        EXPECT_GE(margin({s.x + f * (t.x - s.x), s.y + f * (t.y - s.y)}), -1e-12)
            << trial << " " << star;
      }
    }
  }
  EXPECT_GT(checked_first_leg, 50);
}

TEST(KGoalPaths, EveryPathStartsAtTheStartAndEndsExactlyAtTheTrueTarget) {
  feint::Rng rng(9);
  const feint::metrics::LayoutRegion region;
  for (int trial = 0; trial < 20; ++trial) {
    Layout map = feint::metrics::draw_layout(rng, region, 2 + static_cast<std::size_t>(trial % 5));
    map.start = {rng.uniform() - 0.5, rng.uniform() - 0.5};
    const Geometry g;
    for (std::size_t star = 0; star < map.targets.size(); ++star) {
      std::vector<std::vector<TrajectorySample>> paths;
      for (const Strategy s : kAll) {
        for (const Variant v : {Variant::main, Variant::v2}) {
          if (s != Strategy::optimal || v == Variant::main)
            paths.push_back(k_goal_trajectory(map, star, s, v));
        }
      }
      for (const auto plan : {DeceptivePlan::simulation, DeceptivePlan::dissimulation}) {
        paths.push_back(deceptive_trajectory(map, star, plan));
      }
      for (const auto& p : paths) {
        EXPECT_EQ(p.front().t, 0.0);
        EXPECT_EQ(p.front().x, map.start.x);
        EXPECT_EQ(p.front().y, map.start.y);
        EXPECT_EQ(p.back().x, map.targets[star].x);
        EXPECT_EQ(p.back().y, map.targets[star].y);
        // Constant speed: no step longer than speed / rate (the last: up to 1.1 ms longer).
        for (std::size_t i = 1; i < p.size(); ++i) {
          EXPECT_LE(std::hypot(p[i].x - p[i - 1].x, p[i].y - p[i - 1].y),
                    g.speed * (1 / g.sample_rate + 1.1e-3));
          EXPECT_LE(std::hypot(p[i].x - p[i - 1].x, p[i].y - p[i - 1].y),
                    g.speed * (p[i].t - p[i - 1].t) + 1e-12);
        }
      }
    }
  }
}

TEST(KGoalPaths, DeceptivePathsAreMoreDeceptiveThanOptimalAmongThreeTargets) {
  const Layout map = three_targets();
  const feint::models::GoalPosteriorObserver o{1.0, 0.0, {}};
  auto measure = [&](const std::vector<TrajectorySample>& p) {
    return feint::models::deceptiveness_k(to_path(p), 2, map, o);
  };
  const auto opt = measure(k_goal_trajectory(map, 2, Strategy::optimal, Variant::main));
  EXPECT_EQ(opt.time_deceived, 0.0);
  EXPECT_LT(opt.last_deceptive_point, 1e-9);
  for (const Strategy s : {Strategy::exaggerating, Strategy::switching, Strategy::ambiguous}) {
    for (const Variant v : {Variant::main, Variant::v2}) {
      const auto m = measure(k_goal_trajectory(map, 2, s, v));
      EXPECT_GT(m.last_deceptive_point, 0.7) << static_cast<int>(s) << static_cast<int>(v);
      EXPECT_GT(m.time_deceived, 0.2) << static_cast<int>(s) << static_cast<int>(v);
      EXPECT_GT(m.cost_overhead, 0.3) << static_cast<int>(s) << static_cast<int>(v);
      // v2 first feints toward the true target (the paper's "double bluff"): it need not be less
      // legible than the straight path; the main versions are.
      if (v == Variant::main) {
        EXPECT_LT(m.legibility, opt.legibility) << static_cast<int>(s);
      }
    }
  }
  // Masters & Sardina: the last deceptive point is t, 1.5 sqrt 10 of 2 sqrt 10 (simulation), up to
  // one sample (0.04 m); dissimulation reaches t later, having kept the posterior flatter.
  const auto sim = measure(deceptive_trajectory(map, 2, DeceptivePlan::simulation));
  const auto dis = measure(deceptive_trajectory(map, 2, DeceptivePlan::dissimulation));
  EXPECT_NEAR(sim.last_deceptive_point, 0.75, 0.04 / (2 * std::sqrt(10.0)));
  EXPECT_EQ(sim.time_deceived, 0.0);  // targets 1 and 2 tie all the way to t
  EXPECT_GT(dis.last_deceptive_point, 0.7);
  EXPECT_GT(dis.mean_entropy, sim.mean_entropy);
  EXPECT_GT(dis.cost_overhead, sim.cost_overhead);
  for (const auto& m : {sim, dis}) {
    EXPECT_LT(m.legibility, opt.legibility);
    EXPECT_GT(m.mean_entropy, opt.mean_entropy);
  }
}

TEST(KGoalPaths, BadInputIsRefused) {
  const Layout map = three_targets();
  auto refuses = [](auto&& call, const std::string& word) {
    try {
      call();
      ADD_FAILURE() << "accepted: " << word;
    } catch (const feint::UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  refuses([&] { k_goal_waypoints(map, 3, Strategy::optimal, Variant::main); },
          "true target 3 is out of range");
  refuses([&] { deceptive_waypoints(map, 7, DeceptivePlan::simulation); }, "true target 7");
  refuses([&] { k_goal_waypoints(map, 0, Strategy::optimal, Variant::v2); }, "no version 2");
  KGoalPathSettings s;
  s.decoy = 2;
  refuses([&] { k_goal_waypoints(map, 2, Strategy::exaggerating, Variant::main, s); },
          "decoy 2 is the true target");
  s.decoy = 5;
  refuses([&] { k_goal_waypoints(map, 2, Strategy::exaggerating, Variant::main, s); },
          "decoy 5 is out of range");
  s.decoy.reset();
  s.switching_decoys = {0, 2};
  refuses([&] { k_goal_waypoints(map, 2, Strategy::switching, Variant::main, s); },
          "decoy 2 is the true target");
  s.switching_decoys.clear();
  s.geometry.zigzag_corners = 2;
  refuses([&] { k_goal_waypoints(map, 2, Strategy::switching, Variant::main, s); },
          "zigzag_corners");
  s.geometry = Geometry{};
  s.observer.prior = {0.5, 0.5};
  refuses([&] { k_goal_waypoints(map, 2, Strategy::ambiguous, Variant::main, s); }, "prior");
  refuses(
      [&] {
        k_goal_waypoints({{0, 0}, {{3, 4}}}, 0, Strategy::optimal, Variant::main);
      },
      "at least 2");
  refuses(
      [&] {
        k_goal_waypoints({{0, 0}, {{3, 4}, {0, 0}}}, 0, Strategy::optimal, Variant::main);
      },
      "target 1 is at the start");
  refuses(
      [&] {
        k_goal_waypoints({{0, 0}, {{3, 4}, {3, 4}}}, 0, Strategy::optimal, Variant::main);
      },
      "same point");
  refuses(
      [&] {
        k_goal_waypoints({{0, 0}, {{-1, 0}, {1, 0}}}, 0, Strategy::exaggerating, Variant::main);
      },
      "centroid is at the start");
  refuses([&] { ambiguous_point(map, 1.2, {}); }, "ambiguous_height");
}

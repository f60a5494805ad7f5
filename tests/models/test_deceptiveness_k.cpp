// Deceptiveness among K targets (feint/models/deceptiveness_k.hpp): the two-target measures at
// K = 2, the K = 3 worked example of docs/deceptive-paths.md, ties, and refused input.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/metrics/layout.hpp"
#include "feint/models/deceptiveness.hpp"
#include "feint/models/deceptiveness_k.hpp"
#include "observer_test_paths.hpp"

using namespace feint::models;
using feint::metrics::Layout;
namespace tp = feint::testpaths;

namespace {

Layout three_targets() { return {{0, 0}, {{-3, 4}, {0, 5}, {3, 4}}}; }

}  // namespace

TEST(DeceptivenessK, TwoTargetsEqualTheTwoTargetMeasures) {
  // The paper's four shapes toward each target, several beta and priors: every measure the two
  // definitions share agrees (target 1 = right).
  const Layout paper = feint::metrics::paper_layout();
  for (int shape = 0; shape < 4; ++shape) {
    for (const double side : {-1.0, 1.0}) {
      for (const double beta : {0.0, 0.3, 1.0, 4.0, 20.0}) {
        for (const double prior_right : {0.5, 0.3}) {
          const auto path = tp::shape(shape, side);
          DeceptivenessSettings two;
          two.observer = {beta, 0.0, prior_right};
          const auto a = deceptiveness(path, side > 0 ? GoalSide::right : GoalSide::left, two);
          const auto b = deceptiveness_k(path, side > 0 ? 1 : 0, paper,
                                         {beta, 0.0, {1 - prior_right, prior_right}});
          const std::string at =
              fmt::format("shape {} side {} beta {} prior {}", shape, side, beta, prior_right);
          EXPECT_EQ(a.duration, b.duration) << at;
          EXPECT_EQ(a.path_length, b.path_length) << at;
          EXPECT_NEAR(a.cost_overhead, b.cost_overhead, 1e-15) << at;
          EXPECT_NEAR(a.legibility, b.legibility, 1e-14) << at;
          EXPECT_NEAR(a.time_deceived, b.time_deceived, 1e-14) << at;
          EXPECT_NEAR(a.last_deceptive_point, b.last_deceptive_point, 1e-14) << at;
          EXPECT_NEAR(a.final_belief, b.final_belief, 1e-15) << at;
        }
      }
    }
  }
}

TEST(DeceptivenessK, ThreeTargetsWorkedExample) {
  // docs/deceptive-paths.md: targets (-3, 4), (0, 5), (3, 4), the true one 2; the simulation path
  // S -> t = (1.5, 4.5) -> (3, 4) sampled at its corners, t = 0, 1.5 sqrt 10, 2 sqrt 10; beta = 1.
  const double r10 = std::sqrt(10.0);
  const std::vector<PathSample> path{{0, 0, 0}, {1.5 * r10, 1.5, 4.5}, {2 * r10, 3, 4}};
  const auto m = deceptiveness_k(path, 2, three_targets(), {1.0, 0.0, {}});
  // At t targets 1 and 2 tie: V = (|t - G0|, sqrt 10 / 2, sqrt 10 / 2); p* = 1 / (2 + e^(a0 - a2)).
  const double a0_minus_a2 = r10 / 2 - std::hypot(4.5, 0.5);
  const double pt = 1 / (2 + std::exp(a0_minus_a2));
  const double pend = 1 / (1 + std::exp(-6.0) + std::exp(-r10));  // V(G2) = (6, sqrt 10, 0)
  const double T = 2 * r10, t1 = 1.5 * r10;
  const double num = (1.0 / 3 * T + pt * (T - t1)) / 2 * t1 + (pt * (T - t1) + 0) / 2 * (T - t1);
  EXPECT_NEAR(m.legibility, num / (T * T / 2), 1e-15);
  EXPECT_NEAR(m.legibility, 0.37180147, 5e-9);
  EXPECT_NEAR(m.final_belief, pend, 1e-15);
  EXPECT_NEAR(m.final_belief, 0.95711368, 5e-9);
  EXPECT_EQ(m.time_deceived, 0.0);  // a tie at the top (1 and 2 on the first leg) is not deceived
  EXPECT_NEAR(m.last_deceptive_point, 0.75, 1e-15);  // 1.5 sqrt 10 / (2 sqrt 10)
  EXPECT_NEAR(m.cost_overhead, 2 * r10 / 5 - 1, 1e-15);
  EXPECT_NEAR(m.mean_entropy, 1.20102258, 5e-9);
}

TEST(DeceptivenessK, ATieLineSampledDenselyIsNeitherDeceivedNorTruthful) {
  // The same path at 25 Hz: on the first leg targets 1 and 2 are equally far in cost, but their
  // probabilities are computed with different roundings. They must tie (no time deceived), and the
  // last deceptive point is t, up to one sample (0.04 m of 6.32 m).
  const auto path = tp::polyline({{0, 0}, {1.5, 4.5}, {3, 4}});
  const auto m = deceptiveness_k(path, 2, three_targets(), {1.0, 0.0, {}});
  EXPECT_EQ(m.time_deceived, 0.0);
  EXPECT_NEAR(m.last_deceptive_point, 0.75, 0.04 / (2 * std::sqrt(10.0)));
  EXPECT_GE(m.last_deceptive_point, 0.75 - 0.04 / (2 * std::sqrt(10.0)));
}

TEST(DeceptivenessK, AFeintTowardADecoyIsMoreDeceptiveThanTheStraightPath) {
  const Layout map = three_targets();
  const GoalPosteriorObserver o{1.0, 0.0, {}};
  const auto straight = deceptiveness_k(tp::polyline({{0, 0}, {3, 4}}), 2, map, o);
  const auto feint = deceptiveness_k(tp::polyline({{0, 0}, {-1.5, 3.0}, {3, 4}}), 2, map, o);
  EXPECT_EQ(straight.time_deceived, 0.0);
  EXPECT_NEAR(straight.last_deceptive_point, 0.0, 1e-15);
  EXPECT_NEAR(straight.cost_overhead, 0.0, 1e-15);
  EXPECT_GT(feint.time_deceived, 0.5);
  EXPECT_GT(feint.last_deceptive_point, 0.5);
  EXPECT_LT(feint.legibility, straight.legibility);
  EXPECT_GT(feint.cost_overhead, 0.2);
  for (const auto& m : {straight, feint}) {
    EXPECT_GE(m.legibility, 0.0);
    EXPECT_LE(m.legibility, 1.0);
    EXPECT_LE(m.mean_entropy, std::log2(3.0) + 1e-15);
    EXPECT_GE(m.mean_entropy, 0.0);
  }
  // Toward the decoy on the left the observer believes target 0 for a while: deceived, and the
  // true target is less probable at every sample of the first leg.
  EXPECT_GT(feint.mean_entropy, straight.mean_entropy);
}

TEST(DeceptivenessK, ThreeEqualTargetsAtBetaZeroNeverDeceiveAndNeverTellTheTruth) {
  // beta = 0: the posterior stays the uniform prior, a three-way tie throughout.
  const auto m =
      deceptiveness_k(tp::polyline({{0, 0}, {3, 4}}), 2, three_targets(), {0.0, 0.0, {}});
  EXPECT_EQ(m.time_deceived, 0.0);
  EXPECT_EQ(m.last_deceptive_point, 1.0);
  EXPECT_NEAR(m.legibility, 1.0 / 3, 1e-15);
  EXPECT_NEAR(m.mean_entropy, std::log2(3.0), 1e-13);  // 125 trapezoids of log2 3
}

TEST(DeceptivenessK, BadInputIsRefused) {
  const Layout map = three_targets();
  const auto path = tp::polyline({{0, 0}, {3, 4}});
  try {
    deceptiveness_k(path, 3, map, {});
    FAIL();
  } catch (const feint::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("true target 3 is out of range"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(deceptiveness_k(path, 0, map, {-1, 0, {}}), feint::UsageError);
  EXPECT_THROW(deceptiveness_k(path, 0, map, {1, 0, {0.5, 0.6, 0.1}}), feint::UsageError);
  EXPECT_THROW(deceptiveness_k(path, 0, Layout{{0, 0}, {{3, 4}}}, {}), feint::UsageError);
  const std::vector<PathSample> loop{{0, 0, 0}, {1, 1, 1}, {2, 0, 0}};
  EXPECT_THROW(deceptiveness_k(loop, 0, map, {}), feint::InvalidData);
  const std::vector<PathSample> one{{0, 0, 0}};
  EXPECT_THROW(deceptiveness_k(one, 0, map, {}), feint::InvalidData);
}

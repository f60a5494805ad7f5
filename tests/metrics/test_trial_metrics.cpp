// Trial metrics (metrics.md): the five worked examples and invariants on random traces.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include "feint/error.hpp"
#include "feint/io/trace.hpp"
#include "feint/metrics/trial_metrics.hpp"

using feint::metrics::ConfusionNorm;
using feint::metrics::MetricSettings;
using feint::metrics::score_trace;
using feint::metrics::TrialScore;

namespace {

struct Example {
  const char* name;
  std::vector<double> t, mu;
  double target, v;
  double error, conf_speed, conf_raw, t_rev;  // t_rev NaN = none
};

const double kNone = std::nan("");

std::vector<double> zero_to_ten() {
  std::vector<double> t;
  for (int i = 0; i <= 10; ++i) t.push_back(i);
  return t;
}

// metrics.md, "Worked examples" (exact fractions).
std::vector<Example> worked_examples() {
  return {
      {"A", zero_to_ten(), {0.5, 0.75, 1, 1, 1, 1, 1, 1, 1, 1, 1}, 1, 0.25, 1.0 / 32, 0, 0, kNone},
      {"B", zero_to_ten(), {0.5, 0.25, 0, 0, 0, 0, 0, 0.25, 0.5, 0.75, 1}, 1, 0.25, 115.0 / 144,
       217.0 / 360, 217.0 / 320, 6},
      {"C", zero_to_ten(), {0.5, 0.75, 0.5, 0.75, 0.5, 0.75, 0.5, 0.75, 0.5, 0.75, 0.5}, 0, 0.25,
       91.0 / 144, 119.0 / 120, 357.0 / 320, 1},
      {"D", {0, 0.5, 2, 3.5, 4}, {0.5, 0.5, 0.2, 0.6, 0.6}, 0.3, 0.5, 37.0 / 288, 11.0 / 36,
       11.0 / 40, 2},
      {"E", {0, 0.3, 1, 2, 4}, {0.5, 0.6, 0.4, 0.4, 0.9}, 1, 1, 25.0 / 54, 287.0 / 1440,
       287.0 / 800, 0.3},
  };
}

TrialScore score(const std::vector<double>& t, const std::vector<double>& mu, double target,
                 double v, ConfusionNorm norm, double eps = 1e-9) {
  MetricSettings s;
  s.norm = norm;
  s.deadband = eps;
  return score_trace(t, mu, target, v, s);
}

}  // namespace

TEST(WorkedExamples, ReproduceBothNormalisationsAndReversalTime) {
  for (const auto& ex : worked_examples()) {
    SCOPED_TRACE(ex.name);
    for (double eps : {0.0, 1e-9}) {
      const auto sp = score(ex.t, ex.mu, ex.target, ex.v, ConfusionNorm::speed, eps);
      const auto raw = score(ex.t, ex.mu, ex.target, ex.v, ConfusionNorm::raw, eps);
      EXPECT_NEAR(sp.error, ex.error, 1e-12);
      EXPECT_NEAR(raw.error, ex.error, 1e-12);
      EXPECT_NEAR(sp.confusion, ex.conf_speed, 1e-12);
      EXPECT_NEAR(raw.confusion, ex.conf_raw, 1e-12);
      if (std::isnan(ex.t_rev)) {
        EXPECT_TRUE(std::isnan(sp.reversal_time));
      } else {
        EXPECT_NEAR(sp.reversal_time, ex.t_rev, 1e-12);
      }
      EXPECT_EQ(sp.n_samples, ex.t.size());
      EXPECT_DOUBLE_EQ(sp.duration, ex.t.back());
      EXPECT_DOUBLE_EQ(sp.final_pad, ex.mu.back());
      EXPECT_EQ(sp.overspeed_segments, 0);
    }
  }
}

TEST(WorkedExamples, DiagnosticsCountReversals) {
  const auto ex = worked_examples();
  EXPECT_EQ(score(ex[0].t, ex[0].mu, 1, 0.25, ConfusionNorm::speed).reversals, 0);
  EXPECT_EQ(score(ex[1].t, ex[1].mu, 1, 0.25, ConfusionNorm::speed).reversals, 1);
  EXPECT_EQ(score(ex[2].t, ex[2].mu, 0, 0.25, ConfusionNorm::speed).reversals, 9);
  EXPECT_EQ(score(ex[3].t, ex[3].mu, 0.3, 0.5, ConfusionNorm::speed).reversals, 1);
  EXPECT_EQ(score(ex[4].t, ex[4].mu, 1, 1, ConfusionNorm::speed).reversals, 2);
}

TEST(WorkedExamples, TimeShiftOfExampleEChangesNothing) {
  auto ex = worked_examples()[4];
  for (auto& t : ex.t) t += 1000.25;
  const auto s = score(ex.t, ex.mu, ex.target, ex.v, ConfusionNorm::speed);
  EXPECT_NEAR(s.error, 25.0 / 54, 1e-12);
  EXPECT_NEAR(s.confusion, 287.0 / 1440, 1e-12);
  EXPECT_NEAR(s.reversal_time, 0.3, 1e-12);
}

TEST(Overspeed, SegmentsFasterThanThePadSpeedAreClampedAndCounted) {
  // Pad jumps 0.5 in 0.1 s (5 units/s) with v = 1: m = 1 and one overspeed segment.
  const std::vector<double> t{0, 1, 1.1, 2, 3};
  const std::vector<double> mu{0.5, 0.8, 0.3, 0.3, 0.3};
  const auto s = score(t, mu, 0, 1, ConfusionNorm::speed);
  EXPECT_EQ(s.overspeed_segments, 1);
  EXPECT_GE(s.confusion, 0.0);
  EXPECT_LE(s.confusion, 1.0);
  // c = t_rev = 1, b = 2.85; only [1, 1.1] moves (m = 1): M = (1.1^2 - 1)/2, D = (2.85^2-0.15^2)/2.
  EXPECT_NEAR(s.confusion, (1.21 - 1) / (2.85 * 2.85 - 0.15 * 0.15), 1e-12);
}

TEST(Validation, RejectsBadTraces) {
  MetricSettings s;
  s.norm = ConfusionNorm::speed;  // the check that speed needs v (raw, the default, does not)
  const std::vector<double> t{0, 1, 2};
  EXPECT_THROW(score_trace(std::vector<double>{0}, std::vector<double>{0.5}, 1, 1, s),
               feint::InvalidData);
  EXPECT_THROW(score_trace(std::vector<double>{0, 1, 1}, std::vector<double>{0.5, 0.5, 0.5}, 1, 1, s),
               feint::InvalidData);
  EXPECT_THROW(score_trace(t, std::vector<double>{0.5, 1.5, 0.5}, 1, 1, s), feint::InvalidData);
  EXPECT_THROW(score_trace(t, std::vector<double>{0.5, NAN, 0.5}, 1, 1, s), feint::InvalidData);
  EXPECT_THROW(score_trace(t, std::vector<double>{0.5, 0.5, 0.5}, 1.2, 1, s), feint::InvalidData);
  // speed normalisation needs v; raw does not.
  try {
    score_trace(t, std::vector<double>{0.5, 0.5, 0.5}, 1, std::nullopt, s);
    ADD_FAILURE() << "no throw";
  } catch (const feint::InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("--pad-speed"), std::string::npos) << e.what();
  }
  s.norm = ConfusionNorm::raw;
  const auto r = score_trace(t, std::vector<double>{0.5, 0.5, 0.5}, 1, std::nullopt, s);
  EXPECT_EQ(r.overspeed_segments, -1);
  EXPECT_DOUBLE_EQ(r.error, 0.5);
}

TEST(Validation, SettingsOutOfRangeAreUsageErrors) {
  MetricSettings s;
  s.trim_start = 0.6;
  s.trim_end = 0.4;
  EXPECT_THROW(s.validate(), feint::UsageError);
  s = {};
  s.trim_end = 1;
  EXPECT_THROW(s.validate(), feint::UsageError);
  s = {};
  s.deadband = -1;
  EXPECT_THROW(s.validate(), feint::UsageError);
  s = {};
  s.pad_speed = 0;
  EXPECT_THROW(s.validate(), feint::UsageError);
  s = {};
  EXPECT_NO_THROW(s.validate());
}

TEST(Trimming, ZeroTrimIntegratesTheWholeTrace) {
  MetricSettings s;
  s.trim_start = s.trim_end = 0;
  // Straight line from 0 to 1 over 2 s, target 1: error = mean of 1 - t/2 = 0.5.
  const auto r = score_trace(std::vector<double>{0, 2}, std::vector<double>{0, 1}, 1, 0.5, s);
  EXPECT_NEAR(r.error, 0.5, 1e-15);
  EXPECT_EQ(r.confusion, 0);  // never reverses
}

// ---- Invariants on random traces -------------------------------------------------------------

namespace {

struct Trace {
  std::vector<double> t, mu;
  double target, v;
};

// A ~30 Hz trace: the pad is still or moves at speed <= v; times jitter; the target is 0, 1 or
// inside the range.
Trace random_trace(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  Trace tr;
  const int n = 2 + static_cast<int>(u(rng) * 120);
  tr.v = 0.2 + 2 * u(rng);
  const double r = u(rng);
  tr.target = r < 0.4 ? 0.0 : (r < 0.8 ? 1.0 : u(rng));
  double t = 100 * u(rng) - 50;
  double mu = u(rng) < 0.7 ? 0.5 : u(rng);
  int dir = 0;
  for (int i = 0; i < n; ++i) {
    tr.t.push_back(t);
    tr.mu.push_back(mu);
    const double dt = (0.2 + u(rng)) / 30;
    if (u(rng) < 0.15) dir = static_cast<int>(u(rng) * 3) - 1;
    const double speed = tr.v * (u(rng) < 0.8 ? 1.0 : u(rng));
    mu = std::clamp(mu + dir * speed * dt, 0.0, 1.0);
    t += dt;
  }
  return tr;
}

TrialScore score_tr(const Trace& tr, ConfusionNorm norm, double eps = 1e-9) {
  return score(tr.t, tr.mu, tr.target, tr.v, norm, eps);
}

// Midpoint-rule quadrature of the same integrals on a fine grid (independent of the exact code).
void quadrature(const Trace& tr, double fs, double fe, double& error, double& conf_speed) {
  const std::size_t n = tr.t.size();
  const double t0 = tr.t[0], tau = tr.t[n - 1] - t0;
  const double a = t0 + fs * tau, b = t0 + (1 - fe) * tau;
  // reversal (eps = 1e-9)
  int first = 0;
  double trev = NAN;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double d = tr.mu[i + 1] - tr.mu[i];
    const int dir = d > 1e-9 ? 1 : (d < -1e-9 ? -1 : 0);
    if (dir != 0 && first == 0) first = dir;
    if (dir != 0 && dir == -first) {
      trev = tr.t[i];
      break;
    }
  }
  const int steps = 400000;
  const double h = (b - a) / steps;
  double e = 0, m = 0, d = 0;
  std::size_t seg = 0;
  for (int k = 0; k < steps; ++k) {
    const double x = a + (k + 0.5) * h;
    while (seg + 2 < n && tr.t[seg + 1] <= x) ++seg;
    const double dt = tr.t[seg + 1] - tr.t[seg];
    const double slope = (tr.mu[seg + 1] - tr.mu[seg]) / dt;
    const double mu = tr.mu[seg] + slope * (x - tr.t[seg]);
    e += std::fabs(tr.target - mu) * h;
    d += (x - t0) * h;
    if (!std::isnan(trev) && x >= trev) m += std::min(1.0, std::fabs(slope) / tr.v) * (x - t0) * h;
  }
  error = e / (b - a);
  conf_speed = m / d;
}

}  // namespace

TEST(Invariants, BoundsHoldOnRandomTraces) {
  std::mt19937_64 rng(20261121);
  for (int k = 0; k < 2000; ++k) {
    const auto tr = random_trace(rng);
    const auto s = score_tr(tr, ConfusionNorm::speed);
    ASSERT_GE(s.error, 0);
    ASSERT_LE(s.error, 1);
    ASSERT_GE(s.confusion, 0);
    ASSERT_LE(s.confusion, 1);
    const auto r = score_tr(tr, ConfusionNorm::raw);
    ASSERT_GE(r.confusion, 0);
    ASSERT_EQ(r.error, s.error);
  }
}

TEST(Invariants, ShiftingAllTimesChangesNothing) {
  std::mt19937_64 rng(1);
  for (int k = 0; k < 500; ++k) {
    auto tr = random_trace(rng);
    const auto s0 = score_tr(tr, ConfusionNorm::speed);
    const auto r0 = score_tr(tr, ConfusionNorm::raw);
    const double shift = (k % 2 ? 1 : -1) * 37.125 * (k % 7);
    for (auto& t : tr.t) t += shift;
    const auto s1 = score_tr(tr, ConfusionNorm::speed);
    const auto r1 = score_tr(tr, ConfusionNorm::raw);
    ASSERT_NEAR(s1.error, s0.error, 1e-9);
    ASSERT_NEAR(s1.confusion, s0.confusion, 1e-9);
    ASSERT_NEAR(r1.confusion, r0.confusion, 1e-9 * (1 + r0.confusion));
    ASSERT_EQ(std::isnan(s1.reversal_time), std::isnan(s0.reversal_time));
    if (!std::isnan(s0.reversal_time)) {
      ASSERT_NEAR(s1.reversal_time, s0.reversal_time, 1e-9);
    }
  }
}

TEST(Invariants, ScalingTimeAndInverseScalingSpeedChangesNothing) {
  std::mt19937_64 rng(2);
  for (int k = 0; k < 500; ++k) {
    auto tr = random_trace(rng);
    const auto s0 = score_tr(tr, ConfusionNorm::speed);
    const auto r0 = score_tr(tr, ConfusionNorm::raw);
    const double scale = k % 2 ? 3.7 : 0.013;
    for (auto& t : tr.t) t *= scale;
    tr.v /= scale;
    const auto s1 = score_tr(tr, ConfusionNorm::speed);
    const auto r1 = score_tr(tr, ConfusionNorm::raw);
    ASSERT_NEAR(s1.error, s0.error, 1e-9);
    ASSERT_NEAR(s1.confusion, s0.confusion, 1e-9);
    ASSERT_NEAR(r1.confusion, r0.confusion, 1e-9 * (1 + r0.confusion));
    ASSERT_EQ(s1.overspeed_segments, s0.overspeed_segments);
  }
}

TEST(Invariants, MirroringThePadChangesNothing) {
  std::mt19937_64 rng(3);
  for (int k = 0; k < 500; ++k) {
    auto tr = random_trace(rng);
    const auto s0 = score_tr(tr, ConfusionNorm::speed);
    for (auto& m : tr.mu) m = 1 - m;
    tr.target = 1 - tr.target;
    const auto s1 = score_tr(tr, ConfusionNorm::speed);
    ASSERT_NEAR(s1.error, s0.error, 1e-12);
    ASSERT_NEAR(s1.confusion, s0.confusion, 1e-12);
    ASSERT_EQ(s1.reversals, s0.reversals);
  }
}

TEST(Invariants, ATraceThatNeverReversesHasConfusionZero) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 300; ++k) {
    auto tr = random_trace(rng);
    // Make the trace monotone: sort the positions (non-decreasing), keep the times.
    std::sort(tr.mu.begin(), tr.mu.end());
    if (k % 2) std::reverse(tr.mu.begin(), tr.mu.end());
    for (auto norm : {ConfusionNorm::speed, ConfusionNorm::raw}) {
      const auto s = score(tr.t, tr.mu, tr.target, 1e6, norm);
      ASSERT_EQ(s.confusion, 0);
      ASSERT_TRUE(std::isnan(s.reversal_time));
      ASSERT_EQ(s.reversals, 0);
    }
  }
}

TEST(Invariants, ExactIntegrationAgreesWithFineQuadrature) {
  std::mt19937_64 rng(5);
  for (int k = 0; k < 25; ++k) {
    const auto tr = random_trace(rng);
    double e = 0, c = 0;
    quadrature(tr, 0.05, 0.05, e, c);
    const auto s = score_tr(tr, ConfusionNorm::speed);
    EXPECT_NEAR(s.error, e, 1e-6);
    EXPECT_NEAR(s.confusion, c, 1e-4);  // the midpoint rule smears the reversal instant
  }
}

TEST(Invariants, DeadbandIgnoresJitterForTheReversal) {
  // Float noise of 1e-12 backwards must not count as the reversal with the default eps.
  const std::vector<double> t{0, 1, 2, 3, 4, 5};
  const std::vector<double> mu{0.5, 0.7, 0.7 - 1e-12, 0.9, 0.6, 0.6};
  const auto s = score(t, mu, 1, 1, ConfusionNorm::speed);
  EXPECT_NEAR(s.reversal_time, 3, 1e-15);
  const auto s0 = score(t, mu, 1, 1, ConfusionNorm::speed, 0.0);
  EXPECT_NEAR(s0.reversal_time, 1, 1e-15);
}

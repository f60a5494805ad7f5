// Simulation power: the fast path agrees with the full mixed ANOVA and Welch tests on the same
// simulated data; a true null rejects at alpha within Monte Carlo error; runs are reproducible and
// independent of the number of threads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/models/power_sim.hpp"
#include "feint/stats/ttest.hpp"

namespace feint::models {
namespace {

SimulationDesign paper_like(std::size_t k, double interaction) {
  SimulationDesign d;
  for (std::size_t j = 0; j < k; ++j) {
    d.means_a.push_back(0.6);
    d.means_b.push_back(0.6 - interaction * static_cast<double>(j) / static_cast<double>(k));
  }
  d.sd_participant = 0.1;
  d.sd_residual = 0.15;
  d.n_a = 30;
  d.n_b = 30;
  return d;
}

TEST(SimulationPower, FastPathAgreesWithTheMixedAnovaAndWelchTestsOnTheSameData) {
  SimulationDesign d = paper_like(6, 0.1);
  d.n_a = 7;
  d.n_b = 11;  // unbalanced
  SimulationOptions o;
  o.seed = 42;
  for (std::uint64_t index : {0u, 1u, 17u}) {
    const auto s = detail::analyse_simulated_study(d, o, index);
    std::vector<Observation> obs;
    const std::size_t k = d.means_a.size();
    for (std::size_t i = 0; i < d.n_a + d.n_b; ++i) {
      for (std::size_t j = 0; j < k; ++j) {
        obs.push_back({"P" + std::to_string(i), i < d.n_a ? "A" : "B",
                       static_cast<long long>(j + 1), s.y[i * k + j], 0});
      }
    }
    const MixedAnova a = mixed_anova(make_wide_design(obs, "y", "sim"), SphericityCorrection::GG);
    EXPECT_NEAR(s.f_interaction, a.effects[2].f, 1e-9 * a.effects[2].f);
    EXPECT_NEAR(s.gg_eps, *a.effects[2].gg_eps, 1e-9);
    EXPECT_NEAR(s.p_interaction, a.effects[2].report_p, 1e-9 * a.effects[2].report_p + 1e-15);
    EXPECT_NEAR(s.f_condition, a.effects[0].f, 1e-9 * a.effects[0].f);
    for (std::size_t j = 0; j < k; ++j) {
      std::vector<double> xa, xb;
      for (std::size_t i = 0; i < d.n_a + d.n_b; ++i)
        (i < d.n_a ? xa : xb).push_back(s.y[i * k + j]);
      const auto w = stats::t_test_welch(xa, xb);
      EXPECT_NEAR(s.p_iteration[j], *w.p_value, 1e-10 * *w.p_value + 1e-15) << j;
    }
  }
}

TEST(SimulationPower, TrueNullRejectsAtAlphaWithinMonteCarloError) {
  // Data simulated with compound symmetry (sphericity holds): the uncorrected F is exact, so it
  // rejects at alpha; the GG-corrected one, with epsilon estimated below 1, is conservative.
  SimulationDesign d = paper_like(20, 0.0);
  SimulationOptions o;
  o.studies = 4000;
  o.seed = 7;
  o.correction = SphericityCorrection::none;
  const auto r = simulate_power(d, o);
  const double se = std::sqrt(0.05 * 0.95 / 4000.0);
  EXPECT_NEAR(r.interaction.power, 0.05, 4 * se);
  EXPECT_NEAR(r.condition.power, 0.05, 4 * se);
  // Holm controls the family-wise rate: at most alpha (+ Monte Carlo error).
  EXPECT_LE(r.any_iteration.power, 0.05 + 4 * se);
  EXPECT_NEAR(r.interaction.mc_se,
              std::sqrt(r.interaction.power * (1 - r.interaction.power) / 4000), 1e-15);
  o.correction = SphericityCorrection::GG;
  const auto gg = simulate_power(d, o);
  EXPECT_LE(gg.interaction.power, 0.05 + 4 * se);
  EXPECT_LE(gg.interaction.power, r.interaction.power);  // same data, larger p-values
  EXPECT_LT(gg.mean_gg_eps, 1.0);
}

TEST(SimulationPower, ReproducibleFromTheSeedWhateverTheThreads) {
  SimulationDesign d = paper_like(8, 0.15);
  SimulationOptions o;
  o.studies = 500;
  o.seed = 123;
  o.threads = 1;
  const auto one = simulate_power(d, o);
  o.threads = 2;
  const auto two = simulate_power(d, o);
  EXPECT_EQ(one.interaction.power, two.interaction.power);
  EXPECT_EQ(one.any_iteration.power, two.any_iteration.power);
  for (std::size_t j = 0; j < 8; ++j) EXPECT_EQ(one.iteration[j].power, two.iteration[j].power);
  o.seed = 124;
  const auto other = simulate_power(d, o);
  EXPECT_NE(other.interaction.power + other.condition.power + other.any_iteration.power,
            one.interaction.power + one.condition.power + one.any_iteration.power);
}

TEST(SimulationPower, LargerEffectsAndSamplesGiveMorePower) {
  // The interaction's power over a grid of effects and sample sizes, 1000 studies each: it must
  // grow along both axes, by more than 4 Monte Carlo SEs of the difference at every step
  // (sqrt(p1 (1 - p1) / 1000 + p2 (1 - p2) / 1000) <= 0.023).
  SimulationOptions o;
  o.studies = 1000;
  const double effects[] = {0.1, 0.15, 0.2};
  const std::size_t sizes[] = {10, 20, 40};
  double power[3][3];
  for (int e = 0; e < 3; ++e)
    for (int n = 0; n < 3; ++n) {
      SimulationDesign d = paper_like(10, effects[e]);
      d.n_a = d.n_b = sizes[n];
      power[e][n] = simulate_power(d, o).interaction.power;
    }
  auto step = [&](double lower, double higher) {
    return 4 * std::sqrt(lower * (1 - lower) / 1000 + higher * (1 - higher) / 1000);
  };
  for (int e = 0; e < 3; ++e) {
    for (int n = 0; n < 3; ++n) {
      std::printf("effect %.2f, n %zu: power %.3f\n", effects[e], sizes[n], power[e][n]);
      if (e > 0) {
        EXPECT_GT(power[e][n], power[e - 1][n] + step(power[e - 1][n], power[e][n]))
            << "effect " << effects[e] << ", n " << sizes[n];
      }
      if (n > 0) {
        EXPECT_GT(power[e][n], power[e][n - 1] + step(power[e][n - 1], power[e][n]))
            << "effect " << effects[e] << ", n " << sizes[n];
      }
    }
  }
}

TEST(SimulationPower, PilotGivesCellMeansAndVarianceComponents) {
  // A small pilot: the means are the cell means, the sizes carry over, and the variance components
  // are the ANOVA estimators computed here by hand: MS(within) = sum (y_ij - mean_i - mean_gj +
  // mean_g)^2 / ((N - 2)(k - 1)), MS(between) = k sum (mean_i - mean_g)^2 / (N - 2).
  std::vector<Observation> obs;
  double y[6][3];
  for (int i = 0; i < 6; ++i) {
    for (int j = 1; j <= 3; ++j) {
      const double v =
          (i < 3 ? 0.5 : 0.3) + 0.1 * j + 0.05 * (i % 3) + ((i + j) % 2 ? 0.01 : -0.01) + 0.003 * ((i * j) % 5);
      y[i][j - 1] = v;
      obs.push_back({"P" + std::to_string(i), i < 3 ? "A" : "B", j, v, 0});
    }
  }
  const WideDesign w = make_wide_design(obs, "m", "pilot.csv");
  const SimulationDesign d = design_from_pilot(w);
  EXPECT_EQ(d.n_a, 3u);
  EXPECT_EQ(d.n_b, 3u);
  double cell[2][3] = {}, group[2] = {}, person[6] = {};
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 3; ++j) {
      cell[i / 3][j] += y[i][j] / 3;
      group[i / 3] += y[i][j] / 9;
      person[i] += y[i][j] / 3;
    }
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(d.means_a[j], cell[0][j], 1e-12);
    EXPECT_NEAR(d.means_b[j], cell[1][j], 1e-12);
  }
  double ss_within = 0, ss_between = 0;
  for (int i = 0; i < 6; ++i) {
    ss_between += 3 * (person[i] - group[i / 3]) * (person[i] - group[i / 3]);
    for (int j = 0; j < 3; ++j) {
      const double r = y[i][j] - person[i] - cell[i / 3][j] + group[i / 3];
      ss_within += r * r;
    }
  }
  const double ms_within = ss_within / (4 * 2), ms_between = ss_between / 4;
  ASSERT_GT(ms_between, ms_within);
  EXPECT_NEAR(d.sd_residual, std::sqrt(ms_within), 1e-12);
  EXPECT_NEAR(d.sd_participant, std::sqrt((ms_between - ms_within) / 3), 1e-12);

  // A large pilot drawn here from the generating model (sd_participant 0.1, sd_residual 0.15,
  // 200 per condition, 10 iterations): the estimates recover the truth within 4 of their standard
  // errors. SE(sd_residual) = sd_e / sqrt(2 df_w), df_w = (N - 2)(k - 1) = 3582: 0.0018.
  // SE(sd_participant) = SE(sd_u^2) / (2 sd_u), Var(sd_u^2) = 2 (E[MS_b]^2 / df_b + E[MS_w]^2 /
  // df_w) / k^2, E[MS_b] = sd_e^2 + k sd_u^2, df_b = N - 2 = 398: 0.0044. Mean of a cell: SE
  // sqrt((sd_u^2 + sd_e^2) / 200) = 0.0127.
  const double su = 0.1, se = 0.15;
  const std::size_t n = 200, k = 10;
  std::mt19937_64 rng(2026);
  std::normal_distribution<double> z(0, 1);
  std::vector<Observation> big;
  for (std::size_t i = 0; i < 2 * n; ++i) {
    const double u = su * z(rng);
    for (std::size_t j = 1; j <= k; ++j) {
      const double mu = i < n ? 0.6 : 0.6 - 0.02 * static_cast<double>(j);
      big.push_back({"P" + std::to_string(i), i < n ? "A" : "B", static_cast<long long>(j), mu + u + se * z(rng), 0});
    }
  }
  const SimulationDesign b = design_from_pilot(make_wide_design(big, "m", "big.csv"));
  const double df_w = (2.0 * n - 2) * (k - 1), df_b = 2.0 * n - 2, kd = static_cast<double>(k);
  const double se_residual = se / std::sqrt(2 * df_w);
  const double ms_b = se * se + kd * su * su;
  const double se_participant =
      std::sqrt(2 * (ms_b * ms_b / df_b + se * se * se * se / df_w) / (kd * kd)) / (2 * su);
  const double se_mean = std::sqrt((su * su + se * se) / static_cast<double>(n));
  EXPECT_NEAR(b.sd_residual, se, 4 * se_residual);
  EXPECT_NEAR(b.sd_participant, su, 4 * se_participant);
  for (std::size_t j = 0; j < k; ++j) {
    EXPECT_NEAR(b.means_a[j], 0.6, 4 * se_mean) << j;
    EXPECT_NEAR(b.means_b[j], 0.6 - 0.02 * static_cast<double>(j + 1), 4 * se_mean) << j;
  }
}

TEST(SimulationPower, BadDesignsAreUsageErrors) {
  SimulationDesign d = paper_like(5, 0.1);
  d.means_b.pop_back();
  EXPECT_THROW(simulate_power(d, {}), UsageError);
  d = paper_like(5, 0.1);
  d.sd_residual = 0;
  EXPECT_THROW(simulate_power(d, {}), UsageError);
}

}  // namespace
}  // namespace feint::models

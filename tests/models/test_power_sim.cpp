// Simulation power: the fast path agrees with the full mixed ANOVA and Welch tests on the same
// simulated data; a true null rejects at alpha within Monte Carlo error; runs are reproducible and
// independent of the number of threads.
#include <gtest/gtest.h>

#include <cmath>
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
  SimulationOptions o;
  o.studies = 1000;
  const double small = simulate_power(paper_like(10, 0.05), o).interaction.power;
  const double large = simulate_power(paper_like(10, 0.2), o).interaction.power;
  EXPECT_GT(large, small + 0.2);
}

TEST(SimulationPower, PilotGivesCellMeansAndVarianceComponents) {
  // A pilot with no noise beyond participant shifts: residual sd 0 is impossible, so add a known
  // alternating pattern; check the means are the cell means and sizes carry over.
  std::vector<Observation> obs;
  for (int i = 0; i < 6; ++i) {
    for (int j = 1; j <= 3; ++j) {
      const double v =
          (i < 3 ? 0.5 : 0.3) + 0.1 * j + 0.05 * (i % 3) + ((i + j) % 2 ? 0.01 : -0.01);
      obs.push_back({"P" + std::to_string(i), i < 3 ? "A" : "B", j, v, 0});
    }
  }
  const WideDesign w = make_wide_design(obs, "m", "pilot.csv");
  const SimulationDesign d = design_from_pilot(w);
  EXPECT_EQ(d.n_a, 3u);
  EXPECT_EQ(d.n_b, 3u);
  EXPECT_NEAR(d.means_a[0], (0.61 + 0.64 + 0.71) / 3, 1e-12);
  EXPECT_GT(d.sd_participant, 0.0);
  EXPECT_GT(d.sd_residual, 0.0);
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

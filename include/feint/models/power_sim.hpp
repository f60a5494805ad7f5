// feint/models/power_sim.hpp - simulation-based power of the 2-condition x k-iteration design: the
// condition x iteration interaction of the mixed ANOVA, the condition main effect, and the
// per-iteration contrasts of the paper's Table 1 (Welch t per iteration, p adjusted over the k
// iterations).
//
// Generating model (compound symmetry): y_ij = mu_{g(i), j} + u_i + e_ij, u_i ~ N(0,
// sd_participant^2), e_ij ~ N(0, sd_residual^2), all independent; the intra-class correlation is
// sd_participant^2 / (sd_participant^2 + sd_residual^2). Each simulated study is analysed as the
// real one: mixed ANOVA with the chosen sphericity correction (epsilon estimated from the simulated
// data, as afex does), Welch t-tests per iteration with stats::p_adjust.
//
// Fast path (no generic matrix code): per study, condition profiles and the k x k residual SSP E;
// with C the centring matrix, tr(P'EP) = tr(CEC) and sum lambda^2 = ||CEC||_F^2, so the
// Greenhouse-Geisser epsilon needs no eigen-decomposition: eps = tr(CEC)^2 / ((k-1) ||CEC||_F^2).
//
// Reproducible: study s draws from its own xoshiro256** stream seeded from (seed, s) by SplitMix64
// (the scheme of feint/rng.hpp), normals by Marsaglia's polar method, so the result depends on
// the seed only, not on the number of threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "feint/models/design.hpp"
#include "feint/models/mixed_anova.hpp"
#include "feint/stats/p_adjust.hpp"

namespace feint::models {

struct SimulationDesign {
  std::vector<double> means_a, means_b;  ///< true mean per iteration (same length k >= 2)
  double sd_participant = 0;             ///< sd of the participant intercepts
  double sd_residual = 1;                ///< sd of a trial around its participant's profile
  std::size_t n_a = 30, n_b = 30;        ///< participants per condition
};

struct SimulationOptions {
  std::size_t studies = 10000;
  std::uint64_t seed = 1;
  unsigned threads = 2;
  double alpha = 0.05;
  SphericityCorrection correction = SphericityCorrection::GG;
  stats::PAdjustMethod p_adjust = stats::PAdjustMethod::holm;  ///< over the k per-iteration tests
};

/// A proportion of studies with its Monte Carlo standard error sqrt(p (1 - p) / studies).
struct SimulatedPower {
  double power = 0;
  double mc_se = 0;
};

struct SimulationPowerResult {
  SimulationDesign design;
  SimulationOptions options;
  SimulatedPower interaction;    ///< condition:iteration F (corrected) p < alpha
  SimulatedPower condition;      ///< condition main effect p < alpha
  SimulatedPower any_iteration;  ///< at least one per-iteration contrast (adjusted) < alpha
  std::vector<SimulatedPower> iteration;  ///< per iteration: adjusted Welch p < alpha
  double mean_gg_eps = 0;                 ///< average estimated epsilon (GG)
};

/// The design a pilot suggests: per-condition means of every iteration, and the variance
/// components by the ANOVA (method-of-moments) estimators of the compound-symmetry model:
/// sd_residual^2 = MS(within error), sd_participant^2 = max(0, (MS(between error) - MS(within
/// error)) / k). The pilot must have exactly two conditions (InvalidData otherwise); group sizes
/// default to the pilot's.
SimulationDesign design_from_pilot(const WideDesign& pilot);

/// Runs `options.studies` simulated studies. Throws UsageError for a bad design (lengths differ,
/// k < 2, fewer than 2 participants per condition, sd_residual <= 0, studies == 0).
SimulationPowerResult simulate_power(const SimulationDesign& design,
                                     const SimulationOptions& options);

namespace detail {
/// One simulated study and its analysis (for tests: the fast path against mixed_anova and
/// stats::t_test_welch on the same data).
struct StudyAnalysis {
  std::vector<double> y;  ///< participants (A first) x iterations, row-major
  double f_interaction = 0, gg_eps = 0, p_interaction = 1, f_condition = 0;
  std::vector<double> p_iteration;  ///< unadjusted Welch p per iteration
};
StudyAnalysis analyse_simulated_study(const SimulationDesign& design,
                                      const SimulationOptions& options, std::uint64_t index);
}  // namespace detail

}  // namespace feint::models

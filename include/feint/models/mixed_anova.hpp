// feint/models/mixed_anova.hpp - the mixed (split-plot) ANOVA of a repeated-measures design:
// condition between participants x iteration within, as afex::aov_ez(id, dv, data,
// between = "condition", within = "iteration") reports it (afex 1.2, car 3.1).
//
// Type-III sums of squares with sum-to-zero (effect) contrasts for condition, the within part by
// the multivariate SSP approach of car::Anova.mlm (Fox & Weisberg 2019, ch. 9):
//   between stratum (participant sums s_i = sum_j y_ij, P = 1):
//     SS(condition) = sum_g n_g (mean_g(s) - mean(s))^2 / k,   Error SS = sum_i (s_i - mean_g(s))^2
//     / k
//   within stratum (orthonormal contrasts P, k x (k-1); E = P' [sum_i r_i r_i'] P with r_i the
//   participant's deviation from its condition's mean profile):
//     SS(iteration) = sum_j (m_j - m.)^2 / c,  m = unweighted mean of the condition profiles,
//                     c = sum_g (1/n_g) / a^2 (the variance factor of the effect-coded intercept),
//     SS(condition:iteration) = sum_g n_g || (profile_g - weighted mean profile) P ||^2,
//     Error SS = tr(E), df = (N - a)(k - 1).
// Sphericity (car:::summary.Anova.mlm): with lambda the eigenvalues of E and p = k - 1,
//   Greenhouse-Geisser eps = (sum lambda / p)^2 / (sum lambda^2 / p),
//   Huynh-Feldt eps (Lecoutre 1991 correction, as R) = ((N - a + 1) p eps_GG - 2) / (p (N - a - p
//   eps_GG)), used capped at 1; Mauchly's W = det(E) / (tr(E)/p)^p with R's chi-squared
//   approximation (including car's `3 * p` term, p = k there, reproduced for agreement with R).
// Effect sizes (afex): generalized eta squared (Olejnik & Algina 2003; Bakeman 2005), all factors
// manipulated: ges = SS / (SS + Error SS(between) + Error SS(within)); partial eta squared
// pes = SS / (SS + Error SS).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "feint/models/design.hpp"

namespace feint::models {

/// Which degrees of freedom the within-participant F tests use (afex's `correction`).
enum class SphericityCorrection { none, GG, HF };

/// "none", "GG", "HF" (case-insensitive); throws UsageError otherwise.
SphericityCorrection parse_sphericity_correction(std::string_view text);
std::string_view to_string(SphericityCorrection correction) noexcept;

/// One row of the ANOVA table.
struct AnovaEffect {
  std::string effect;             ///< "condition", "iteration", "condition:iteration"
  bool within = false;            ///< tested against the within-participant error
  double ss = 0;                  ///< type-III sum of squares
  double error_ss = 0;            ///< its error term's sum of squares
  double num_df = 0, den_df = 0;  ///< uncorrected
  double f = 0;
  double p_value = 1;                    ///< uncorrected (sphericity assumed)
  std::optional<double> gg_eps, hf_eps;  ///< within effects with num df > 1 and a regular E
  std::optional<double> p_gg, p_hf;      ///< p with GG df, and with HF df (eps capped at 1)
  double ges = 0, pes = 0;

  // As reported under the chosen correction (afex's anova_table): df multiplied by eps,
  // MSE = Error SS / corrected den df, p corrected. When the correction applies but cannot be
  // computed, these are the uncorrected values and `correction_note` says why.
  double report_num_df = 0, report_den_df = 0, mse = 0, report_p = 1;
  std::optional<double> report_eps;  ///< the eps applied (HF capped at 1), empty when none
  std::string correction_note;
};

/// Mauchly's test for one within effect (iteration and condition:iteration share their error and
/// get the same W and p, as in car's output).
struct MauchlyTest {
  std::string effect;
  std::optional<double> statistic;  ///< W
  std::optional<double> p_value;
  std::string note;  ///< why not computed
};

struct MixedAnova {
  std::string metric;
  std::vector<std::string> conditions;
  std::vector<std::size_t> group_sizes;
  std::vector<long long> iterations;
  std::size_t n_participants = 0;     ///< complete cases used
  std::vector<std::string> excluded;  ///< participants left out (missing values)
  /// Conditions dropped because all their participants were excluded (--drop-empty-conditions).
  std::vector<std::string> dropped_conditions;
  SphericityCorrection correction = SphericityCorrection::GG;
  std::vector<AnovaEffect> effects;     ///< condition (when > 1 condition), iteration, interaction
  std::vector<MauchlyTest> sphericity;  ///< empty for 2 iterations (sphericity holds trivially)
  /// Empty, or why sphericity tests and corrections cannot be computed (singular error SSP).
  std::string sphericity_note;
  bool one_way() const noexcept { return conditions.size() < 2; }
};

/// The mixed ANOVA of `design` (one condition: the one-way repeated-measures ANOVA). Throws
/// InvalidData when there is no error df (N <= number of conditions) or no residual variation.
MixedAnova mixed_anova(const WideDesign& design,
                       SphericityCorrection correction = SphericityCorrection::GG);

}  // namespace feint::models

// feint/models/within_anova.hpp - the repeated-measures ANOVA with condition AND iteration within
// participants (every participant sees every condition: within-participant designs,
// counterbalanced blocks), as afex::aov_ez(id, dv, data, within = c("condition", "iteration"))
// reports it (afex 1.2, car 3.1).
//
// The multivariate approach of car::Anova.mlm (Fox & Weisberg 2019, ch. 9). Each participant i has
// one response vector y_i of a x k cells (a conditions, k iterations; cell c * k + j). With P_a
// (a x (a-1)) and P_k (k x (k-1)) orthonormal contrasts and 1_m / sqrt(m) the normalised mean,
// each effect has its own orthonormal contrast matrix L (a k x q) in the cell space:
//   condition            L = P_a (x) 1_k / sqrt(k),   q = a - 1
//   iteration            L = 1_a / sqrt(a) (x) P_k,   q = k - 1
//   condition:iteration  L = P_a (x) P_k,             q = (a - 1)(k - 1)
//   participant stratum  L = 1_ak / sqrt(a k),        q = 1 (the error of the intercept)
// ((x) the Kronecker product). With z_i = L' y_i, z. their mean over the N complete participants:
//   SS(effect) = N ||z.||^2,   E = sum_i (z_i - z.)(z_i - z.)' (q x q),   Error SS = tr(E),
//   F = (SS / q) / (Error SS / (q (N - 1))) on q and q (N - 1) df.
// Every effect is tested against its own effect x participant error (unlike the split-plot design
// of mixed_anova.hpp, where iteration and condition:iteration share one error SSP).
// Sphericity, per effect with q > 1 (car:::summary.Anova.mlm), with lambda the eigenvalues of E:
//   Greenhouse-Geisser eps = (sum lambda / q)^2 / (sum lambda^2 / q),
//   Huynh-Feldt eps (Lecoutre 1991, as R) = (N q eps_GG - 2) / (q (N - 1 - q eps_GG)), used capped
//   at 1; Mauchly's W = det(E) / (tr(E)/q)^q with R's chi-squared approximation on N - 1 df
//   (car's second-order term uses 3 a k, the number of response columns, where the textbook has
//   3 q; reproduced for agreement with R).
// Degenerate cases: an effect with q = 1 (2 conditions, 2 iterations) satisfies sphericity
// trivially: eps = 1, no Mauchly test, no correction. E is singular when N - 1 < q (few
// participants, many cells): that effect's test and corrections are not computable and its F test
// assumes sphericity (car and afex do the same; the effect's correction_note says so).
// Effect sizes (afex, all factors manipulated): generalized eta squared ges = SS / (SS + the sum of
// ALL error SS, the participant stratum's included) (Olejnik & Algina 2003; Bakeman 2005); partial
// eta squared pes = SS / (SS + Error SS).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "feint/models/design.hpp"
#include "feint/models/mixed_anova.hpp"

namespace feint::models {

/// Participants x (conditions x iterations), complete cases only: afex drops a participant with
/// any missing cell from the whole analysis of the metric.
struct WithinDesign {
  std::string source;  ///< file name, for messages
  std::string metric;
  std::vector<std::string> conditions;    ///< levels in order of first appearance
  std::vector<long long> iterations;      ///< levels, ascending
  std::vector<std::string> participants;  ///< complete participants, order of first appearance
  /// participants x (conditions x iterations), row-major; cell index c * k() + j.
  std::vector<double> y;
  std::vector<std::string> excluded;  ///< participants left out for a missing cell (or value)

  std::size_t n() const noexcept { return participants.size(); }
  std::size_t a() const noexcept { return conditions.size(); }
  std::size_t k() const noexcept { return iterations.size(); }
  std::size_t cells() const noexcept { return a() * k(); }
  double at(std::size_t participant, std::size_t condition, std::size_t iteration) const {
    return y[participant * cells() + condition * k() + iteration];
  }
};

/// Builds the within design of `metric` from its observations. Throws InvalidData (exit 65) for
///  - two values for one participant x condition x iteration (`scores.csv:14: participant 'P03'
///    has a second value for condition 'honest' at iteration 2 (first on line 9)`),
///  - fewer than two iterations and fewer than two conditions (nothing to compare),
///  - a condition x iteration cell without a value for anybody,
///  - no participant with every cell, or fewer than two complete participants (no error df),
///  - a metric with no variance (every value equal).
WithinDesign make_within_design(std::span<const Observation> observations,
                                const std::string& metric, const std::string& source);

/// The ANOVA of `design`: effects condition (a > 1), iteration (k > 1) and condition:iteration
/// (both), all `within`. `group_sizes` holds N for every condition (each condition has every
/// participant). Throws InvalidData when an effect has no error variation (its error SS below
/// 1e-13 of the total sum of squares: its F is undefined).
MixedAnova within_anova(const WithinDesign& design,
                        SphericityCorrection correction = SphericityCorrection::GG);

}  // namespace feint::models

// feint/models/mixed_model.hpp - the linear mixed model of a repeated-measures study, fitted by
// REML, with type-III F tests and contrasts using Satterthwaite's degrees of freedom, as
// lme4::lmer + lmerTest::anova / lmerTest::contest (and emmeans with lmer.df = "satterthwaite").
//
//   y ~ group * time + (1 | participant)                (time as a factor, or a linear trend)
//   y ~ group * time + (1 + time | participant)         (linear trend with a random slope)
//   y ~ group * time + (1 + group | participant)        (group within participants: a random
//                                                        deviation per participant and group level)
//
// `group` is the between- (condition) or within- (strategy) factor, `time` the iteration (or the
// count of exposures to a strategy). The design uses R's default treatment coding with levels in R's
// order, so coefficients, their covariance and every contrast equal lme4's. See docs/mixed-model.md
// for the formulas and the golden tests (tests/golden/models/).
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "feint/stats/htest.hpp"

namespace feint::models {

/// Observations in long format, one entry per trial (all vectors the same length).
struct LongData {
  std::vector<std::string> participant;
  std::vector<std::string> group;  ///< condition (or strategy); all equal = one group
  std::vector<double> time;        ///< iteration (or exposure)
  std::vector<double> y;           ///< the metric (finite)
};

enum class TimeScale {
  factor,  ///< one level per distinct time value (iteration as a factor)
  linear,  ///< a numeric covariate (linear trend)
};

/// Denominator degrees of freedom of the F and t tests (lmerTest's `ddf`).
enum class DdfMethod {
  satterthwaite,  ///< lmerTest's default (Kuznetsova, Brockhoff & Christensen 2017)
  kenward_roger,  ///< Kenward & Roger (1997) as pbkrtest: adjusted vcov(beta), scaled F
};

struct ModelSpec {
  std::string response = "y";  ///< names used in term labels and notes
  std::string group = "condition";
  std::string time = "iteration";
  std::string participant = "participant";
  TimeScale time_scale = TimeScale::factor;
  bool random_slope = false;  ///< (1 + time | participant); only with TimeScale::linear
  /// (1 + group | participant): Z has the intercept and one treatment dummy per non-reference
  /// group level (R's model.matrix(~ group)), so q = the number of group levels and theta has
  /// q (q + 1) / 2 entries. Only with the group within participants (group_between == false) and
  /// not with random_slope (UsageError otherwise).
  bool random_group_slope = false;
  /// Order of the group levels (the first is the reference of the treatment coding). Empty: sorted
  /// as R's factor() sorts ASCII names (byte order).
  std::vector<std::string> group_levels;
  DdfMethod ddf = DdfMethod::satterthwaite;
};

/// One row of lmerTest's type-III ANOVA table.
struct AnovaTerm {
  std::string term;  ///< "condition", "iteration", "condition:iteration"
  double sum_sq = 0, mean_sq = 0, num_df = 0, den_df = 0, f = 0, p = 1;
  /// False when the test cannot be computed (a zero variance of the contrast, or Satterthwaite's
  /// df not positive and finite); the numbers are then meaningless and `note` says why.
  bool computed = true;
  std::string note;
};

/// Variance components (lme4's VarCorr) on the variance scale.
struct VarianceComponents {
  double participant = 0;             ///< variance of the random intercept
  std::optional<double> slope;        ///< variance of the random slope
  std::optional<double> correlation;  ///< intercept-slope correlation
  /// With random_group_slope: the variance of each non-reference group level's dummy (its
  /// participant deviation from the reference level), in the order of the levels.
  std::vector<double> group_slopes;
  /// With random_group_slope: the lower triangle of the random effects' correlation matrix
  /// (intercept, dummies), column-wise, as as.data.frame(VarCorr(m)) lists it: (intercept, g1),
  /// (intercept, g2), ..., (g1, g2), ...; NaN where a variance is 0 (R's NaN too).
  std::vector<double> group_correlations;
  double residual = 0;                ///< sigma^2
  /// Intraclass correlation participant / (participant + residual): the share of the variance
  /// between participants. Empty with a random slope (it then depends on time or group).
  std::optional<double> icc;
};

/// A fitted model. Everything a report needs; contrasts of the fixed effects via contrast().
struct MixedModelFit {
  ModelSpec spec;
  std::vector<std::string> group_levels;
  std::vector<double> time_levels;        ///< distinct time values, ascending
  std::vector<std::string> participants;  ///< distinct, first-appearance order
  std::size_t n_obs = 0;
  std::vector<std::size_t> trials_per_participant;

  std::vector<std::string> coef_names;  ///< lme4's fixef names, e.g. "conditionrandom:iteration3"
  Eigen::VectorXd beta;                 ///< fixef(m)
  Eigen::MatrixXd vcov_beta;            ///< vcov(m)
  Eigen::VectorXd theta;      ///< getME(m, "theta"): relative Cholesky factor, column-wise
  double sigma = 0;           ///< sigma(m)
  double reml_criterion = 0;  ///< REMLcrit(m) (-2 REML log-likelihood)
  /// A variance estimate on the boundary, as lme4's isSingular(tol = 1e-4): a diagonal entry of
  /// the relative Cholesky factor (theta's entries with lower bound 0) below 1e-4.
  bool singular = false;
  VarianceComponents variance;
  std::vector<AnovaTerm> anova;  ///< type III, Satterthwaite
  /// The hypothesis matrix L of each anova row (lmerTest's type-III contrasts; F = contrast_md(fit,
  /// L)): a property of the fixed effects alone, so a model with other random effects and the same
  /// fixed effects (fit_crossed_model) tests the same hypotheses.
  std::vector<Eigen::MatrixXd> anova_hypotheses;

  // Satterthwaite machinery (lmerTest): the variance parameters (theta, sigma), the asymptotic
  // covariance 2 H^-1 of their REML deviance, and d vcov(beta) / d varpar.
  Eigen::VectorXd varpar;
  Eigen::MatrixXd vcov_varpar;
  std::vector<Eigen::MatrixXd> jac_vcov_beta;

  // Kenward-Roger (spec.ddf == kenward_roger; pbkrtest's vcovAdj): the adjusted covariance
  // Phi_A = Phi + 2 Phi U Phi of beta, and the P_r = -X' S^-1 G_r S^-1 X and W = 2 IE2^-1 that
  // the df and the F scaling use (S the marginal covariance, G_r its derivative in the r-th
  // variance parameter).
  Eigen::MatrixXd vcov_beta_adj;
  std::vector<Eigen::MatrixXd> kr_P;
  Eigen::MatrixXd kr_W;

  /// The design row (fixed effects) of the cell (group level, time value).
  Eigen::VectorXd cell_row(std::size_t group_level, double time) const;
};

/// Fits the model by REML. Throws InvalidData (exit 65) when the data cannot identify it: fewer
/// than 2 participants, a response without variance, a participant in two groups when the group
/// is between participants (`group_between`), an empty group x time cell (time as a factor), a
/// time level without observations, or (random slopes) no more trials than random effects.
MixedModelFit fit_mixed_model(const LongData& data, const ModelSpec& spec, bool group_between);

/// A contrast of the fixed effects: the test (TestResult: test "lmm_contrast", estimate, t, df, p,
/// interval; not computable when its variance or df is not positive) and its standard error.
struct Contrast {
  stats::TestResult test;
  double std_error = 0;
};

/// A linear function L'beta with Satterthwaite's df, as lmerTest::contest1D(m, L, confint = TRUE)
/// (with spec.ddf == kenward_roger: SE from Phi_A and Kenward-Roger's df, as lmerTest's get_KR1D
/// and emmeans with lmer.df = "kenward-roger"):
/// estimate, SE = sqrt(L' V L), df = 2 (L'VL)^2 / (g' A g) with g_k = L' dV/dvarpar_k L and A the
/// covariance of the variance parameters; t = estimate / SE; two-sided p; interval estimate -+
/// qt(1 - (1 - conf)/2, df) SE.
Contrast contrast(const MixedModelFit& fit, const Eigen::VectorXd& L, double conf_level = 0.95);

/// pbkrtest's Lb_ddf(L, Phi, Phi_A): Kenward-Roger's denominator df of the hypothesis L beta = 0
/// (rows of L), and the F scaling factor lambda of .KR_adjust (F = lambda * Wald_A / q).
struct KenwardRogerDf {
  double ddf = 0;
  double f_scaling = 1;
};
KenwardRogerDf kenward_roger_df(const MixedModelFit& fit, const Eigen::MatrixXd& L);

/// lmerTest::contestMD(m, L): the Wald F of the rows of L (F = sum of the squared t of the
/// eigen-components of L V L' / q) with the Satterthwaite denominator df of lmerTest.
AnovaTerm contrast_md(const MixedModelFit& fit, const Eigen::MatrixXd& L);

namespace detail {

/// R's zapsmall(x, digits): rounds to `digits` significant digits of the largest |x| (lmerTest
/// rounds its type-III hypothesis matrices this way).
Eigen::MatrixXd zapsmall(const Eigen::MatrixXd& x, int digits = 7);

/// lmerTest's Doolittle factorisation (unit lower L of x = L U, entries below 1e-6 zeroed): its
/// type-I hypotheses are the rows of L'.
Eigen::MatrixXd doolittle_lower(const Eigen::MatrixXd& x, double eps = 1e-6);

}  // namespace detail

}  // namespace feint::models

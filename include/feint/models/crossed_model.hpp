// feint/models/crossed_model.hpp - the linear mixed model with the strategy as a random effect,
// fitted by REML as lme4::lmer, with lmerTest's Satterthwaite df:
//
//   y ~ group * time + (1 | participant) + (1 | strategy)               (crossed)
//   y ~ group * time + (1 | participant) + (1 | participant:strategy)   (nested)
//
// (and both strategy terms together). The fixed effects are fit_mixed_model's: the same
// treatment coding, level order, coefficient names and checks of the data. Each random term is an
// intercept of its grouping factor (lme4's Lambda diagonal, one theta per term); Z'Z is not block
// diagonal, so the penalised least squares are one dense system of all the levels. See
// docs/crossed-random-effects.md for the formulas and the golden tests.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "feint/models/mixed_model.hpp"

namespace feint::models {

/// A random intercept (lme4's random-effects term).
enum class RandomIntercept {
  participant,           ///< (1 | participant)
  strategy,              ///< (1 | strategy): crossed with participant
  participant_strategy,  ///< (1 | participant:strategy): strategy nested in participant
};

struct CrossedModelSpec {
  /// The fixed effects and names, as fit_mixed_model's spec. random_slope and random_group_slope
  /// must be false and ddf Satterthwaite (UsageError otherwise).
  ModelSpec model;
  std::string strategy = "strategy";  ///< the strategy column's name (terms, messages)
  /// The random intercepts in the formula's order, each at most once; (1 | participant) is
  /// required (UsageError otherwise).
  std::vector<RandomIntercept> random_terms = {RandomIntercept::participant,
                                               RandomIntercept::strategy};
};

/// One random intercept's estimate (a row of as.data.frame(VarCorr(m))).
struct RandomTermVariance {
  RandomIntercept term = RandomIntercept::participant;
  std::string name;        ///< lme4's grp: "participant", "strategy", "participant:strategy"
  std::size_t levels = 0;  ///< levels of the grouping factor (observed pairs for the nested term)
  double theta = 0;        ///< lme4's theta: the term's standard deviation / sigma
  double variance = 0;     ///< sigma^2 theta^2
  /// theta < 1e-4 (lme4's isSingular tolerance): the variance is estimated at its boundary 0.
  bool at_boundary = false;
};

/// One row of summary(m)'s coefficient table (lmerTest: Satterthwaite df).
struct Coefficient {
  std::string name;
  double estimate = 0, std_error = 0, df = 0, t = 0, p = 1;
  bool computed = true;  ///< false when the df are not positive and finite
};

/// lmerTest::ranova's row of a random term: the likelihood-ratio test of the model without it,
/// LRT = REMLcrit(without) - REMLcrit(with), against chi-squared with 1 df (not halved for the
/// boundary, as ranova).
struct RandomTermTest {
  RandomIntercept term = RandomIntercept::strategy;
  std::string name;  ///< "(1 | strategy)", "(1 | participant:strategy)"
  double lrt = 0, df = 1, p = 1;
};

struct CrossedModelFit {
  CrossedModelSpec spec;
  /// This model's fixed effects (beta, vcov_beta, coef_names, levels, cell_row) and Satterthwaite
  /// machinery (varpar = (theta, sigma), vcov_varpar, jac_vcov_beta) in the layout of
  /// fit_mixed_model's, so that contrast(), contrast_md() and emm_contrasts() work on it
  /// unchanged. Its theta is the terms' theta in lme4's order (that of `random`), sigma,
  /// reml_criterion and singular are this model's; variance holds participant and residual
  /// (no ICC); anova is lmerTest's type-III table of this model (the base model's hypotheses).
  MixedModelFit model;
  /// lme4's order: the formula's, unless a later term has more levels than an earlier one, then
  /// by decreasing number of levels (mkReTrms: rev(order(nlevels))).
  std::vector<RandomTermVariance> random;
  std::vector<std::string> strategies;  ///< the strategy levels, sorted as factor() sorts them
  std::vector<Coefficient> coefficients;
  std::vector<RandomTermTest> term_tests;  ///< one per strategy term
  /// Why a variance is 0, when one is (a singular fit); empty otherwise.
  std::string note;
};

/// Fits the model by REML. `strategy` holds each trial's strategy (same length as `data`; may be
/// empty only when no term uses it). Throws what fit_mixed_model throws, and InvalidData when
/// the strategy column is missing or a value is empty, there is a single strategy, a grouping
/// factor has as many levels as there are trials, there are not more trials than random effects,
/// or the nested term is the same grouping as participant (every participant saw one strategy).
CrossedModelFit fit_crossed_model(const LongData& data, const std::vector<std::string>& strategy,
                                  const CrossedModelSpec& spec, bool group_between);

/// lme4's name of a term's grouping factor ("participant", "strategy", "participant:strategy"),
/// from the spec's column names.
std::string term_name(const CrossedModelSpec& spec, RandomIntercept term);

/// The random part as lme4 writes it: "(1 | participant) + (1 | strategy)".
std::string random_formula(const CrossedModelSpec& spec);

}  // namespace feint::models

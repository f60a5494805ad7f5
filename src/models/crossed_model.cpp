// fit_crossed_model(): the strategy as a random effect, crossed with or nested in participant.
// The fixed effects, their checks and coding come from fit_mixed_model (the (1 | participant)
// model of the same data); the random part, its REML fit and lmerTest's Satterthwaite machinery
// are here and in crossed_model_reml.cpp. See feint/models/crossed_model.hpp.
#include "feint/models/crossed_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

#include "feint/error.hpp"
#include "mixed_model_detail.hpp"

namespace feint::models {

std::string term_name(const CrossedModelSpec& spec, RandomIntercept term) {
  switch (term) {
    case RandomIntercept::participant:
      return spec.model.participant;
    case RandomIntercept::strategy:
      return spec.strategy;
    case RandomIntercept::participant_strategy:
      return spec.model.participant + ":" + spec.strategy;
  }
  return {};
}

std::string random_formula(const CrossedModelSpec& spec) {
  std::string out;
  for (const RandomIntercept t : spec.random_terms)
    out += (out.empty() ? "" : " + ") + fmt::format("(1 | {})", term_name(spec, t));
  return out;
}

namespace {

bool uses_strategy(const CrossedModelSpec& spec) {
  return std::any_of(spec.random_terms.begin(), spec.random_terms.end(),
                     [](RandomIntercept t) { return t != RandomIntercept::participant; });
}

void check_spec(const CrossedModelSpec& spec) {
  const ModelSpec& m = spec.model;
  if (m.random_slope || m.random_group_slope)
    throw UsageError(fmt::format(
        "random slopes cannot be combined with a random {} term: use random intercepts only ({})",
        spec.strategy, random_formula(spec)));
  if (m.ddf != DdfMethod::satterthwaite)
    throw UsageError(
        fmt::format("Kenward-Roger df are not available with a random {} term; use Satterthwaite's",
                    spec.strategy));
  std::set<RandomIntercept> seen;
  for (const RandomIntercept t : spec.random_terms)
    if (!seen.insert(t).second)
      throw UsageError(fmt::format("the random term (1 | {}) is given twice", term_name(spec, t)));
  if (!seen.count(RandomIntercept::participant))
    throw UsageError(fmt::format("the model needs the random term (1 | {})", m.participant));
}

/// The strategy of every trial: present and not empty.
void check_strategy_column(const LongData& data, const std::vector<std::string>& strategy,
                           const CrossedModelSpec& spec) {
  if (!uses_strategy(spec)) return;
  if (strategy.empty())
    throw InvalidData(fmt::format("no {} column: the random part {} needs the {} of every trial",
                                  spec.strategy, random_formula(spec), spec.strategy));
  if (strategy.size() != data.y.size())
    throw std::invalid_argument("fit_crossed_model: strategy and data of different lengths");
  for (std::size_t i = 0; i < strategy.size(); ++i)
    if (strategy[i].find_first_not_of(" \t\r\n") == std::string::npos)
      throw InvalidData(fmt::format(
          "{} is empty for the trial of {} {} at {} {}: the random part {} needs the {} of "
          "every trial",
          spec.strategy, spec.model.participant, data.participant[i], spec.model.time, data.time[i],
          random_formula(spec), spec.strategy));
}

/// A grouping factor: its levels (sorted, as factor() sorts ASCII names) and each trial's level.
struct Grouping {
  RandomIntercept term;
  std::string name;
  std::vector<std::string> levels;
  std::vector<std::size_t> index;
};

Grouping grouping_of(RandomIntercept term, const std::string& name,
                     const std::vector<std::string>& key) {
  Grouping g{term, name, {}, std::vector<std::size_t>(key.size())};
  const std::set<std::string> s(key.begin(), key.end());
  g.levels.assign(s.begin(), s.end());
  for (std::size_t i = 0; i < key.size(); ++i)
    g.index[i] = static_cast<std::size_t>(
        std::lower_bound(g.levels.begin(), g.levels.end(), key[i]) - g.levels.begin());
  return g;
}

std::vector<Grouping> groupings(const LongData& data, const std::vector<std::string>& strategy,
                                const CrossedModelSpec& spec) {
  std::vector<Grouping> out;
  for (const RandomIntercept t : spec.random_terms) {
    std::vector<std::string> key = data.participant;
    if (t == RandomIntercept::strategy) key = strategy;
    if (t == RandomIntercept::participant_strategy)
      for (std::size_t i = 0; i < key.size(); ++i) key[i] += '\x1f' + strategy[i];  // a pair
    out.push_back(grouping_of(t, term_name(spec, t), key));
  }
  return out;
}

/// lme4's checks of the grouping factors (check.nlev.gtr.1, check.nobs.vs.nlev,
/// check.nobs.vs.nRE), and two terms that group the trials identically (their variances cannot be
/// told apart).
void check_groupings(const std::vector<Grouping>& gs, const CrossedModelSpec& spec,
                     const std::vector<std::string>& strategies, std::size_t n) {
  std::size_t q = 0;
  for (const Grouping& g : gs) {
    q += g.levels.size();
    if (g.term == RandomIntercept::strategy && g.levels.size() < 2)
      throw InvalidData(fmt::format(
          "metric '{}': one {} ('{}'): a variance between {} levels cannot be estimated from "
          "one; the random term (1 | {}) needs at least two",
          spec.model.response, spec.strategy, strategies.empty() ? "" : strategies[0],
          spec.strategy, spec.strategy));
    if (g.levels.size() >= n)
      throw InvalidData(fmt::format(
          "metric '{}': (1 | {}) has {} levels for {} trials: every level has a single trial, so "
          "its variance cannot be told apart from the residual variance",
          spec.model.response, g.name, g.levels.size(), n));
  }
  if (n <= q)
    throw InvalidData(fmt::format(
        "metric '{}': {} trials are not more than the {} random effects of {}: the variances "
        "cannot all be estimated",
        spec.model.response, n, q, random_formula(spec)));
  for (std::size_t a = 0; a < gs.size(); ++a)
    for (std::size_t b = a + 1; b < gs.size(); ++b) {
      std::set<std::pair<std::size_t, std::size_t>> pairs;
      for (std::size_t i = 0; i < n; ++i) pairs.emplace(gs[a].index[i], gs[b].index[i]);
      if (pairs.size() == gs[a].levels.size() && pairs.size() == gs[b].levels.size())
        throw InvalidData(fmt::format(
            "metric '{}': (1 | {}) and (1 | {}) group the trials identically{}: their variances "
            "cannot be told apart",
            spec.model.response, gs[a].name, gs[b].name,
            gs[b].term == RandomIntercept::participant_strategy ||
                    gs[a].term == RandomIntercept::participant_strategy
                ? fmt::format(" (every {} saw one {})", spec.model.participant, spec.strategy)
                : ""));
    }
}

/// lme4's order of the terms (mkReTrms): the formula's, unless a later term has more levels than
/// an earlier one; then rev(order(nlevels)), R's order being stable.
std::vector<std::size_t> lme4_term_order(const std::vector<Grouping>& gs) {
  std::vector<std::size_t> ord(gs.size());
  for (std::size_t k = 0; k < ord.size(); ++k) ord[k] = k;
  bool increase = false;
  for (std::size_t k = 1; k < gs.size(); ++k)
    if (gs[k].levels.size() > gs[k - 1].levels.size()) increase = true;
  if (!increase) return ord;
  std::stable_sort(ord.begin(), ord.end(), [&](std::size_t a, std::size_t b) {
    return gs[a].levels.size() < gs[b].levels.size();
  });
  std::reverse(ord.begin(), ord.end());
  return ord;
}

/// The fixed-effects design of the trials, in their order: the rows of fit_mixed_model's design.
Eigen::MatrixXd fixed_design(const LongData& data, const MixedModelFit& base) {
  const auto n = static_cast<Eigen::Index>(data.y.size());
  Eigen::MatrixXd X(n, static_cast<Eigen::Index>(base.coef_names.size()));
  std::map<std::pair<std::size_t, double>, Eigen::VectorXd> cell;  // cell_row formats names
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto r = static_cast<std::size_t>(i);
    const auto g = static_cast<std::size_t>(
        std::find(base.group_levels.begin(), base.group_levels.end(), data.group[r]) -
        base.group_levels.begin());
    auto it = cell.find({g, data.time[r]});
    if (it == cell.end())
      it = cell.emplace(std::pair{g, data.time[r]}, base.cell_row(g, data.time[r])).first;
    X.row(i) = it->second.transpose();
  }
  return X;
}

/// beta, sigma, vcov(beta), the REML criterion and the Satterthwaite machinery in the units of y,
/// from the fit in those of y / 2^scale_exp.
void store_estimates(MixedModelFit& m, const detail::CrossedProblem& problem,
                     const Eigen::VectorXd& theta, int scale_exp) {
  const detail::ThetaDerivatives d = problem.derivatives(theta);
  const double n = problem.n(), p = problem.p();
  const double sigma_s = std::sqrt(d.ev.r2 / (n - p));
  m.theta = theta;
  m.sigma = std::ldexp(sigma_s, scale_exp);
  m.beta = d.ev.beta.unaryExpr([&](double v) { return std::ldexp(v, scale_exp); });
  // REMLcrit of y: (n - p) log(r2) gains (n - p) log(2^(2k)).
  m.reml_criterion = detail::profiled_reml_at(d.ev, n, p) +
                     (n - p) * 2.0 * static_cast<double>(scale_exp) * std::log(2.0);
  m.vcov_beta = m.sigma * m.sigma * d.C;
  detail::SatterthwaiteParts parts = detail::satterthwaite_parts(
      detail::reml_deviance_hessian_at(d, sigma_s, n, p), detail::vcov_beta_jacobian_at(d, sigma_s),
      sigma_s, m.sigma, scale_exp);
  m.varpar.resize(theta.size() + 1);
  m.varpar << theta, m.sigma;
  m.vcov_varpar = std::move(parts.vcov_varpar);
  m.jac_vcov_beta = std::move(parts.jac_vcov_beta);
}

/// The variance components, isSingular and the note on variances at the boundary.
void store_random(CrossedModelFit& fit, const std::vector<Grouping>& gs,
                  const std::vector<std::size_t>& order) {
  MixedModelFit& m = fit.model;
  const double s2 = m.sigma * m.sigma;
  m.variance = VarianceComponents{};
  m.variance.residual = s2;
  m.singular = false;
  std::vector<std::string> zero;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Grouping& g = gs[order[k]];
    RandomTermVariance r;
    r.term = g.term;
    r.name = g.name;
    r.levels = g.levels.size();
    r.theta = m.theta(static_cast<Eigen::Index>(k));
    r.variance = s2 * r.theta * r.theta;
    r.at_boundary = r.theta < 1e-4;  // lme4's isSingular(tol = 1e-4)
    if (g.term == RandomIntercept::participant) m.variance.participant = r.variance;
    if (r.at_boundary) {
      m.singular = true;
      zero.push_back(fmt::format("(1 | {})", r.name));
    }
    fit.random.push_back(r);
  }
  if (zero.empty()) return;
  std::string terms = zero[0];
  for (std::size_t i = 1; i < zero.size(); ++i) terms += " and " + zero[i];
  fit.note = fmt::format(
      "boundary (singular) fit: the variance of {} is estimated at 0 (theta below 1e-4, lme4's "
      "isSingular): the data show no variation between its levels beyond the other terms and the "
      "residual, and the fixed effects, their SEs and df are those of the model without it",
      terms);
}

void store_coefficients(CrossedModelFit& fit) {
  const MixedModelFit& m = fit.model;
  for (std::size_t j = 0; j < m.coef_names.size(); ++j) {
    Eigen::VectorXd L = Eigen::VectorXd::Zero(m.beta.size());
    L(static_cast<Eigen::Index>(j)) = 1;
    const Contrast c = contrast(m, L);
    Coefficient row;
    row.name = m.coef_names[j];
    row.estimate = m.beta(static_cast<Eigen::Index>(j));
    row.std_error =
        std::sqrt(m.vcov_beta(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(j)));
    row.computed = c.test.computed;
    if (row.computed) {
      row.df = *c.test.df;
      row.t = *c.test.statistic;
      row.p = *c.test.p_value;
    }
    fit.coefficients.push_back(row);
  }
}

/// The model with the random terms of `spec`, its fixed effects those of `base`.
CrossedModelFit fit_terms(const LongData& data, const std::vector<std::string>& strategy,
                          const CrossedModelSpec& spec, const MixedModelFit& base) {
  CrossedModelFit fit;
  fit.spec = spec;
  const std::vector<Grouping> gs = groupings(data, strategy, spec);
  if (uses_strategy(spec)) {
    const std::set<std::string> s(strategy.begin(), strategy.end());
    fit.strategies.assign(s.begin(), s.end());
  }
  check_groupings(gs, spec, fit.strategies, data.y.size());
  const std::vector<std::size_t> order = lme4_term_order(gs);
  std::vector<std::vector<std::size_t>> level;
  std::vector<std::size_t> n_levels;
  for (const std::size_t k : order) {
    level.push_back(gs[k].index);
    n_levels.push_back(gs[k].levels.size());
  }
  const Eigen::VectorXd y =
      Eigen::Map<const Eigen::VectorXd>(data.y.data(), static_cast<Eigen::Index>(data.y.size()));
  // Scale invariance, as fit_mixed_model: the fit sees y / 2^k (exact), k from y's spread.
  const int scale_exp = detail::response_scale_exponent(y);
  const detail::CrossedProblem problem(
      fixed_design(data, base), y.unaryExpr([&](double v) { return std::ldexp(v, -scale_exp); }),
      level, n_levels);
  fit.model = base;
  fit.model.anova.clear();
  fit.model.vcov_beta_adj.resize(0, 0);
  fit.model.kr_P.clear();
  fit.model.kr_W.resize(0, 0);
  store_estimates(fit.model, problem, detail::optimise_crossed_theta(problem), scale_exp);
  store_random(fit, gs, order);
  store_coefficients(fit);
  return fit;
}

}  // namespace

CrossedModelFit fit_crossed_model(const LongData& data, const std::vector<std::string>& strategy,
                                  const CrossedModelSpec& spec, bool group_between) {
  check_spec(spec);
  check_strategy_column(data, strategy, spec);
  // The (1 | participant) model: its checks of the data, its design, and the reduced model of
  // the likelihood-ratio tests.
  const MixedModelFit base = fit_mixed_model(data, spec.model, group_between);
  CrossedModelFit fit = fit_terms(data, strategy, spec, base);
  // lmerTest's type-III table of this model: the base model's hypotheses, this model's covariance.
  for (std::size_t t = 0; t < base.anova.size() && t < base.anova_hypotheses.size(); ++t) {
    AnovaTerm row = contrast_md(fit.model, base.anova_hypotheses[t]);
    row.term = base.anova[t].term;
    fit.model.anova.push_back(row);
  }
  for (const RandomIntercept t : spec.random_terms) {
    if (t == RandomIntercept::participant) continue;
    CrossedModelSpec reduced = spec;
    std::erase(reduced.random_terms, t);
    const double without = reduced.random_terms.size() == 1
                               ? base.reml_criterion
                               : fit_terms(data, strategy, reduced, base).model.reml_criterion;
    RandomTermTest test;
    test.term = t;
    test.name = fmt::format("(1 | {})", term_name(spec, t));
    // The full model contains the reduced one: a negative difference is rounding (a variance at 0).
    test.lrt = std::max(0.0, without - fit.model.reml_criterion);
    test.p = boost::math::cdf(boost::math::complement(boost::math::chi_squared(1.0), test.lrt));
    fit.term_tests.push_back(test);
  }
  return fit;
}

}  // namespace feint::models

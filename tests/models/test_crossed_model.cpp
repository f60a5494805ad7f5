// The strategy as a random effect against lme4 / lmerTest (tests/golden/models/crossed_golden.R):
// per data set
//   crossed  y ~ condition * iteration + (1 | participant) + (1 | strategy)
//   nested   y ~ condition * iteration + (1 | participant) + (1 | participant:strategy)
// summary(m)'s coefficients (estimate, SE, Satterthwaite df, t, p), theta, sigma, REMLcrit,
// isSingular, VarCorr, ranova's test of the strategy term and two contest() contrasts; then the
// boundary note, the reduction to fit_mixed_model, the exact derivatives, scale invariance and the
// refusals.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "../../src/models/mixed_model_detail.hpp"
#include "accuracy.hpp"
#include "feint/error.hpp"
#include "feint/models/crossed_model.hpp"
#include "feint/models/emmeans.hpp"
#include "golden_csv.hpp"

namespace {

using feint::models::CrossedModelFit;
using feint::models::CrossedModelSpec;
using feint::models::LongData;
using feint::models::RandomIntercept;

const std::vector<std::vector<std::string>>& golden_rows() {
  static const auto rows =
      feint::test::read_csv(feint::test::kModelGoldenDir + "crossed_golden.csv");
  return rows;
}

// g[dataset|model][quantity][name]
using Golden = std::map<std::string, std::map<std::string, std::map<std::string, double>>>;
const Golden& golden() {
  static const Golden g = [] {
    Golden m;
    const auto& rows = golden_rows();
    for (std::size_t r = 1; r < rows.size(); ++r)
      m[rows[r][0] + "|" + rows[r][1]][rows[r][2]][rows[r][3]] = std::stod(rows[r][4]);
    return m;
  }();
  return g;
}

// getME(m, "theta")'s names in R's order (lme4's order of the terms).
std::vector<std::string> theta_names(const std::string& key) {
  std::vector<std::string> out;
  for (const auto& row : golden_rows())
    if (row.size() > 3 && row[0] + "|" + row[1] == key && row[2] == "theta") out.push_back(row[3]);
  return out;
}

struct Data {
  LongData trials;
  std::vector<std::string> strategy;
};

Data load(const std::string& dataset) {
  static const auto rows = feint::test::read_csv(feint::test::kModelGoldenDir + "crossed_data.csv");
  Data d;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    if (rows[r][0] != dataset) continue;
    d.trials.participant.push_back(rows[r][1]);
    d.trials.group.push_back(rows[r][2]);
    d.trials.time.push_back(std::stod(rows[r][3]));
    d.strategy.push_back(rows[r][4]);
    d.trials.y.push_back(std::stod(rows[r][5]));
  }
  return d;
}

CrossedModelSpec spec_of(const std::string& dataset, const std::string& model) {
  CrossedModelSpec s;
  s.model.response = "y";
  if (dataset == "trend") s.model.time_scale = feint::models::TimeScale::linear;
  s.random_terms = {RandomIntercept::participant, model == "nested"
                                                      ? RandomIntercept::participant_strategy
                                                      : RandomIntercept::strategy};
  return s;
}

CrossedModelFit fit(const std::string& dataset, const std::string& model) {
  const Data d = load(dataset);
  return feint::models::fit_crossed_model(d.trials, d.strategy, spec_of(dataset, model), true);
}

// The brief's tolerance: 1e-6 relative (absolute `abs` where the value is near 0).
constexpr double kTol = 1e-6;

void expect_close(double got, double want, const std::string& family, const std::string& what,
                  double rel, double abs = 0) {
  feint::test::record("crossed " + family, got, want, what);
  EXPECT_LE(std::abs(got - want), std::max(rel * std::abs(want), abs))
      << what << " " << family << ": got " << got << ", R " << want;
}

void check_coefficients(const std::string& key, const CrossedModelFit& f) {
  const auto& g = golden().at(key);
  ASSERT_EQ(f.coefficients.size(), g.at("beta").size()) << key;
  for (const auto& c : f.coefficients) {
    ASSERT_TRUE(c.computed) << key << " " << c.name;
    const double se = g.at("se").at(c.name), t = g.at("t").at(c.name);
    const std::string w = key + " " + c.name;
    // An estimate near 0 has no relative precision: relative to its SE.
    expect_close(c.estimate / se, g.at("beta").at(c.name) / se, "estimate (in SE)", w, 0, kTol);
    expect_close(c.std_error, se, "SE", w, kTol);
    expect_close(c.df, g.at("df").at(c.name), "df", w, kTol);
    expect_close(c.t, t, "t", w, 0, kTol * std::max(1.0, std::abs(t)));
    // p's error is t's times the density: relative to p, |t| magnifies it.
    expect_close(c.p, g.at("p").at(c.name), "p", w, kTol * std::max(1.0, t * t));
  }
}

void check_random(const std::string& key, const CrossedModelFit& f) {
  const auto& g = golden().at(key);
  ASSERT_EQ(f.random.size(), g.at("theta").size()) << key;
  const auto& theta = g.at("theta");
  const std::vector<std::string> order = theta_names(key);
  for (std::size_t k = 0; k < f.random.size(); ++k) {
    const auto& r = f.random[k];
    // lme4's order of the terms: that of model.theta and of R's theta.
    EXPECT_EQ(f.model.theta(static_cast<Eigen::Index>(k)), r.theta);
    EXPECT_EQ(order.at(k), r.name + ".(Intercept)") << key;
    expect_close(r.theta, theta.at(r.name + ".(Intercept)"), "theta", key + " " + r.name, kTol,
                 1e-7);
    expect_close(r.variance, g.at("variance").at(r.name), "variance", key + " " + r.name, kTol,
                 1e-12);
  }
  expect_close(f.model.variance.residual, g.at("variance").at("Residual"), "variance",
               key + " Residual", kTol);
  expect_close(f.model.sigma, g.at("sigma").at(""), "sigma", key, kTol);
  // feint's optimum is never worse than lme4's: the REML criterion not above R's.
  const double crit = g.at("REMLcrit").at("");
  EXPECT_LE(f.model.reml_criterion, crit + 1e-8) << key;
  expect_close(f.model.reml_criterion, crit, "REMLcrit", key, 1e-12);
  EXPECT_EQ(f.model.singular, g.at("singular").at("") != 0) << key;
  EXPECT_EQ(f.note.empty(), !f.model.singular) << key;
  ASSERT_EQ(f.term_tests.size(), 1u) << key;
  expect_close(f.term_tests[0].lrt, g.at("ranova.LRT").at(""), "ranova LRT", key, kTol, 1e-6);
  expect_close(f.term_tests[0].p, g.at("ranova.p").at(""), "ranova p", key,
               kTol * std::max(1.0, f.term_tests[0].lrt), 1e-300);
}

// The contrasts random - adaptive at the last iteration and averaged over the iterations (the
// trend: at iteration 10), as contest(m, L, joint = FALSE, confint = TRUE).
void check_contrasts(const std::string& dataset, const std::string& key, const CrossedModelFit& f) {
  const auto& g = golden().at(key);
  const auto& m = f.model;
  const double last = m.time_levels.back();
  std::map<std::string, Eigen::VectorXd> L;
  L["last"] = m.cell_row(1, last) - m.cell_row(0, last);
  if (dataset == "trend") {
    L["mean"] = m.cell_row(1, 10) - m.cell_row(0, 10);
  } else {
    L["mean"] = Eigen::VectorXd::Zero(m.beta.size());
    for (const double t : m.time_levels) L["mean"] += (m.cell_row(1, t) - m.cell_row(0, t));
    L["mean"] /= static_cast<double>(m.time_levels.size());
  }
  for (const auto& [name, l] : L) {
    const auto c = feint::models::contrast(m, l);
    ASSERT_TRUE(c.test.computed) << key << " " << name;
    const double se = g.at("c.SE").at(name), t = g.at("c.t").at(name);
    const std::string w = key + " " + name;
    expect_close(*c.test.estimate / se, g.at("c.estimate").at(name) / se,
                 "contrast estimate (in SE)", w, 0, kTol);
    expect_close(c.std_error, se, "contrast SE", w, kTol);
    expect_close(*c.test.df, g.at("c.df").at(name), "contrast df", w, kTol);
    expect_close(*c.test.statistic, t, "contrast t", w, 0, kTol * std::max(1.0, std::abs(t)));
    expect_close(*c.test.p_value, g.at("c.p").at(name), "contrast p", w,
                 kTol * std::max(1.0, t * t));
    expect_close(*c.test.conf_low / se, g.at("c.lower").at(name) / se, "contrast interval (in SE)",
                 w, 0, kTol);
    expect_close(*c.test.conf_high / se, g.at("c.upper").at(name) / se, "contrast interval (in SE)",
                 w, 0, kTol);
  }
}

void check_dataset(const std::string& dataset) {
  for (const char* model : {"crossed", "nested"}) {
    SCOPED_TRACE(dataset + " " + model);
    const std::string key = dataset + "|" + model;
    const CrossedModelFit f = fit(dataset, model);
    check_coefficients(key, f);
    check_random(key, f);
    check_contrasts(dataset, key, f);
  }
}

// lmerTest's type-III table (anova(m)) of each model: tests/golden/models/crossed_anova_golden.R.
void check_anova(const std::string& dataset) {
  static const auto rows = feint::test::read_csv(feint::test::kModelGoldenDir + "crossed_anova_golden.csv");
  for (const char* model : {"crossed", "nested"}) {
    const CrossedModelFit f = fit(dataset, model);
    std::size_t checked = 0;
    for (std::size_t r = 1; r < rows.size(); ++r) {
      if (rows[r][0] != dataset || rows[r][1] != model) continue;
      const auto row = std::find_if(f.model.anova.begin(), f.model.anova.end(),
                                    [&](const auto& a) { return a.term == rows[r][2]; });
      ASSERT_NE(row, f.model.anova.end()) << dataset << " " << model << " " << rows[r][2];
      ASSERT_TRUE(row->computed) << row->note;
      const double want = std::stod(rows[r][4]);
      const std::string w = dataset + " " + model + " " + rows[r][2];
      const std::string& q = rows[r][3];
      if (q == "NumDF") {
        EXPECT_EQ(row->num_df, want) << w;
      }
      if (q == "DenDF") expect_close(row->den_df, want, "anova DenDF", w, kTol);
      if (q == "F value") expect_close(row->f, want, "anova F", w, kTol);
      if (q == "Pr(>F)") expect_close(row->p, want, "anova p", w, kTol * std::max(1.0, row->f));
      ++checked;
    }
    EXPECT_EQ(checked, 4 * f.model.anova.size()) << dataset << " " << model;
    EXPECT_EQ(f.model.anova.size(), 3u);
  }
}

TEST(CrossedGolden, TypeThreeAnovaOfEveryDataSet) {
  for (const char* ds : {"balanced", "unbalanced_missing", "adaptive_choice", "nested_strong", "singular_strategy", "trend"})
    check_anova(ds);
}

TEST(CrossedGolden, Balanced) { check_dataset("balanced"); }
TEST(CrossedGolden, UnbalancedMissing) { check_dataset("unbalanced_missing"); }
TEST(CrossedGolden, AdaptiveChoice) { check_dataset("adaptive_choice"); }
TEST(CrossedGolden, NestedStrong) { check_dataset("nested_strong"); }
TEST(CrossedGolden, SingularStrategy) { check_dataset("singular_strategy"); }
TEST(CrossedGolden, Trend) { check_dataset("trend"); }

// The golden's singular fit: the strategy variance at 0, the note says so, and the model is then
// the (1 | participant) model (fit_mixed_model) in every number.
TEST(CrossedModel, BoundaryNoteAndReductionToParticipantModel) {
  const Data d = load("singular_strategy");
  const CrossedModelFit f = fit("singular_strategy", "crossed");
  ASSERT_EQ(f.random.size(), 2u);
  EXPECT_EQ(f.random[1].name, "strategy");
  EXPECT_TRUE(f.random[1].at_boundary);
  EXPECT_EQ(f.random[1].theta, 0.0);
  EXPECT_FALSE(f.random[0].at_boundary);
  EXPECT_TRUE(f.model.singular);
  EXPECT_NE(f.note.find("(1 | strategy)"), std::string::npos) << f.note;
  EXPECT_NE(f.note.find("singular"), std::string::npos) << f.note;
  EXPECT_EQ(f.term_tests[0].lrt, 0.0);
  EXPECT_EQ(f.term_tests[0].p, 1.0);
  feint::models::ModelSpec ms;
  ms.response = "y";
  const auto base = feint::models::fit_mixed_model(d.trials, ms, true);
  EXPECT_NEAR(f.model.reml_criterion, base.reml_criterion, 1e-9);
  for (Eigen::Index j = 0; j < base.beta.size(); ++j) {
    Eigen::VectorXd L = Eigen::VectorXd::Zero(base.beta.size());
    L(j) = 1;
    const auto c0 = feint::models::contrast(base, L);
    const auto& c = f.coefficients[static_cast<std::size_t>(j)];
    EXPECT_NEAR(c.estimate, *c0.test.estimate, 1e-9 * c0.std_error);
    EXPECT_NEAR(c.std_error, c0.std_error, 1e-9 * c0.std_error);
    EXPECT_NEAR(c.df, *c0.test.df, 1e-8 * *c0.test.df) << c.name;
  }
  // A positive strategy variance: no note.
  const CrossedModelFit b = fit("balanced", "crossed");
  EXPECT_FALSE(b.model.singular);
  EXPECT_TRUE(b.note.empty()) << b.note;
}

// (1 | participant) alone through the crossed fitter is fit_mixed_model's model: an independent
// check of the penalised least squares, the optimiser and the Satterthwaite machinery.
TEST(CrossedModel, ParticipantOnlyEqualsFitMixedModel) {
  for (const char* dataset : {"unbalanced_missing", "trend"}) {
    const Data d = load(dataset);
    CrossedModelSpec s = spec_of(dataset, "crossed");
    s.random_terms = {RandomIntercept::participant};
    const CrossedModelFit f = feint::models::fit_crossed_model(d.trials, {}, s, true);
    const auto base = feint::models::fit_mixed_model(d.trials, s.model, true);
    EXPECT_NEAR(f.model.theta(0), base.theta(0), 1e-9) << dataset;
    EXPECT_NEAR(f.model.reml_criterion, base.reml_criterion, 1e-9) << dataset;
    EXPECT_TRUE(f.term_tests.empty());
    for (Eigen::Index j = 0; j < base.beta.size(); ++j) {
      const auto& c = f.coefficients[static_cast<std::size_t>(j)];
      const double se = std::sqrt(base.vcov_beta(j, j));
      EXPECT_NEAR(c.estimate, base.beta(j), 1e-9 * se) << dataset << " " << c.name;
      EXPECT_NEAR(c.std_error, se, 1e-9 * se) << dataset << " " << c.name;
      Eigen::VectorXd L = Eigen::VectorXd::Zero(base.beta.size());
      L(j) = 1;
      EXPECT_NEAR(c.df, *feint::models::contrast(base, L).test.df, 1e-8 * c.df) << c.name;
    }
  }
}

// The per-iteration contrasts of emmeans work on the crossed fit unchanged: adaptive - random at
// the last iteration is minus the golden's "last" contrast.
TEST(CrossedModel, EmmeansOnTheCrossedFit) {
  const CrossedModelFit f = fit("unbalanced_missing", "crossed");
  const auto& g = golden().at("unbalanced_missing|crossed");
  const auto rows = feint::models::emm_contrasts(
      f.model, feint::models::EmmFamily::condition_at_iteration, feint::models::EmmAdjust::none);
  ASSERT_EQ(rows.size(), 20u);
  const auto& r = rows.back();
  EXPECT_EQ(r.by, "20");
  EXPECT_NEAR(r.estimate, -g.at("c.estimate").at("last"), kTol * r.std_error);
  EXPECT_NEAR(r.std_error, g.at("c.SE").at("last"), kTol * r.std_error);
  EXPECT_NEAR(r.df, g.at("c.df").at("last"), kTol * r.df);
  EXPECT_NEAR(r.p_value, g.at("c.p").at("last"), kTol * r.p_value);
}

// Multiplying y by c scales beta and SE by c and leaves theta, df, t and p unchanged.
TEST(CrossedModel, ScaleInvariant) {
  Data d = load("adaptive_choice");
  const auto s = spec_of("adaptive_choice", "nested");
  const CrossedModelFit f1 = feint::models::fit_crossed_model(d.trials, d.strategy, s, true);
  for (double& v : d.trials.y) v *= 1e-6;
  const CrossedModelFit f2 = feint::models::fit_crossed_model(d.trials, d.strategy, s, true);
  for (Eigen::Index k = 0; k < f1.model.theta.size(); ++k)
    EXPECT_NEAR(f2.model.theta(k), f1.model.theta(k), 1e-9);
  for (std::size_t j = 0; j < f1.coefficients.size(); ++j) {
    const auto &a = f1.coefficients[j], &b = f2.coefficients[j];
    EXPECT_NEAR(b.std_error, 1e-6 * a.std_error, 1e-9 * 1e-6 * a.std_error) << a.name;
    EXPECT_NEAR(b.df, a.df, 1e-8 * a.df) << a.name;
    EXPECT_NEAR(b.t, a.t, 1e-8 * std::max(1.0, std::abs(a.t))) << a.name;
  }
}

// The exact derivatives of the crossed criterion against central differences (Richardson, 4
// levels) at a point away from the optimum: gradient of the profiled criterion, Hessian from
// differences of the exact gradient, the REML deviance's Hessian in (theta, sigma) and the
// Jacobian of vcov(beta).
TEST(CrossedModel, ExactDerivativesAgainstDifferences) {
  const Data d = load("nested_strong");
  const CrossedModelFit f = fit("nested_strong", "crossed");
  // Rebuild the problem from the fit: participants and strategies in lme4's order (30 > 4).
  std::vector<std::vector<std::size_t>> level(2);
  std::map<std::string, std::size_t> pi, si;
  for (std::size_t i = 0; i < d.strategy.size(); ++i) {
    level[0].push_back(pi.emplace(d.trials.participant[i], pi.size()).first->second);
    level[1].push_back(si.emplace(d.strategy[i], si.size()).first->second);
  }
  Eigen::MatrixXd X(static_cast<Eigen::Index>(d.trials.y.size()), f.model.beta.size());
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    X.row(i) = f.model
                   .cell_row(d.trials.group[static_cast<std::size_t>(i)] == "random" ? 1 : 0,
                             d.trials.time[static_cast<std::size_t>(i)])
                   .transpose();
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(d.trials.y.data(), X.rows());
  const feint::models::detail::CrossedProblem pr(X, y, level, {pi.size(), si.size()});
  auto richardson = [](const std::function<double(double)>& diff, double h) {
    double a[4];
    for (int k = 0; k < 4; ++k, h /= 2) a[k] = diff(h);
    for (int m = 1; m < 4; ++m)
      for (int k = 0; k < 4 - m; ++k)
        a[k] = (a[k + 1] * std::pow(4.0, m) - a[k]) / (std::pow(4.0, m) - 1);
    return a[0];
  };
  Eigen::VectorXd th(2);
  th << 0.7, 0.3;
  const double n = pr.n(), p = pr.p();
  Eigen::VectorXd g;
  Eigen::MatrixXd H;
  ASSERT_TRUE(feint::models::detail::profiled_reml_derivatives_at(pr.derivatives(th), n, p, g, H));
  for (Eigen::Index k = 0; k < 2; ++k) {
    const double num = richardson(
        [&](double h) {
          Eigen::VectorXd a = th, b = th;
          a(k) += h;
          b(k) -= h;
          return (pr.profiled_reml(a) - pr.profiled_reml(b)) / (2 * h);
        },
        1e-3);
    EXPECT_NEAR(g(k), num, 1e-7 * std::max(1.0, std::abs(num))) << k;
    for (Eigen::Index l = 0; l < 2; ++l) {
      const double numh = richardson(
          [&](double h) {
            Eigen::VectorXd a = th, b = th, ga, gb;
            Eigen::MatrixXd Ha;
            a(l) += h;
            b(l) -= h;
            feint::models::detail::profiled_reml_derivatives_at(pr.derivatives(a), n, p, ga, Ha);
            feint::models::detail::profiled_reml_derivatives_at(pr.derivatives(b), n, p, gb, Ha);
            return (ga(k) - gb(k)) / (2 * h);
          },
          1e-3);
      EXPECT_NEAR(H(k, l), numh, 1e-7 * std::max(1.0, std::abs(numh))) << k << " " << l;
    }
  }
  // vcov(beta) = sigma^2 C: its derivative in theta_k against differences.
  const double sigma = 0.1;
  const auto J = feint::models::detail::vcov_beta_jacobian_at(pr.derivatives(th), sigma);
  ASSERT_EQ(J.size(), 3u);
  auto vcov = [&](const Eigen::VectorXd& t) {
    const auto ev = pr.evaluate(t);
    return Eigen::MatrixXd(sigma * sigma *
                           ev.xthx_chol.solve(Eigen::MatrixXd::Identity(X.cols(), X.cols())));
  };
  for (Eigen::Index k = 0; k < 2; ++k) {
    const double num = richardson(
        [&](double h) {
          Eigen::VectorXd a = th, b = th;
          a(k) += h;
          b(k) -= h;
          return (vcov(a)(1, 1) - vcov(b)(1, 1)) / (2 * h);
        },
        1e-3);
    EXPECT_NEAR(J[static_cast<std::size_t>(k)](1, 1), num, 1e-7 * std::abs(num)) << k;
  }
}

// Refusals: each with a message that names the problem.
std::string error_of(const Data& d, const CrossedModelSpec& s) {
  try {
    feint::models::fit_crossed_model(d.trials, d.strategy, s, true);
  } catch (const feint::InvalidData& e) {
    return std::string("InvalidData: ") + e.what();
  } catch (const feint::UsageError& e) {
    return std::string("UsageError: ") + e.what();
  }
  return "no error";
}

TEST(CrossedModel, RefusesDataThatCannotIdentifyTheStrategyTerm) {
  const Data d = load("balanced");
  const auto crossed = spec_of("balanced", "crossed");
  const auto nested = spec_of("balanced", "nested");
  Data one = d;
  for (auto& s : one.strategy) s = "exaggerating";
  EXPECT_NE(error_of(one, crossed).find("InvalidData: metric 'y': one strategy ('exaggerating')"),
            std::string::npos)
      << error_of(one, crossed);
  // One strategy per participant: the nested term is participant itself.
  Data per = d;
  for (std::size_t i = 0; i < per.strategy.size(); ++i) per.strategy[i] = per.trials.participant[i];
  EXPECT_NE(error_of(per, nested)
                .find("group the trials identically (every participant saw one "
                      "strategy)"),
            std::string::npos)
      << error_of(per, nested);
  Data missing = d;
  missing.strategy.clear();
  EXPECT_EQ(error_of(missing, crossed),
            "InvalidData: no strategy column: the random part (1 | participant) + (1 | strategy) "
            "needs the strategy of every trial");
  Data blank = d;
  blank.strategy[7] = " ";
  EXPECT_EQ(error_of(blank, nested),
            "InvalidData: strategy is empty for the trial of participant P01 at iteration 8: the "
            "random part (1 | participant) + (1 | participant:strategy) needs the strategy of "
            "every trial");
}

TEST(CrossedModel, RefusesUnsupportedSpecs) {
  const Data d = load("balanced");
  auto s = spec_of("balanced", "crossed");
  s.model.ddf = feint::models::DdfMethod::kenward_roger;
  EXPECT_NE(error_of(d, s).find("UsageError: Kenward-Roger"), std::string::npos);
  s = spec_of("balanced", "crossed");
  s.random_terms = {RandomIntercept::strategy};
  EXPECT_NE(error_of(d, s).find("UsageError: the model needs the random term (1 | participant)"),
            std::string::npos);
  s.random_terms = {RandomIntercept::participant, RandomIntercept::strategy,
                    RandomIntercept::strategy};
  EXPECT_NE(error_of(d, s).find("given twice"), std::string::npos);
  s = spec_of("balanced", "crossed");
  s.model.time_scale = feint::models::TimeScale::linear;
  s.model.random_slope = true;
  EXPECT_NE(error_of(d, s).find("UsageError: random slopes"), std::string::npos);
}

}  // namespace

// The tests of a fitted mixed model: contrast() (lmerTest's contest1D) and contrast_md()
// (contestMD, Satterthwaite or Kenward-Roger); see feint/models/mixed_model.hpp.
#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>

#include "feint/error.hpp"
#include "feint/models/mixed_model.hpp"
#include "mixed_model_detail.hpp"

namespace feint::models {

namespace {

double two_sided_t_p(double t, double df) {
  boost::math::students_t dist(df);
  return 2.0 * boost::math::cdf(boost::math::complement(dist, std::abs(t)));
}

}  // namespace

Contrast contrast(const MixedModelFit& fit, const Eigen::VectorXd& L, double conf_level) {
  Contrast out;
  stats::TestResult& r = out.test;
  r.test = "lmm_contrast";
  r.method = "Linear mixed model contrast (REML, Satterthwaite df)";
  r.conf_level = conf_level;
  r.mu = 0.0;
  r.statistic_name = "t";
  const double est = L.dot(fit.beta);
  double var = 0, df = 0;
  if (fit.spec.ddf == DdfMethod::kenward_roger) {
    r.method = "Linear mixed model contrast (REML, Kenward-Roger df)";
    var = L.dot(fit.vcov_beta_adj * L);
    df = kenward_roger_df(fit, L.transpose()).ddf;
  } else {
    var = L.dot(fit.vcov_beta * L);
    Eigen::VectorXd g(static_cast<Eigen::Index>(fit.jac_vcov_beta.size()));
    for (std::size_t k = 0; k < fit.jac_vcov_beta.size(); ++k)
      g(static_cast<Eigen::Index>(k)) = L.dot(fit.jac_vcov_beta[k] * L);
    df = 2.0 * var * var / g.dot(fit.vcov_varpar * g);
  }
  r.estimate = est;
  if (!(var > 0) || !std::isfinite(df) || !(df > 0)) {
    r.computed = false;
    r.note = "contrast variance or Satterthwaite df not positive";
    r.estimate.reset();
    return out;
  }
  const double se = std::sqrt(var);
  r.statistic = est / se;
  r.df = df;
  r.p_value = two_sided_t_p(est / se, df);
  const double q = detail::t_quantile_upper((1 - conf_level) / 2, df);
  r.conf_low = est - q * se;
  r.conf_high = est + q * se;
  out.std_error = se;
  return out;
}

namespace {

/// A row of the ANOVA table from its F and df (the Satterthwaite table: Mean Sq = F sigma^2).
AnovaTerm f_table_row(const MixedModelFit& fit, double F, double ndf, double ddf) {
  AnovaTerm out;
  const double s2 = fit.sigma * fit.sigma;
  if (!(std::isfinite(F) && std::isfinite(ddf) && ddf > 0)) {
    out.computed = false;
    out.note = "Satterthwaite's df not positive and finite";
    out.num_df = ndf;
    return out;
  }
  out.f = F;
  out.num_df = ndf;
  out.den_df = ddf;
  out.mean_sq = F * s2;
  out.sum_sq = F * s2 * ndf;
  boost::math::fisher_f dist(ndf, ddf);
  out.p = boost::math::cdf(boost::math::complement(dist, F));
  return out;
}

// lmerTest's contestMD with ddf = "Kenward-Roger": pbkrtest::KRmodcomp(model, L)$test; the
// table's Mean Sq is the unscaled Wald F (with Phi_A) times sigma^2, F is it times the scaling.
AnovaTerm kenward_roger_md(const MixedModelFit& fit, const Eigen::MatrixXd& L) {
  const double s2 = fit.sigma * fit.sigma;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(L);
  const double q = static_cast<double>(lu.rank());
  const Eigen::VectorXd Lb = L * fit.beta;
  const Eigen::MatrixXd LAL = L * fit.vcov_beta_adj * L.transpose();
  const double wald = Lb.dot(LAL.ldlt().solve(Lb));
  const KenwardRogerDf kr = kenward_roger_df(fit, L);
  const double fu = wald / q;
  AnovaTerm out = f_table_row(fit, fu * kr.f_scaling, q, kr.ddf);
  if (out.computed) {
    out.mean_sq = fu * s2;
    out.sum_sq = fu * s2 * q;
  }
  return out;
}

/// A one-df hypothesis: the square of the contrast's t, with its df.
AnovaTerm one_df_md(const MixedModelFit& fit, const Eigen::VectorXd& l) {
  const stats::TestResult c = contrast(fit, l).test;
  if (!c.computed) return f_table_row(fit, std::nan(""), 1, std::nan(""));
  return f_table_row(fit, *c.statistic * *c.statistic, 1, *c.df);
}

// lmerTest's get_Fstat_ddf: the denominator df of an F from the df `nu` of its q components.
double fstat_ddf(const std::vector<double>& nu, Eigen::Index q) {
  double ddf;
  bool all_equal = true;
  for (std::size_t i = 1; i < nu.size(); ++i)
    if (std::abs(nu[i] - nu[i - 1]) >= 1e-8) all_equal = false;
  if (all_equal) {
    ddf = 0;
    for (double v : nu) ddf += v;
    ddf /= static_cast<double>(nu.size());
  } else if (std::any_of(nu.begin(), nu.end(), [](double v) { return v <= 2; })) {
    ddf = 2;
  } else {
    double E = 0;
    for (double v : nu) E += v / (v - 2);
    ddf = 2 * E / (E - static_cast<double>(q));
  }
  return ddf;
}

}  // namespace

AnovaTerm contrast_md(const MixedModelFit& fit, const Eigen::MatrixXd& L) {
  if (fit.spec.ddf == DdfMethod::kenward_roger) return kenward_roger_md(fit, L);
  if (L.rows() == 1) return one_df_md(fit, L.row(0).transpose());
  const Eigen::MatrixXd VL = L * fit.vcov_beta * L.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(VL);
  // R's eigen(): decreasing eigenvalues.
  const Eigen::Index m = VL.rows();
  Eigen::VectorXd d = es.eigenvalues().reverse();
  Eigen::MatrixXd P = es.eigenvectors().rowwise().reverse();
  const double tol = std::max(std::sqrt(std::numeric_limits<double>::epsilon()) * d(0), 0.0);
  Eigen::Index q = 0;
  for (Eigen::Index i = 0; i < m; ++i)
    if (d(i) > tol) ++q;
  const Eigen::MatrixXd PtL = (P.transpose() * L).topRows(q);
  if (q == 1) return one_df_md(fit, PtL.row(0).transpose());
  double F = 0;
  std::vector<double> nu(static_cast<std::size_t>(q));
  for (Eigen::Index i = 0; i < q; ++i) {
    const Eigen::VectorXd l = PtL.row(i).transpose();
    const double lb = l.dot(fit.beta);
    F += lb * lb / d(i);
    Eigen::VectorXd g(static_cast<Eigen::Index>(fit.jac_vcov_beta.size()));
    for (std::size_t k = 0; k < fit.jac_vcov_beta.size(); ++k)
      g(static_cast<Eigen::Index>(k)) = l.dot(fit.jac_vcov_beta[k] * l);
    nu[static_cast<std::size_t>(i)] = 2 * d(i) * d(i) / g.dot(fit.vcov_varpar * g);
  }
  F /= static_cast<double>(q);
  return f_table_row(fit, F, static_cast<double>(q), fstat_ddf(nu, q));
}

}  // namespace feint::models

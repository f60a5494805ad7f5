// src/models/mixed_model_detail.hpp - internals of the mixed model shared by its .cpp files.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <optional>
#include <vector>

namespace feint::models::detail {

/// The criterion at one theta: H = I + Z Lambda Lambda' Z' (the marginal covariance / sigma^2).
struct Evaluation {
  bool ok = true;
  double logdet_m = 0;  ///< log |I + Lambda' Z' Z Lambda| summed over participants
  double logdet_x = 0;  ///< log |X' H^-1 X|
  double r2 = 0;        ///< (y - X beta)' H^-1 (y - X beta) at the GLS beta
  Eigen::MatrixXd XtHX;
  Eigen::LLT<Eigen::MatrixXd> xthx_chol;
  Eigen::VectorXd beta;
};

/// The fixed-effect step of an evaluation, shared by Problem and CrossedProblem: with ev.XtHX =
/// X'H^-1X formed, factors it (ev.xthx_chol), sets ev.logdet_x = log|X'H^-1X| and the GLS
/// ev.beta = (X'H^-1X)^-1 X'H^-1y, and returns the residuals y - X beta (the caller takes
/// e'H^-1e from them). Where the factorisation fails: ev.ok = false and no residuals.
std::optional<Eigen::VectorXd> fixed_effect_step(Evaluation& ev, const Eigen::VectorXd& XtHy,
                                                 const Eigen::MatrixXd& X,
                                                 const Eigen::VectorXd& y);

/// Exact derivatives at one theta (mixed_model_derivatives.cpp), with P = H^-1 - H^-1 X C X' H^-1.
struct ThetaDerivatives {
  Evaluation ev;
  Eigen::MatrixXd C;                ///< (X' H^-1 X)^-1
  Eigen::VectorXd tr_pg;            ///< tr(P G_k) = d (log|H| + log|X'H^-1X|) / d theta_k
  Eigen::MatrixXd logdet_hessian;   ///< tr(P G_kl) - tr(P G_k P G_l), its second derivatives
  Eigen::VectorXd r2_gradient;      ///< d r2 / d theta_k = -y'P G_k P y
  Eigen::MatrixXd r2_hessian;       ///< d2 r2 / d theta_k d theta_l
  std::vector<Eigen::MatrixXd> B;   ///< X'H^-1 G_k H^-1 X = -d (X'H^-1X) / d theta_k
};

/// Data of a fit, rows sorted by participant (participant i owns rows start[i] .. start[i+1]-1).
struct Problem {
  Eigen::MatrixXd X, Z;
  Eigen::VectorXd y;
  std::vector<std::size_t> start;
  std::vector<Eigen::MatrixXd> ZtZ, ZtX;
  std::vector<Eigen::VectorXd> Zty;
  Eigen::MatrixXd XtX;
  Eigen::VectorXd Xty;

  Problem(Eigen::MatrixXd X, Eigen::MatrixXd Z, Eigen::VectorXd y, std::vector<std::size_t> start);
  Eigen::MatrixXd lambda(const Eigen::VectorXd& theta) const;
  Evaluation evaluate(const Eigen::VectorXd& theta) const;
  /// lme4's REML criterion with sigma and beta profiled out:
  /// log|M| + log|X'H^-1X| + (n-p)(1 + log(2 pi r2 / (n-p))).
  double profiled_reml(const Eigen::VectorXd& theta) const;
  /// lmerTest's devfun_vp: the REML deviance at varpar = (theta, sigma).
  double reml_deviance(const Eigen::VectorXd& varpar) const;
  /// sigma^2 (X' H^-1 X)^-1 at varpar = (theta, sigma).
  Eigen::MatrixXd vcov_beta(const Eigen::VectorXd& varpar) const;
  ThetaDerivatives derivatives(const Eigen::VectorXd& theta) const;
  /// Gradient and Hessian of profiled_reml at theta; false where the criterion is not finite.
  bool profiled_reml_derivatives(const Eigen::VectorXd& theta, Eigen::VectorXd& gradient,
                                 Eigen::MatrixXd& hessian) const;
  /// Hessian of reml_deviance at varpar = (theta, sigma).
  Eigen::MatrixXd reml_deviance_hessian(const Eigen::VectorXd& varpar) const;
  /// d vcov_beta / d varpar_k, k over (theta, sigma).
  std::vector<Eigen::MatrixXd> vcov_beta_jacobian(const Eigen::VectorXd& varpar) const;
};

Eigen::VectorXd optimise_theta(const Problem& problem);

// The criteria and their derivatives from an evaluation, shared by Problem (random effects
// grouped by participant) and CrossedProblem (crossed or nested random intercepts); n
// observations, p fixed effects.

/// lme4's profiled REML criterion: log|M| + log|X'H^-1X| + (n-p)(1 + log(2 pi r2 / (n-p)));
/// infinite where the evaluation failed.
double profiled_reml_at(const Evaluation& ev, double n, double p);
/// lmerTest's devfun_vp (the REML deviance) at sigma.
double reml_deviance_at(const Evaluation& ev, double sigma, double n, double p);
/// Gradient and Hessian in theta of profiled_reml_at; false where the criterion is not finite.
bool profiled_reml_derivatives_at(const ThetaDerivatives& d, double n, double p,
                                  Eigen::VectorXd& gradient, Eigen::MatrixXd& hessian);
/// Hessian of reml_deviance_at in varpar = (theta, sigma).
Eigen::MatrixXd reml_deviance_hessian_at(const ThetaDerivatives& d, double sigma, double n,
                                         double p);
/// d (sigma^2 C) / d varpar_k, k over (theta, sigma).
std::vector<Eigen::MatrixXd> vcov_beta_jacobian_at(const ThetaDerivatives& d, double sigma);

/// lmerTest's Satterthwaite machinery (as_lmerModLT), made scale-free: the Hessian of the REML
/// deviance and the Jacobian of vcov(beta), taken at (theta, sigma_s) in the units of
/// y / 2^scale_exp, are carried to (theta, u = sigma / sigma_s) at u = 1, where the
/// positive-eigenvalue cut (1e-8) of A = 2 H^-1 is made, then to (theta, sigma) in the units of y
/// (sigma_y = sigma_s 2^scale_exp).
struct SatterthwaiteParts {
  Eigen::MatrixXd vcov_varpar;                 ///< A
  std::vector<Eigen::MatrixXd> jac_vcov_beta;  ///< d vcov(beta) / d varpar_k
};
SatterthwaiteParts satterthwaite_parts(const Eigen::MatrixXd& deviance_hessian,
                                       std::vector<Eigen::MatrixXd> jacobian, double sigma_s,
                                       double sigma_y, int scale_exp);

/// Random intercepts of several grouping factors, crossed or nested (lme4's Lambda diagonal with
/// one theta per term; crossed_model_reml.cpp). Z's columns are the indicators of the levels, term
/// by term (term k owns columns offset[k] .. offset[k+1]-1). Z'Z is not block diagonal, so the
/// penalised least squares are one dense q x q system (q = the levels of all terms).
struct CrossedProblem {
  Eigen::MatrixXd X;
  Eigen::VectorXd y;
  std::vector<Eigen::Index> offset;
  Eigen::MatrixXd ZtZ, ZtX, XtX;
  Eigen::VectorXd Zty, Xty;

  /// level[k][i]: the level (0 .. n_levels[k]-1) of observation i in term k.
  CrossedProblem(Eigen::MatrixXd X, Eigen::VectorXd y,
                 const std::vector<std::vector<std::size_t>>& level,
                 const std::vector<std::size_t>& n_levels);
  Eigen::Index n_terms() const { return static_cast<Eigen::Index>(offset.size()) - 1; }
  double n() const { return static_cast<double>(y.size()); }
  double p() const { return static_cast<double>(X.cols()); }
  /// The diagonal of Lambda: theta_k on the columns of term k.
  Eigen::VectorXd lambda(const Eigen::VectorXd& theta) const;
  Evaluation evaluate(const Eigen::VectorXd& theta) const;
  double profiled_reml(const Eigen::VectorXd& theta) const;
  ThetaDerivatives derivatives(const Eigen::VectorXd& theta) const;
};

/// The REML optimum over theta >= 0 (crossed_model_reml.cpp).
Eigen::VectorXd optimise_crossed_theta(const CrossedProblem& problem);

/// Kenward-Roger's pieces (pbkrtest's vcovAdj_internal): the marginal covariance is
/// S = sum_r gamma_r G_r with gamma = (the entries of D's lower triangle, sigma^2) and G_r the
/// matching Z E_r Z' (E_r symmetric unit) or I; all products are formed per participant (S is
/// block diagonal), never as n x n matrices.
struct KenwardRogerParts {
  Eigen::MatrixXd phi_adj;            ///< Phi_A = Phi + 2 Phi U Phi
  std::vector<Eigen::MatrixXd> P;     ///< P_r = -X' S^-1 G_r S^-1 X
  Eigen::MatrixXd W;                  ///< 2 IE2^-1 (generalised inverse when IE2 is singular)
};
KenwardRogerParts kenward_roger_parts(const Problem& problem, const Eigen::MatrixXd& D,
                                      double sigma2, const Eigen::MatrixXd& Phi);

/// The exponent k of the power of two 2^k nearest the spread (largest |y - mean|) of y; the fit
/// works on y / 2^k so that it is scale-free and multiplying back is exact.
int response_scale_exponent(const Eigen::VectorXd& y);

/// qt(1 - upper, df), upper in (0, 1): Student's t upper quantile, the normal one when df is so
/// large that Boost's quantile would overflow (df > 1e10, where they agree to 1e-10).
double t_quantile_upper(double upper, double df);

/// 2 P(T_df > |t|) (the normal tail when df > 1e10).
double t_two_sided_p(double t, double df);

}  // namespace feint::models::detail

// Exact first and second derivatives of the REML criteria with respect to theta (and sigma), and
// of vcov(beta), for the optimiser's Newton steps and for Satterthwaite's df. Matrix calculus of
// H(theta) = I + Z Lambda Lambda' Z' (the marginal covariance / sigma^2), with
// P = H^-1 - H^-1 X (X'H^-1X)^-1 X' H^-1 (so that P y = H^-1 (y - X beta) and r2 = y'P y):
//   d/dtheta_k (log|H| + log|X'H^-1X|) = tr(P G_k),         G_k  = dH/dtheta_k
//   d2/dtheta_k dtheta_l (same)        = tr(P G_kl) - tr(P G_k P G_l),   G_kl = d2H/dtheta_k dtheta_l
//   d r2 / dtheta_k                    = -y'P G_k P y
//   d2 r2 / dtheta_k dtheta_l          = 2 y'P G_k P G_l P y - y'P G_kl P y
//   d (X'H^-1X)^-1 / dtheta_k          = C X'H^-1 G_k H^-1 X C,   C = (X'H^-1X)^-1
// (Searle, Casella & McCulloch 1992, ch. 6; Kuznetsova et al. 2017 take the same quantities by
// numerical differentiation). With E_k = dLambda/dtheta_k (a unit matrix), G_k = Z D_k Z' where
// D_k = E_k Lambda' + Lambda E_k' and G_kl = Z (E_k E_l' + E_l E_k') Z', so every trace is a sum
// over participants of q x q products of S_i = Z_i'H_i^-1 Z_i, R_i = Z_i'H_i^-1 X_i and
// v_i = Z_i'H_i^-1 e_i (Woodbury, as Problem::evaluate): no n x n matrix, no n_i x n_i matrix.
// Exact derivatives make the fit a smooth function of the data to rounding, so the fit of y and
// of c y agree to ~1e-12 (docs/mixed-model.md, "Scale invariance").
#include <Eigen/Dense>
#include <cmath>
#include <cstddef>
#include <vector>

#include "mixed_model_detail.hpp"

namespace feint::models::detail {

ThetaDerivatives Problem::derivatives(const Eigen::VectorXd& theta) const {
  ThetaDerivatives d;
  d.ev = evaluate(theta);
  if (!d.ev.ok) return d;
  const Eigen::Index q = Z.cols(), p = X.cols(), nt = theta.size();
  const Eigen::MatrixXd L = lambda(theta);
  std::vector<Eigen::MatrixXd> E, Dk;
  for (Eigen::Index j = 0; j < q; ++j)
    for (Eigen::Index i = j; i < q; ++i) {
      Eigen::MatrixXd e = Eigen::MatrixXd::Zero(q, q);
      e(i, j) = 1;
      E.push_back(e);
    }
  for (Eigen::Index k = 0; k < nt; ++k)
    Dk.push_back(E[static_cast<std::size_t>(k)] * L.transpose() +
                 L * E[static_cast<std::size_t>(k)].transpose());
  auto Dkl = [&](Eigen::Index k, Eigen::Index l) {
    const auto& a = E[static_cast<std::size_t>(k)];
    const auto& b = E[static_cast<std::size_t>(l)];
    return Eigen::MatrixXd(a * b.transpose() + b * a.transpose());
  };
  d.C = d.ev.xthx_chol.solve(Eigen::MatrixXd::Identity(p, p));
  d.B.assign(static_cast<std::size_t>(nt), Eigen::MatrixXd::Zero(p, p));
  std::vector<Eigen::VectorXd> b(static_cast<std::size_t>(nt), Eigen::VectorXd::Zero(p));
  d.tr_pg = Eigen::VectorXd::Zero(nt);
  d.r2_gradient = Eigen::VectorXd::Zero(nt);
  Eigen::MatrixXd tr_pgpg = Eigen::MatrixXd::Zero(nt, nt), tr_pgkl = tr_pgpg, y_gkl = tr_pgpg,
                  y_gpg = tr_pgpg;
  std::vector<Eigen::MatrixXd> SD(static_cast<std::size_t>(nt)), DT(SD);
  for (std::size_t i = 0; i < ZtZ.size(); ++i) {
    const Eigen::MatrixXd M = Eigen::MatrixXd::Identity(q, q) + L.transpose() * ZtZ[i] * L;
    const Eigen::MatrixXd K = L * M.llt().solve(L.transpose());  // H^-1 = I - Z K Z'
    const Eigen::MatrixXd ZtZK = ZtZ[i] * K;
    const Eigen::MatrixXd S = ZtZ[i] - ZtZK * ZtZ[i];
    const Eigen::MatrixXd R = ZtX[i] - ZtZK * ZtX[i];
    const Eigen::VectorXd Zte = Zty[i] - ZtX[i] * d.ev.beta;
    const Eigen::VectorXd v = Zte - ZtZK * Zte;
    const Eigen::MatrixXd T = R * d.C * R.transpose();
    for (Eigen::Index k = 0; k < nt; ++k) {
      const auto ks = static_cast<std::size_t>(k);
      SD[ks] = S * Dk[ks];
      DT[ks] = Dk[ks] * T;
      d.tr_pg(k) += SD[ks].trace() - DT[ks].trace();
      d.r2_gradient(k) -= v.dot(Dk[ks] * v);
      d.B[ks] += R.transpose() * Dk[ks] * R;
      b[ks] += R.transpose() * (Dk[ks] * v);
    }
    for (Eigen::Index k = 0; k < nt; ++k)
      for (Eigen::Index l = 0; l < nt; ++l) {
        const auto ks = static_cast<std::size_t>(k), ls = static_cast<std::size_t>(l);
        const Eigen::MatrixXd G2 = Dkl(k, l);
        // tr(H^-1 G_k H^-1 G_l) - 2 tr(C X'H^-1 G_k H^-1 G_l H^-1 X)
        tr_pgpg(k, l) += (SD[ks] * SD[ls]).trace() - 2 * (Dk[ks] * SD[ls] * T).trace();
        tr_pgkl(k, l) += (S * G2).trace() - (G2 * T).trace();
        y_gkl(k, l) += v.dot(G2 * v);
        y_gpg(k, l) += v.dot(Dk[ks] * (SD[ls] * v));
      }
  }
  d.logdet_hessian = Eigen::MatrixXd(nt, nt);
  d.r2_hessian = Eigen::MatrixXd(nt, nt);
  for (Eigen::Index k = 0; k < nt; ++k)
    for (Eigen::Index l = 0; l < nt; ++l) {
      const auto ks = static_cast<std::size_t>(k), ls = static_cast<std::size_t>(l);
      const double pgpg = tr_pgpg(k, l) + (d.C * d.B[ks] * d.C * d.B[ls]).trace();
      d.logdet_hessian(k, l) = tr_pgkl(k, l) - pgpg;
      d.r2_hessian(k, l) = 2 * (y_gpg(k, l) - b[ks].dot(d.C * b[ls])) - y_gkl(k, l);
    }
  // Symmetric by construction up to rounding; make it exact.
  d.logdet_hessian = (0.5 * (d.logdet_hessian + d.logdet_hessian.transpose())).eval();
  d.r2_hessian = (0.5 * (d.r2_hessian + d.r2_hessian.transpose())).eval();
  return d;
}

bool profiled_reml_derivatives_at(const ThetaDerivatives& d, double n, double p,
                                  Eigen::VectorXd& gradient, Eigen::MatrixXd& hessian) {
  if (!d.ev.ok || !(d.ev.r2 > 0)) return false;
  const double np = n - p;
  const double r2 = d.ev.r2;
  gradient = d.tr_pg + np * d.r2_gradient / r2;
  hessian = d.logdet_hessian +
            np * (d.r2_hessian / r2 - d.r2_gradient * d.r2_gradient.transpose() / (r2 * r2));
  return true;
}

Eigen::MatrixXd reml_deviance_hessian_at(const ThetaDerivatives& d, double sigma, double n,
                                         double p) {
  const Eigen::Index nt = d.tr_pg.size();
  const double s = sigma, s2 = s * s;
  const double np = n - p;
  Eigen::MatrixXd H(nt + 1, nt + 1);
  H.topLeftCorner(nt, nt) = d.logdet_hessian + d.r2_hessian / s2;
  H.col(nt).head(nt) = -2 * d.r2_gradient / (s2 * s);
  H.row(nt).head(nt) = H.col(nt).head(nt).transpose();
  H(nt, nt) = 6 * d.ev.r2 / (s2 * s2) - 2 * np / s2;
  return H;
}

std::vector<Eigen::MatrixXd> vcov_beta_jacobian_at(const ThetaDerivatives& d, double sigma) {
  const double s = sigma;
  std::vector<Eigen::MatrixXd> J;
  for (const auto& Bk : d.B) J.push_back(s * s * d.C * Bk * d.C);
  J.push_back(2 * s * d.C);
  return J;
}

SatterthwaiteParts satterthwaite_parts(const Eigen::MatrixXd& deviance_hessian,
                                       std::vector<Eigen::MatrixXd> jacobian, double sigma_s,
                                       double sigma_y, int scale_exp) {
  const Eigen::Index nv = deviance_hessian.rows();
  Eigen::VectorXd du = Eigen::VectorXd::Ones(nv);  // d varpar / d (theta, u)
  du(nv - 1) = sigma_s;
  const Eigen::MatrixXd H = du.asDiagonal() * deviance_hessian * du.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(H);
  Eigen::MatrixXd A_u = Eigen::MatrixXd::Zero(nv, nv);
  for (Eigen::Index i = 0; i < nv; ++i) {
    const double ev_i = es.eigenvalues()(i);
    if (ev_i > 1e-8) A_u += es.eigenvectors().col(i) * es.eigenvectors().col(i).transpose() / ev_i;
  }
  A_u *= 2.0;
  for (Eigen::Index k = 0; k < nv; ++k) jacobian[static_cast<std::size_t>(k)] *= du(k);
  // Back to the units of y: d sigma = sigma_y d u; vcov(beta) scales by 2^(2k).
  Eigen::VectorXd D = Eigen::VectorXd::Ones(nv);
  D(nv - 1) = sigma_y;
  SatterthwaiteParts out;
  out.vcov_varpar = D.asDiagonal() * A_u * D.asDiagonal();
  for (Eigen::Index k = 0; k < nv; ++k)
    out.jac_vcov_beta.push_back(jacobian[static_cast<std::size_t>(k)].unaryExpr([&](double v) {
      return std::ldexp(v, 2 * scale_exp);
    }) / D(k));
  return out;
}

bool Problem::profiled_reml_derivatives(const Eigen::VectorXd& theta, Eigen::VectorXd& gradient,
                                        Eigen::MatrixXd& hessian) const {
  return profiled_reml_derivatives_at(derivatives(theta), static_cast<double>(y.size()),
                                      static_cast<double>(X.cols()), gradient, hessian);
}

Eigen::MatrixXd Problem::reml_deviance_hessian(const Eigen::VectorXd& varpar) const {
  const Eigen::Index nt = varpar.size() - 1;
  return reml_deviance_hessian_at(derivatives(varpar.head(nt)), varpar(nt),
                                  static_cast<double>(y.size()), static_cast<double>(X.cols()));
}

std::vector<Eigen::MatrixXd> Problem::vcov_beta_jacobian(const Eigen::VectorXd& varpar) const {
  const Eigen::Index nt = varpar.size() - 1;
  return vcov_beta_jacobian_at(derivatives(varpar.head(nt)), varpar(nt));
}

}  // namespace feint::models::detail

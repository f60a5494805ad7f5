// Kenward & Roger (1997) for the linear mixed model, following pbkrtest 0.5.2 (Halekoh &
// Højsgaard 2014, "A Kenward-Roger approximation and parametric bootstrap methods for tests in
// linear mixed models - the R package pbkrtest", J. Stat. Softw. 59(9)): vcovAdj_internal for
// the adjusted covariance Phi_A, and .KR_adjust / Lb_ddf for the denominator df and F scaling.
// Written from the published algorithm; the covariance S is block diagonal by participant, so
// every trace and product below is a sum over participants.
#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "feint/models/mixed_model.hpp"
#include "mixed_model_detail.hpp"

namespace feint::models {

namespace detail {

namespace {

using Index = Eigen::Index;

// The unit matrices E_r of the random-effect covariance (lower triangle, column-wise); the
// residual's (the identity) is implied after them.
std::vector<Eigen::MatrixXd> unit_matrices(Index q) {
  std::vector<Eigen::MatrixXd> E;
  for (Index j = 0; j < q; ++j)
    for (Index i = j; i < q; ++i) {
      Eigen::MatrixXd e = Eigen::MatrixXd::Zero(q, q);
      e(i, j) = e(j, i) = 1;
      E.push_back(e);
    }
  return E;
}

/// pbkrtest's P_r, Q_rs (r <= s, at r * ng + s) and tr(H_r H_s) (upper triangle of K), summed over
/// participants.
struct KrSums {
  std::vector<Eigen::MatrixXd> P, Q;
  Eigen::MatrixXd K;
};

// S is block diagonal by participant, so every product is a sum of per-participant blocks.
KrSums participant_sums(const Problem& problem, const Eigen::MatrixXd& D, double sigma2,
                        const std::vector<Eigen::MatrixXd>& E) {
  const Index p = problem.X.cols();
  const std::size_t ng = E.size() + 1;  // + residual
  const std::size_t m = problem.start.size() - 1;
  KrSums sums{std::vector<Eigen::MatrixXd>(ng, Eigen::MatrixXd::Zero(p, p)),
              std::vector<Eigen::MatrixXd>(ng * ng, Eigen::MatrixXd::Zero(p, p)),
              Eigen::MatrixXd::Zero(static_cast<Index>(ng), static_cast<Index>(ng))};
  for (std::size_t i = 0; i < m; ++i) {
    const auto r0 = static_cast<Index>(problem.start[i]);
    const auto ni = static_cast<Index>(problem.start[i + 1] - problem.start[i]);
    const Eigen::MatrixXd Zi = problem.Z.middleRows(r0, ni);
    const Eigen::MatrixXd Xi = problem.X.middleRows(r0, ni);
    const Eigen::MatrixXd S =
        Zi * D * Zi.transpose() + sigma2 * Eigen::MatrixXd::Identity(ni, ni);
    const Eigen::MatrixXd Si = S.llt().solve(Eigen::MatrixXd::Identity(ni, ni));
    const Eigen::MatrixXd T = Si * Xi;  // TT
    std::vector<Eigen::MatrixXd> H(ng), O(ng);  // HH = G S^-1, OO = HH X
    for (std::size_t r = 0; r < ng; ++r) {
      const Eigen::MatrixXd G = r + 1 < ng ? Eigen::MatrixXd(Zi * E[r] * Zi.transpose())
                                           : Eigen::MatrixXd::Identity(ni, ni);
      H[r] = G * Si;
      O[r] = H[r] * Xi;
    }
    for (std::size_t r = 0; r < ng; ++r) {
      sums.P[r] -= O[r].transpose() * T;
      const Eigen::MatrixXd OrSi = O[r].transpose() * Si;
      for (std::size_t s = r; s < ng; ++s) {
        sums.Q[r * ng + s] += OrSi * O[s];
        sums.K(static_cast<Index>(r), static_cast<Index>(s)) += (H[r] * H[s]).trace();
      }
    }
  }
  return sums;
}

// IE2 (twice the REML information of the variance parameters).
Eigen::MatrixXd doubled_information(const KrSums& sums, const Eigen::MatrixXd& Phi) {
  const std::size_t ng = sums.P.size();
  const auto n = static_cast<Index>(ng);
  Eigen::MatrixXd IE2(n, n);
  for (std::size_t r = 0; r < ng; ++r) {
    const Eigen::MatrixXd PhiPr = Phi * sums.P[r];
    for (std::size_t s = r; s < ng; ++s) {
      const double v = sums.K(static_cast<Index>(r), static_cast<Index>(s)) -
                       2 * Phi.cwiseProduct(sums.Q[r * ng + s]).sum() +
                       PhiPr.cwiseProduct(sums.P[s] * Phi).sum();  // tr(Phi P_r Phi P_s)
      IE2(static_cast<Index>(r), static_cast<Index>(s)) = v;
      IE2(static_cast<Index>(s), static_cast<Index>(r)) = v;
    }
  }
  return IE2;
}

// W = 2 IE2^-1; pbkrtest takes the Moore-Penrose inverse when min |eigenvalue| <= 1e-10.
Eigen::MatrixXd twice_inverse(const Eigen::MatrixXd& IE2) {
  const Index n = IE2.rows();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(IE2);
  const double condi = es.eigenvalues().cwiseAbs().minCoeff();
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(n, n);
  const double cut = condi > 1e-10 ? 0.0
                                   : std::max(static_cast<double>(n), 1.0) *
                                         es.eigenvalues().cwiseAbs().maxCoeff() * 2.220446e-16;
  for (Index k = 0; k < n; ++k) {
    const double ev = es.eigenvalues()(k);
    if (condi > 1e-10 || std::abs(ev) > cut)
      W += es.eigenvectors().col(k) * es.eigenvectors().col(k).transpose() / ev;
  }
  W *= 2.0;
  return W;
}

// U = sum_rs W_rs (Q_rs - P_r Phi P_s), symmetric in (r, s).
Eigen::MatrixXd adjustment_sum(const KrSums& sums, const Eigen::MatrixXd& W,
                               const Eigen::MatrixXd& Phi) {
  const std::size_t ng = sums.P.size();
  const Index p = Phi.rows();
  Eigen::MatrixXd U = Eigen::MatrixXd::Zero(p, p);
  for (std::size_t r = 0; r < ng; ++r)
    for (std::size_t s = 0; s < ng; ++s) {
      const Eigen::MatrixXd& Qrs = r <= s ? sums.Q[r * ng + s] : sums.Q[s * ng + r];
      const Eigen::MatrixXd Qx = r <= s ? Qrs : Eigen::MatrixXd(Qrs.transpose());
      U += W(static_cast<Index>(r), static_cast<Index>(s)) * (Qx - sums.P[r] * Phi * sums.P[s]);
    }
  return U;
}

}  // namespace

KenwardRogerParts kenward_roger_parts(const Problem& problem, const Eigen::MatrixXd& D,
                                      double sigma2, const Eigen::MatrixXd& Phi) {
  KrSums sums = participant_sums(problem, D, sigma2, unit_matrices(problem.Z.cols()));
  for (auto& Pr : sums.P) Pr = (0.5 * (Pr + Pr.transpose())).eval();  // forceSymmetric
  const Eigen::MatrixXd W = twice_inverse(doubled_information(sums, Phi));
  const Eigen::MatrixXd U = adjustment_sum(sums, W, Phi);
  KenwardRogerParts out;
  out.phi_adj = Phi + 2 * Phi * U * Phi;
  out.P = std::move(sums.P);
  out.W = W;
  return out;
}

}  // namespace detail

KenwardRogerDf kenward_roger_df(const MixedModelFit& fit, const Eigen::MatrixXd& L) {
  const Eigen::MatrixXd& Phi = fit.vcov_beta;
  const Eigen::MatrixXd LPL = L * Phi * L.transpose();
  const Eigen::MatrixXd Theta = L.transpose() * LPL.ldlt().solve(L);
  const Eigen::MatrixXd ThetaPhi = Theta * Phi;
  const std::size_t ng = fit.kr_P.size();
  double A1 = 0, A2 = 0;
  for (std::size_t i = 0; i < ng; ++i) {
    const Eigen::MatrixXd ui = ThetaPhi * fit.kr_P[i] * Phi;
    for (std::size_t j = i; j < ng; ++j) {
      const double e = i == j ? 1 : 2;
      const Eigen::MatrixXd uj = ThetaPhi * fit.kr_P[j] * Phi;
      const double w = fit.kr_W(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
      A1 += e * w * ui.trace() * uj.trace();
      A2 += e * w * ui.cwiseProduct(uj.transpose()).sum();
    }
  }
  // q = rank of L (pbkrtest: rankMatrix(L); lmerTest's hypotheses have full row rank).
  Eigen::FullPivLU<Eigen::MatrixXd> lu(L);
  const double q = static_cast<double>(lu.rank());
  const double B = (A1 + 6 * A2) / (2 * q);
  const double g = ((q + 1) * A1 - (q + 4) * A2) / ((q + 2) * A2);
  const double den = 3 * q + 2 * (1 - g);
  const double c1 = g / den, c2 = (q - g) / den, c3 = (q + 2 - g) / den;
  double V0 = 1 + c1 * B;
  const double V1 = 1 - c2 * B, V2 = 1 - c3 * B;
  if (std::abs(V0) < 1e-10) V0 = 0;
  const double x = 1 - A2 / q;
  const double ratio = (std::abs(x) < 1e-14 && std::abs(V1) < 1e-14) ? 1.0 : x / V1;  // .divZero
  const double rho = ratio * ratio * V0 / V2 / q;
  KenwardRogerDf out;
  out.ddf = 4 + (q + 2) / (q * rho - 1);
  out.f_scaling = std::abs(out.ddf - 2) < 1e-2 ? 1.0 : out.ddf * (1 - A2 / q) / (out.ddf - 2);
  return out;
}

}  // namespace feint::models

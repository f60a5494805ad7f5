// The REML criterion of crossed or nested random intercepts (lme4's penalised least squares with
// a diagonal Lambda, one theta per term), its exact derivatives, and its optimum over theta >= 0.
// See feint/models/crossed_model.hpp and docs/crossed-random-effects.md.
//
// With psi_k = theta_k^2 the marginal covariance / sigma^2 is linear in psi:
// H = I + sum_k psi_k Z_k Z_k', so G_k = dH/dpsi_k = Z_k Z_k' and d2H/dpsi^2 = 0. With
// P = H^-1 - H^-1 X C X' H^-1 (C = (X'H^-1X)^-1), S = Z'P Z and v = Z'P y = Z'H^-1 (y - X beta),
// every trace of mixed_model_derivatives.cpp is a block of S or v (no n x n matrix):
//   tr(P G_k) = tr S_kk,   tr(P G_k P G_l) = ||S_kl||^2,   y'P G_k P y = ||v_k||^2,
//   y'P G_k P G_l P y = v_k' S_kl v_l,   X'H^-1 G_k H^-1 X = R_k'R_k (R = Z'H^-1X);
// the derivatives in theta follow by the chain rule (d/dtheta_k = 2 theta_k d/dpsi_k).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "mixed_model_detail.hpp"

namespace feint::models::detail {

CrossedProblem::CrossedProblem(Eigen::MatrixXd X_, Eigen::VectorXd y_,
                               const std::vector<std::vector<std::size_t>>& level,
                               const std::vector<std::size_t>& n_levels)
    : X(std::move(X_)), y(std::move(y_)) {
  offset = {0};
  for (const std::size_t m : n_levels)
    offset.push_back(offset.back() + static_cast<Eigen::Index>(m));
  const Eigen::Index q = offset.back(), p = X.cols();
  ZtZ = Eigen::MatrixXd::Zero(q, q);
  ZtX = Eigen::MatrixXd::Zero(q, p);
  Zty = Eigen::VectorXd::Zero(q);
  std::vector<Eigen::Index> col(level.size());
  for (Eigen::Index i = 0; i < y.size(); ++i) {
    // The columns of Z that are 1 in row i: one per term.
    for (std::size_t k = 0; k < level.size(); ++k)
      col[k] = offset[k] + static_cast<Eigen::Index>(level[k][static_cast<std::size_t>(i)]);
    for (const Eigen::Index a : col) {
      for (const Eigen::Index b : col) ZtZ(a, b) += 1.0;
      ZtX.row(a) += X.row(i);
      Zty(a) += y(i);
    }
  }
  XtX = X.transpose() * X;
  Xty = X.transpose() * y;
}

Eigen::VectorXd CrossedProblem::lambda(const Eigen::VectorXd& theta) const {
  Eigen::VectorXd lam(offset.back());
  for (Eigen::Index k = 0; k < n_terms(); ++k)
    lam.segment(offset[static_cast<std::size_t>(k)],
                offset[static_cast<std::size_t>(k) + 1] - offset[static_cast<std::size_t>(k)])
        .setConstant(theta(k));
  return lam;
}

namespace {

/// Cholesky factor of M = I + Lambda' Z'Z Lambda (lme4's L_theta L_theta').
Eigen::LLT<Eigen::MatrixXd> factor_m(const Eigen::MatrixXd& ZtZ, const Eigen::VectorXd& lam) {
  Eigen::MatrixXd M = lam.asDiagonal() * ZtZ * lam.asDiagonal();
  M.diagonal().array() += 1.0;
  return Eigen::LLT<Eigen::MatrixXd>(M);
}

}  // namespace

Evaluation CrossedProblem::evaluate(const Eigen::VectorXd& theta) const {
  const Eigen::VectorXd lam = lambda(theta);
  const Eigen::LLT<Eigen::MatrixXd> chol = factor_m(ZtZ, lam);
  Evaluation ev;
  const Eigen::MatrixXd Lc = chol.matrixL();
  ev.logdet_m = 2.0 * Lc.diagonal().array().log().sum();
  // Woodbury: H^-1 = I - Z Lambda M^-1 Lambda' Z'.
  const Eigen::MatrixXd W = lam.asDiagonal() * ZtX;
  const Eigen::VectorXd w = lam.asDiagonal() * Zty;
  const Eigen::MatrixXd MW = chol.solve(W);
  ev.XtHX = XtX - W.transpose() * MW;
  const Eigen::VectorXd XtHy = Xty - MW.transpose() * w;
  const std::optional<Eigen::VectorXd> e = fixed_effect_step(ev, XtHy, X, y);
  if (!e) return ev;
  // e' H^-1 e from the residuals themselves (no cancellation against y'y).
  const Eigen::VectorXd u = lam.asDiagonal() * (Zty - ZtX * ev.beta);
  ev.r2 = e->squaredNorm() - u.dot(chol.solve(u));
  return ev;
}

double CrossedProblem::profiled_reml(const Eigen::VectorXd& theta) const {
  return profiled_reml_at(evaluate(theta), n(), p());
}

ThetaDerivatives CrossedProblem::derivatives(const Eigen::VectorXd& theta) const {
  ThetaDerivatives d;
  d.ev = evaluate(theta);
  if (!d.ev.ok) return d;
  const Eigen::Index p_ = X.cols(), nt = n_terms();
  const Eigen::VectorXd lam = lambda(theta);
  const Eigen::LLT<Eigen::MatrixXd> chol = factor_m(ZtZ, lam);
  const Eigen::MatrixXd Lm = lam.asDiagonal();
  const Eigen::MatrixXd K = lam.asDiagonal() * chol.solve(Lm);  // H^-1 = I - Z K Z'
  const Eigen::MatrixXd A = ZtZ * K;
  d.C = d.ev.xthx_chol.solve(Eigen::MatrixXd::Identity(p_, p_));
  const Eigen::MatrixXd R = ZtX - A * ZtX;  // Z'H^-1X
  const Eigen::VectorXd Zte = Zty - ZtX * d.ev.beta;
  const Eigen::VectorXd v = Zte - A * Zte;                            // Z'H^-1 e = Z'P y
  const Eigen::MatrixXd S = ZtZ - A * ZtZ - R * d.C * R.transpose();  // Z'P Z
  auto first = [&](Eigen::Index k) { return offset[static_cast<std::size_t>(k)]; };
  auto size = [&](Eigen::Index k) {
    return offset[static_cast<std::size_t>(k) + 1] - offset[static_cast<std::size_t>(k)];
  };
  d.tr_pg.resize(nt);
  d.r2_gradient.resize(nt);
  d.logdet_hessian.resize(nt, nt);
  d.r2_hessian.resize(nt, nt);
  d.B.clear();
  for (Eigen::Index k = 0; k < nt; ++k) {
    const auto Rk = R.middleRows(first(k), size(k));
    const double tr_psi = S.block(first(k), first(k), size(k), size(k)).trace();
    const double r2_psi = -v.segment(first(k), size(k)).squaredNorm();
    d.tr_pg(k) = 2 * theta(k) * tr_psi;
    d.r2_gradient(k) = 2 * theta(k) * r2_psi;
    d.B.push_back(2 * theta(k) * Rk.transpose() * Rk);
    for (Eigen::Index l = 0; l < nt; ++l) {
      const auto Skl = S.block(first(k), first(l), size(k), size(l));
      const double tt = 4 * theta(k) * theta(l);
      d.logdet_hessian(k, l) = -tt * Skl.squaredNorm() + (k == l ? 2 * tr_psi : 0.0);
      d.r2_hessian(k, l) =
          tt * 2 * v.segment(first(k), size(k)).dot(Skl * v.segment(first(l), size(l))) +
          (k == l ? 2 * r2_psi : 0.0);
    }
  }
  d.logdet_hessian = (0.5 * (d.logdet_hessian + d.logdet_hessian.transpose())).eval();
  d.r2_hessian = (0.5 * (d.r2_hessian + d.r2_hessian.transpose())).eval();
  return d;
}

namespace {

// Newton steps on the exact gradient and Hessian, made a descent method far from the optimum: the
// Hessian's eigenvalues taken by their absolute value (floored), the step halved until the
// criterion falls, and at a saddle (a theta at 0 where the gradient vanishes because the criterion
// is even in theta, but its variance should be positive) a step along the direction of negative
// curvature. Close to the optimum (Hessian positive definite, small steps) full steps are taken
// while they keep shrinking, even if the criterion moves by rounding: the result is the root of
// the gradient to rounding, as mixed_model.cpp's newton_polish.
Eigen::VectorXd newton_minimise(const CrossedProblem& problem, Eigen::VectorXd x) {
  double fx = problem.profiled_reml(x);
  double last = std::numeric_limits<double>::infinity();
  Eigen::VectorXd g;
  Eigen::MatrixXd H;
  for (int it = 0; it < 500; ++it) {
    if (!profiled_reml_derivatives_at(problem.derivatives(x), problem.n(), problem.p(), g, H))
      break;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(H);
    const Eigen::VectorXd& ev = es.eigenvalues();
    const Eigen::MatrixXd& V = es.eigenvectors();
    const double scale = std::max(1.0, ev.cwiseAbs().maxCoeff());
    const double xmax = 1.0 + x.cwiseAbs().maxCoeff();
    const bool convex = ev(0) > 1e-10 * scale;
    Eigen::VectorXd step =
        -V * (V.transpose() * g).cwiseQuotient(ev.cwiseAbs().cwiseMax(1e-8 * scale));
    double size = step.cwiseAbs().maxCoeff();
    if (convex && size < 1e-3 * xmax) {
      if (!(size < 0.5 * last)) break;  // rounding reached
      const Eigen::VectorXd xn = x + step;
      const double fn = problem.profiled_reml(xn);
      if (!(fn <= fx + 1e-12 * (1 + std::abs(fx)))) break;
      x = xn;
      fx = fn;
      last = size;
      if (size == 0) break;
      continue;
    }
    if (!convex && size < 1e-6 * xmax) {  // a saddle: leave it along negative curvature
      step = 0.1 * xmax * V.col(0);
      size = step.cwiseAbs().maxCoeff();
    } else if (size > xmax) {
      step *= xmax / size;  // a trust region: theta is of order 1
    }
    bool moved = false;
    for (double t = 1; t > 1e-12; t *= 0.5) {
      const Eigen::VectorXd xn = x + t * step;
      const double fn = problem.profiled_reml(xn);
      if (fn < fx) {
        x = xn;
        fx = fn;
        moved = true;
        break;
      }
    }
    if (!moved) break;
    last = std::numeric_limits<double>::infinity();
  }
  return x;
}

}  // namespace

Eigen::VectorXd optimise_crossed_theta(const CrossedProblem& problem) {
  // A grid over each theta brackets the global minimum; Newton from its two best points.
  const std::vector<double> grid = {0.05, 0.2, 0.6, 1.5, 4.0};
  const Eigen::Index nt = problem.n_terms();
  std::vector<std::pair<double, Eigen::VectorXd>> starts;
  std::vector<std::size_t> idx(static_cast<std::size_t>(nt), 0);
  for (;;) {
    Eigen::VectorXd x(nt);
    for (Eigen::Index k = 0; k < nt; ++k) x(k) = grid[idx[static_cast<std::size_t>(k)]];
    starts.emplace_back(problem.profiled_reml(x), x);
    std::size_t k = 0;
    while (k < idx.size() && ++idx[k] == grid.size()) idx[k++] = 0;
    if (k == idx.size()) break;
  }
  std::sort(starts.begin(), starts.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  Eigen::VectorXd best;
  double f_best = std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s < std::min<std::size_t>(2, starts.size()); ++s) {
    const Eigen::VectorXd x = newton_minimise(problem, starts[s].second).cwiseAbs();
    const double f = problem.profiled_reml(x);
    if (f < f_best) {
      f_best = f;
      best = x;
    }
  }
  // The criterion is even in each theta: a theta that Newton drove to 0 (quadratically) is a
  // boundary optimum; make it exactly 0, as lme4's bounded optimiser returns it.
  for (Eigen::Index k = 0; k < nt; ++k) {
    if (!(best(k) < 1e-8)) continue;
    Eigen::VectorXd z = best;
    z(k) = 0.0;
    if (problem.profiled_reml(z) <= f_best + 1e-12 * (1 + std::abs(f_best))) best = z;
  }
  return best;
}

}  // namespace feint::models::detail

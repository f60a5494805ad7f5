// Linear mixed model by REML (lme4's profiled deviance) with lmerTest's type-III F tests and
// Satterthwaite degrees of freedom. See feint/models/mixed_model.hpp and docs/mixed-model.md.
#include "feint/models/mixed_model.hpp"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <stdexcept>

#include "mixed_model_detail.hpp"

namespace feint::models {

namespace detail {

Eigen::MatrixXd zapsmall(const Eigen::MatrixXd& x, int digits) {
  if (x.size() == 0) return x;
  const double mx = x.cwiseAbs().maxCoeff();
  const int d = mx > 0 ? std::max(0, digits - static_cast<int>(std::ceil(std::log10(mx)))) : digits;
  const double scale = std::pow(10.0, d);
  Eigen::MatrixXd out = x;
  for (Eigen::Index i = 0; i < out.size(); ++i) {
    out.data()[i] = std::round(out.data()[i] * scale) / scale;
    if (out.data()[i] == 0.0) out.data()[i] = 0.0;  // no -0
  }
  return out;
}

Eigen::MatrixXd doolittle_lower(const Eigen::MatrixXd& x, double eps) {
  const Eigen::Index n = x.rows();
  Eigen::MatrixXd L = Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd U = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      U(i, j) = x(i, j);
      for (Eigen::Index k = 0; k < i; ++k) U(i, j) -= L(i, k) * U(k, j);
    }
    for (Eigen::Index j = i + 1; j < n; ++j) {
      L(j, i) = x(j, i);
      for (Eigen::Index k = 0; k < i; ++k) L(j, i) -= L(j, k) * U(k, i);
      L(j, i) = std::abs(U(i, i)) < eps ? 0.0 : L(j, i) / U(i, i);
    }
  }
  for (Eigen::Index i = 0; i < L.size(); ++i)
    if (std::abs(L.data()[i]) < eps) L.data()[i] = 0.0;
  return L;
}

int response_scale_exponent(const Eigen::VectorXd& y) {
  if (y.size() == 0) return 0;
  const double spread = (y.array() - y.mean()).abs().maxCoeff();
  if (!(spread > 0) || !std::isfinite(spread)) return 0;
  int e = 0;
  std::frexp(spread, &e);  // spread = f 2^e, f in [0.5, 1)
  return e;
}

double t_quantile_upper(double upper, double df) {
  if (df > 1e10) {
    const boost::math::normal z;
    return boost::math::quantile(boost::math::complement(z, upper));
  }
  try {
    const boost::math::students_t dist(df);
    return boost::math::quantile(boost::math::complement(dist, upper));
  } catch (const std::overflow_error&) {
    return std::numeric_limits<double>::infinity();  // df -> 0: the interval is the whole line
  }
}

double t_two_sided_p(double t, double df) {
  if (df > 1e10) {
    const boost::math::normal z;
    return 2.0 * boost::math::cdf(boost::math::complement(z, std::abs(t)));
  }
  const boost::math::students_t dist(df);
  return 2.0 * boost::math::cdf(boost::math::complement(dist, std::abs(t)));
}

// ---------------------------------------------------------------------------------------------
// The REML criterion

Problem::Problem(Eigen::MatrixXd X_, Eigen::MatrixXd Z_, Eigen::VectorXd y_,
                 std::vector<std::size_t> start_)
    : X(std::move(X_)), Z(std::move(Z_)), y(std::move(y_)), start(std::move(start_)) {
  const std::size_t m = start.size() - 1;
  ZtZ.resize(m);
  ZtX.resize(m);
  Zty.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    const auto r0 = static_cast<Eigen::Index>(start[i]);
    const auto ni = static_cast<Eigen::Index>(start[i + 1] - start[i]);
    const auto Zi = Z.middleRows(r0, ni);
    ZtZ[i] = Zi.transpose() * Zi;
    ZtX[i] = Zi.transpose() * X.middleRows(r0, ni);
    Zty[i] = Zi.transpose() * y.segment(r0, ni);
  }
  XtX = X.transpose() * X;
  Xty = X.transpose() * y;
}

Eigen::MatrixXd Problem::lambda(const Eigen::VectorXd& theta) const {
  const Eigen::Index q = Z.cols();
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(q, q);
  Eigen::Index k = 0;
  for (Eigen::Index j = 0; j < q; ++j)
    for (Eigen::Index i = j; i < q; ++i) L(i, j) = theta(k++);
  return L;
}

std::optional<Eigen::VectorXd> fixed_effect_step(Evaluation& ev, const Eigen::VectorXd& XtHy,
                                                 const Eigen::MatrixXd& X,
                                                 const Eigen::VectorXd& y) {
  ev.xthx_chol.compute(ev.XtHX);
  if (ev.xthx_chol.info() != Eigen::Success) {
    ev.ok = false;
    return std::nullopt;
  }
  const Eigen::MatrixXd Lx = ev.xthx_chol.matrixL();
  ev.logdet_x = 2.0 * Lx.diagonal().array().log().sum();
  ev.beta = ev.xthx_chol.solve(XtHy);
  return Eigen::VectorXd(y - X * ev.beta);
}

Evaluation Problem::evaluate(const Eigen::VectorXd& theta) const {
  const Eigen::MatrixXd L = lambda(theta);
  const Eigen::Index q = Z.cols();
  Evaluation ev;
  ev.XtHX = XtX;
  Eigen::VectorXd XtHy = Xty;
  std::vector<Eigen::LLT<Eigen::MatrixXd>> chol(ZtZ.size());
  for (std::size_t i = 0; i < ZtZ.size(); ++i) {
    const Eigen::MatrixXd M = Eigen::MatrixXd::Identity(q, q) + L.transpose() * ZtZ[i] * L;
    chol[i].compute(M);
    const Eigen::MatrixXd Lc = chol[i].matrixL();
    ev.logdet_m += 2.0 * Lc.diagonal().array().log().sum();
    // Woodbury: H^-1 = I - Z L M^-1 L' Z'.
    const Eigen::MatrixXd W = L.transpose() * ZtX[i];
    const Eigen::VectorXd w = L.transpose() * Zty[i];
    ev.XtHX.noalias() -= W.transpose() * chol[i].solve(W);
    XtHy.noalias() -= W.transpose() * chol[i].solve(w);
  }
  const std::optional<Eigen::VectorXd> e = fixed_effect_step(ev, XtHy, X, y);
  if (!e) return ev;
  // Penalised residual sum of squares e' H^-1 e from the residuals themselves (no cancellation).
  double r2 = e->squaredNorm();
  for (std::size_t i = 0; i < ZtZ.size(); ++i) {
    const Eigen::VectorXd u = L.transpose() * (Zty[i] - ZtX[i] * ev.beta);
    r2 -= u.dot(chol[i].solve(u));
  }
  ev.r2 = r2;
  return ev;
}

double profiled_reml_at(const Evaluation& ev, double n, double p) {
  if (!ev.ok || !(ev.r2 > 0)) return std::numeric_limits<double>::infinity();
  return ev.logdet_m + ev.logdet_x +
         (n - p) * (1.0 + std::log(2.0 * std::numbers::pi * ev.r2 / (n - p)));
}

double reml_deviance_at(const Evaluation& ev, double sigma, double n, double p) {
  const double sigma2 = sigma * sigma;
  if (!ev.ok) return std::numeric_limits<double>::infinity();
  return ev.logdet_m + ev.r2 / sigma2 + n * std::log(2.0 * std::numbers::pi * sigma2) +
         ev.logdet_x - p * std::log(2.0 * std::numbers::pi * sigma2);
}

double Problem::profiled_reml(const Eigen::VectorXd& theta) const {
  return profiled_reml_at(evaluate(theta), static_cast<double>(y.size()),
                          static_cast<double>(X.cols()));
}

double Problem::reml_deviance(const Eigen::VectorXd& varpar) const {
  const Eigen::Index k = varpar.size() - 1;
  return reml_deviance_at(evaluate(varpar.head(k)), varpar(k), static_cast<double>(y.size()),
                          static_cast<double>(X.cols()));
}

Eigen::MatrixXd Problem::vcov_beta(const Eigen::VectorXd& varpar) const {
  const Eigen::Index k = varpar.size() - 1;
  const Evaluation ev = evaluate(varpar.head(k));
  const Eigen::Index p = X.cols();
  return varpar(k) * varpar(k) * ev.xthx_chol.solve(Eigen::MatrixXd::Identity(p, p));
}

// ---------------------------------------------------------------------------------------------
// Optimisation

namespace {

// Nelder–Mead (standard coefficients) on an unconstrained function; returns the best point.
Eigen::VectorXd nelder_mead(const std::function<double(const Eigen::VectorXd&)>& f,
                            Eigen::VectorXd x0, double step, int max_eval) {
  const Eigen::Index n = x0.size();
  std::vector<Eigen::VectorXd> s(static_cast<std::size_t>(n + 1), x0);
  std::vector<double> fs(static_cast<std::size_t>(n + 1));
  for (Eigen::Index i = 0; i < n; ++i) s[static_cast<std::size_t>(i + 1)](i) += step;
  for (std::size_t i = 0; i < s.size(); ++i) fs[i] = f(s[i]);
  int evals = static_cast<int>(n + 1);
  std::vector<std::size_t> idx(s.size());
  while (evals < max_eval) {
    std::iota(idx.begin(), idx.end(), 0);
    std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return fs[a] < fs[b]; });
    const std::size_t best = idx.front(), worst = idx.back(), second = idx[idx.size() - 2];
    if (std::abs(fs[worst] - fs[best]) <= 1e-14 * (1.0 + std::abs(fs[best]))) {
      double size = 0;
      for (const auto& v : s) size = std::max(size, (v - s[best]).cwiseAbs().maxCoeff());
      if (size < 1e-10) break;
    }
    Eigen::VectorXd c = Eigen::VectorXd::Zero(n);
    for (std::size_t i = 0; i < s.size(); ++i)
      if (i != worst) c += s[i];
    c /= static_cast<double>(n);
    const Eigen::VectorXd xr = c + (c - s[worst]);
    const double fr = f(xr);
    ++evals;
    if (fr < fs[best]) {
      const Eigen::VectorXd xe = c + 2.0 * (c - s[worst]);
      const double fe = f(xe);
      ++evals;
      if (fe < fr) {
        s[worst] = xe;
        fs[worst] = fe;
      } else {
        s[worst] = xr;
        fs[worst] = fr;
      }
    } else if (fr < fs[second]) {
      s[worst] = xr;
      fs[worst] = fr;
    } else {
      const bool outside = fr < fs[worst];
      const Eigen::VectorXd xc =
          outside ? Eigen::VectorXd(c + 0.5 * (xr - c)) : Eigen::VectorXd(c + 0.5 * (s[worst] - c));
      const double fc = f(xc);
      ++evals;
      if (fc < std::min(fr, fs[worst])) {
        s[worst] = xc;
        fs[worst] = fc;
      } else {
        for (std::size_t i = 0; i < s.size(); ++i) {
          if (i == best) continue;
          s[i] = s[best] + 0.5 * (s[i] - s[best]);
          fs[i] = f(s[i]);
          ++evals;
        }
      }
    }
  }
  const auto it = std::min_element(fs.begin(), fs.end());
  return s[static_cast<std::size_t>(it - fs.begin())];
}

// Newton steps on the exact gradient and Hessian of the profiled criterion
// (mixed_model_derivatives.cpp) from a point the direct search left near the optimum, until the
// steps stop shrinking (rounding reached): the optimum is then the root of the gradient to
// rounding (~1e-13), whatever path the search took, so the fit is a smooth function of the data
// (scale invariance, docs/mixed-model.md). Only where the Hessian is positive definite, and a step
// must not raise the criterion beyond rounding (it never does this close to the optimum).
Eigen::VectorXd newton_polish(const Problem& problem, Eigen::VectorXd x) {
  double last = std::numeric_limits<double>::infinity();
  double fx = problem.profiled_reml(x);
  Eigen::VectorXd g;
  Eigen::MatrixXd H;
  for (int it = 0; it < 50; ++it) {
    if (!problem.profiled_reml_derivatives(x, g, H)) break;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(H);
    if (!(es.eigenvalues().minCoeff() > 0)) break;
    const Eigen::VectorXd step =
        -es.eigenvectors() * (es.eigenvectors().transpose() * g).cwiseQuotient(es.eigenvalues());
    const double size = step.cwiseAbs().maxCoeff();
    if (!(size < 0.5 * last) || !(size < 0.1 * (1 + x.cwiseAbs().maxCoeff()))) break;
    const Eigen::VectorXd xn = x + step;
    const double fn = problem.profiled_reml(xn);
    if (!(fn <= fx + 1e-12 * (1 + std::abs(fx)))) break;
    x = xn;
    fx = fn;
    last = size;
    if (size == 0) break;
  }
  return x;
}

// One-dimensional: theta >= 0. A grid on log(theta) brackets the global minimum, Brent refines
// it; theta = 0 (a singular fit) wins when its criterion is lower.
double optimise_intercept(const Problem& problem) {
  auto f = [&](double t) {
    Eigen::VectorXd th(1);
    th(0) = t;
    return problem.profiled_reml(th);
  };
  constexpr double lo = -12.0, hi = 6.0, stepsize = 0.25;
  double best_u = lo, best_f = std::numeric_limits<double>::infinity();
  for (double u = lo; u <= hi + 1e-12; u += stepsize) {
    const double v = f(std::exp(u));
    if (v < best_f) {
      best_f = v;
      best_u = u;
    }
  }
  const auto g = [&](double u) { return f(std::exp(u)); };
  const auto r = boost::math::tools::brent_find_minima(g, best_u - stepsize, best_u + stepsize,
                                                       std::numeric_limits<double>::digits / 2);
  double theta = std::exp(r.first);
  double f_theta = r.second;
  if (f(0.0) <= f_theta) {
    theta = 0.0;
    f_theta = f(0.0);
  }
  // Polish in theta itself (Brent's bracket on the log scale stops near sqrt(eps) relative).
  if (theta > 0) {
    const auto r2 = boost::math::tools::brent_find_minima(f, theta * (1 - 1e-6), theta * (1 + 1e-6),
                                                          std::numeric_limits<double>::digits / 2);
    if (r2.second <= f_theta) theta = r2.first;
    // Brent's minimum is only sqrt(eps) precise where the criterion is flat; Newton steps on
    // its exact derivatives find the root of the gradient to rounding.
    Eigen::VectorXd v(1);
    v(0) = theta;
    theta = std::abs(newton_polish(problem, v)(0));  // the criterion is even in theta
  }
  return theta;
}

}  // namespace

Eigen::VectorXd optimise_theta(const Problem& problem) {
  if (problem.Z.cols() == 1) {
    Eigen::VectorXd th(1);
    th(0) = optimise_intercept(problem);
    return th;
  }
  auto f = [&](const Eigen::VectorXd& t) { return problem.profiled_reml(t); };
  // lme4's start: the entries of the identity (1 on the diagonal), column-wise.
  const Eigen::Index q = problem.Z.cols();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(q * (q + 1) / 2);
  std::vector<Eigen::Index> diagonal;  // where each column of Lambda starts in theta
  for (Eigen::Index j = 0, k = 0; j < q; k += q - j, ++j) {
    diagonal.push_back(k);
    x(k) = 1.0;
  }
  // Unconstrained: the criterion depends on Lambda Lambda' only, and every covariance has a factor
  // with diagonal >= 0, so the unconstrained minimum is lme4's bounded one (found by flipping signs
  // below).
  for (int restart = 0; restart < 4; ++restart)
    x = nelder_mead(f, x, restart == 0 ? 0.5 : 0.05, 4000 * static_cast<int>(q * q) / 4);
  x = newton_polish(problem, x);
  // Canonical signs: diagonal of the Cholesky factor >= 0 (negating a column of Lambda leaves
  // Lambda Lambda' and the criterion unchanged).
  for (Eigen::Index j = 0; j < q; ++j)
    if (x(diagonal[static_cast<std::size_t>(j)]) < 0)
      x.segment(diagonal[static_cast<std::size_t>(j)], q - j) *= -1.0;
  return x;
}

}  // namespace detail

}  // namespace feint::models

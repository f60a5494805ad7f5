// The exact derivatives of the REML criteria (src/models/mixed_model_derivatives.cpp) against
// numDeriv's Richardson extrapolation (lmerTest's method, written here as numDeriv's genD and
// jacobian defaults) at points away from the optimum, and the optimum as a root of the exact
// gradient to rounding. A white-box test of the internal header.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <vector>

#include "../../src/models/mixed_model_detail.hpp"

#include "mixed_model_normal.hpp"

namespace {

using feint::models::detail::Problem;

// numDeriv's default steps: 1e-4 |x| (gradient, jacobian) or 0.1 |x| (Hessian), r = 4 Richardson
// levels halving the step.
double richardson(const std::function<double(double)>& diff, double h) {
  constexpr int r = 4;
  double a[r];
  for (int k = 0; k < r; ++k, h /= 2) a[k] = diff(h);
  for (int m = 1; m < r; ++m)
    for (int k = 0; k < r - m; ++k)
      a[k] = (a[k + 1] * std::pow(4.0, m) - a[k]) / (std::pow(4.0, m) - 1);
  return a[0];
}

double step(double x, double d) { return std::abs(d * x) + (std::abs(x) < 1.78e-5 ? 1e-4 : 0.0); }

Eigen::VectorXd num_gradient(const std::function<double(const Eigen::VectorXd&)>& f,
                             const Eigen::VectorXd& x) {
  Eigen::VectorXd g(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i)
    g(i) = richardson(
        [&](double h) {
          Eigen::VectorXd xp = x, xm = x;
          xp(i) += h;
          xm(i) -= h;
          return (f(xp) - f(xm)) / (2 * h);
        },
        step(x(i), 1e-4));
  return g;
}

// The Jacobian of a vector function by Richardson-extrapolated central differences: the exact
// Hessians are checked against differences of the exact gradients (checked themselves against
// differences of the criteria), so that the check is not limited by nested numerical noise.
Eigen::MatrixXd num_jacobian(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& g,
                             const Eigen::VectorXd& x) {
  const Eigen::Index n = x.size();
  Eigen::MatrixXd J(g(x).size(), n);
  for (Eigen::Index j = 0; j < n; ++j) {
    constexpr int r = 4;
    std::vector<Eigen::VectorXd> a;
    double h = step(x(j), 1e-3);
    for (int k = 0; k < r; ++k, h /= 2) {
      Eigen::VectorXd xp = x, xm = x;
      xp(j) += h;
      xm(j) -= h;
      a.push_back((g(xp) - g(xm)) / (2 * h));
    }
    for (int m = 1; m < r; ++m)
      for (int k = 0; k < r - m; ++k)
        a[static_cast<std::size_t>(k)] =
            (a[static_cast<std::size_t>(k + 1)] * std::pow(4.0, m) - a[static_cast<std::size_t>(k)]) /
            (std::pow(4.0, m) - 1);
    J.col(j) = a[0];
  }
  return J;
}

using feint::test::Normal;

// Two conditions, a linear trend (intercept, condition, time, condition x time), random intercept
// (and slope), unbalanced with missing trials.
Problem make_problem(bool slope, std::uint64_t seed) {
  Normal rnorm{seed};
  std::vector<Eigen::RowVectorXd> xr, zr;
  std::vector<double> ys;
  std::vector<std::size_t> start{0};
  for (int k = 0; k < 17; ++k) {
    const double g = k < 8 ? 1 : 0, u = 0.4 * rnorm(), s = 0.1 * rnorm();
    for (int j = 1; j <= 7; ++j) {
      if (rnorm.uniform() < 0.15) continue;
      Eigen::RowVectorXd x(4), z(slope ? 2 : 1);
      x << 1, g, j, g * j;
      if (slope)
        z << 1, j;
      else
        z << 1;
      xr.push_back(x);
      zr.push_back(z);
      ys.push_back(0.3 + 0.2 * g - 0.05 * j * g + u + s * j + 0.3 * rnorm());
    }
    if (ys.size() > start.back()) start.push_back(ys.size());
  }
  const auto n = static_cast<Eigen::Index>(ys.size());
  Eigen::MatrixXd X(n, 4), Z(n, slope ? 2 : 1);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    X.row(i) = xr[static_cast<std::size_t>(i)];
    Z.row(i) = zr[static_cast<std::size_t>(i)];
    y(i) = ys[static_cast<std::size_t>(i)];
  }
  return Problem(X, Z, y, start);
}

double max_rel(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

void check_at(const Problem& pr, const Eigen::VectorXd& theta, double sigma) {
  Eigen::VectorXd g;
  Eigen::MatrixXd H;
  ASSERT_TRUE(pr.profiled_reml_derivatives(theta, g, H));
  auto f = [&](const Eigen::VectorXd& t) { return pr.profiled_reml(t); };
  EXPECT_LE(max_rel(g, num_gradient(f, theta)), 1e-7) << "gradient at " << theta.transpose();
  auto grad = [&](const Eigen::VectorXd& t) {
    Eigen::VectorXd gt;
    Eigen::MatrixXd Ht;
    EXPECT_TRUE(pr.profiled_reml_derivatives(t, gt, Ht));
    return gt;
  };
  EXPECT_LE(max_rel(H, num_jacobian(grad, theta)), 1e-8) << "Hessian at " << theta.transpose();

  // The REML deviance at (theta, sigma): its gradient from the same pieces, checked against
  // differences of the deviance, and its Hessian against differences of that gradient.
  const Eigen::Index nt = theta.size();
  const double np = static_cast<double>(pr.y.size() - pr.X.cols());
  auto dev_grad = [&](const Eigen::VectorXd& v) {
    const auto d = pr.derivatives(v.head(nt));
    const double s = v(nt);
    Eigen::VectorXd out(nt + 1);
    out.head(nt) = d.tr_pg + d.r2_gradient / (s * s);
    out(nt) = -2 * d.ev.r2 / (s * s * s) + 2 * np / s;
    return out;
  };
  Eigen::VectorXd vp(nt + 1);
  vp << theta, sigma;
  auto dev = [&](const Eigen::VectorXd& v) { return pr.reml_deviance(v); };
  EXPECT_LE(max_rel(dev_grad(vp), num_gradient(dev, vp)), 1e-7) << "deviance gradient";
  EXPECT_LE(max_rel(pr.reml_deviance_hessian(vp), num_jacobian(dev_grad, vp)), 1e-8)
      << "deviance Hessian at " << vp.transpose();

  const std::vector<Eigen::MatrixXd> J = pr.vcov_beta_jacobian(vp);
  ASSERT_EQ(J.size(), static_cast<std::size_t>(vp.size()));
  for (Eigen::Index k = 0; k < vp.size(); ++k) {
    const double h0 = step(vp(k), 1e-4);
    const Eigen::MatrixXd num = [&] {
      constexpr int r = 4;
      std::vector<Eigen::MatrixXd> a;
      double h = h0;
      for (int i = 0; i < r; ++i, h /= 2) {
        Eigen::VectorXd xp = vp, xm = vp;
        xp(k) += h;
        xm(k) -= h;
        a.push_back((pr.vcov_beta(xp) - pr.vcov_beta(xm)) / (2 * h));
      }
      for (int m = 1; m < r; ++m)
        for (int i = 0; i < r - m; ++i)
          a[static_cast<std::size_t>(i)] =
              (a[static_cast<std::size_t>(i + 1)] * std::pow(4.0, m) - a[static_cast<std::size_t>(i)]) /
              (std::pow(4.0, m) - 1);
      return a[0];
    }();
    EXPECT_LE(max_rel(J[static_cast<std::size_t>(k)], num), 1e-8) << "d vcov / d varpar_" << k;
  }
}

TEST(MixedModelDerivatives, RandomInterceptMatchesRichardson) {
  const Problem pr = make_problem(false, 7);
  for (const double t : {0.3, 1.1, 4.0}) check_at(pr, Eigen::VectorXd::Constant(1, t), 0.35);
}

TEST(MixedModelDerivatives, RandomSlopeMatchesRichardson) {
  const Problem pr = make_problem(true, 8);
  Eigen::VectorXd t(3);
  t << 1.2, -0.3, 0.4;
  check_at(pr, t, 0.3);
  t << 0.5, 0.2, 0.9;
  check_at(pr, t, 0.5);
}

// At the optimum the exact gradient vanishes to rounding (the Newton polish), not merely to the
// direct search's tolerance.
TEST(MixedModelDerivatives, OptimumIsARootOfTheExactGradient) {
  for (const bool slope : {false, true}) {
    const Problem pr = make_problem(slope, 9);
    const Eigen::VectorXd theta = feint::models::detail::optimise_theta(pr);
    Eigen::VectorXd g;
    Eigen::MatrixXd H;
    ASSERT_TRUE(pr.profiled_reml_derivatives(theta, g, H));
    EXPECT_LE(g.cwiseAbs().maxCoeff(), 1e-11 * H.cwiseAbs().maxCoeff())
        << (slope ? "random slope" : "random intercept") << " theta " << theta.transpose();
  }
}

}  // namespace

// Refits of the random-intercept models under one labelling: see relabelling_refit.hpp.
#include "relabelling_refit.hpp"

#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace feint::models::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The end of -2 REML (sigma profiled out) for residual df `df`, residual sum of squares `q` and
/// the log-determinants. Infinite when the data leave no residual.
double reml_tail(double df, double q, double logdets) {
  if (!(q > 0) || !(df > 0)) return kInf;
  return logdets + df * std::log(q);
}

/// theta^2 at the REML optimum when every participant has one trial in each of the m levels: the
/// criterion then splits into two independent strata (Patterson & Thompson 1971), the participants'
/// means, of variance lambda = sigma^2 (1 + m theta^2) with P - 2 residual df, and the contrasts
/// within participants, of variance sigma^2 with `within_df`. So lambda = SS_B / (P - 2),
/// sigma^2 = SS_W / within_df and theta^2 = (lambda / sigma^2 - 1) / m, or 0 (the boundary) when
/// that is negative: no search. Empty when a stratum leaves no residual.
std::optional<double> stratum_theta2(double ss_between, double ss_within, double people, double m,
                                     double within_df) {
  if (!(people > 2) || !(within_df > 0) || !(ss_between >= 0) || !(ss_within > 0)) return std::nullopt;
  const double lambda = ss_between / (people - 2), sigma2 = ss_within / within_df;
  return lambda > sigma2 ? (lambda / sigma2 - 1) / m : 0.0;
}

/// Cholesky factor L of the symmetric positive definite A, in place (A's lower triangle; Eigen's
/// in-place decomposition: no allocation, although the size changes from labelling to labelling);
/// false unless A is positive definite.
bool cholesky(Eigen::Ref<Eigen::MatrixXd> A) {
  const Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(A);
  return llt.info() == Eigen::Success;
}

std::optional<double> finite(double x) {
  if (std::isfinite(x)) return x;
  return std::nullopt;
}


/// theta^2 at the REML optimum over theta >= 0: Brent's method on s = theta / (1 + theta) in
/// [0, 1), and the boundary theta = 0 itself (a singular fit) when it is lower.
template <class Criterion>
double reml_theta2(const Criterion& crit) {
  auto at = [&](double s) {
    const double th = s / (1 - s);
    return crit(th * th);
  };
  // 26 bits: Brent cannot locate a minimum closer than sqrt(epsilon) (Boost.Math's documentation).
  std::uintmax_t iterations = 200;
  const auto r = boost::math::tools::brent_find_minima(at, 0.0, 1 - 1e-9, 26, iterations);
  double s = r.first;
  if (at(0.0) <= r.second) s = 0;
  const double th = s / (1 - s);
  return th * th;
}

}  // namespace

void Weights::at(const RefitData& d, double t2) {
  c.resize(d.class_n.size());
  e.resize(d.class_n.size());
  logdet_v = 0;
  yvy = d.syy;
  for (std::size_t k = 0; k < c.size(); ++k) {
    e[k] = 1 / (1 + d.class_n[k] * t2);
    c[k] = t2 * e[k];
    logdet_v += d.class_people[k] * std::log1p(d.class_n[k] * t2);
    yvy -= c[k] * d.class_sy2[k];
  }
}

void FactorGroup::allocate(Index levels, Index patterns) {
  people.assign(static_cast<std::size_t>(patterns), 0.0);
  sy = people;
  d_inv.resize(levels);
  s.resize(levels);
  U.resize(levels, patterns);
  G.resize(patterns, patterns);
  K.resize(patterns, patterns);
  for (auto* v : {&g, &root_w, &wz, &h, &x}) v->resize(patterns);
}

bool FactorGroup::prepare(const RefitData& d) {
  present.clear();
  for (std::size_t p = 0; p < people.size(); ++p)
    if (people[p] > 0) present.push_back(p);
  r = static_cast<Index>(present.size());
  d_inv.setZero();
  for (Index a = 0; a < r; ++a) {
    const auto p = static_cast<Index>(present[static_cast<std::size_t>(a)]);
    U.col(a) = d.pattern_count.col(p);
    d_inv += people[static_cast<std::size_t>(p)] * U.col(a);
  }
  if ((d_inv.array() <= 0).any()) return false;
  logdet_d = d_inv.array().log().sum();
  d_inv = d_inv.cwiseInverse();
  sds = (s.array().square() * d_inv.array()).sum();
  for (Index a = 0; a < r; ++a) {
    g(a) = U.col(a).dot(d_inv.cwiseProduct(s));
    for (Index b = 0; b <= a; ++b) G(a, b) = G(b, a) = (U.col(a).array() * U.col(b).array() * d_inv.array()).sum();
  }
  return true;
}

bool FactorGroup::evaluate(const RefitData& d, const Weights& w) {
  for (Index a = 0; a < r; ++a) {
    const std::size_t p = present[static_cast<std::size_t>(a)];
    const double c = w.c[d.pattern_class[p]];
    root_w(a) = std::sqrt(c * people[p]);
    wz(a) = c * sy[p];
  }
  const auto Gr = G.topLeftCorner(r, r);
  const auto rw = root_w.head(r), z = wz.head(r);
  h.head(r).noalias() = Gr * z;  // G W z, then h = g - G W z
  const double vdv = sds + z.dot(h.head(r) - 2 * g.head(r));  // v'D^-1 v = s'D^-1 s - 2 (Wz)'g + (Wz)'G(Wz)
  h.head(r) = g.head(r) - h.head(r);
  auto L = K.topLeftCorner(r, r);
  L.noalias() = -(rw.asDiagonal() * Gr * rw.asDiagonal());  // K = I - W^1/2 G W^1/2
  L.diagonal().array() += 1;
  if (!cholesky(L)) return false;
  logdet = logdet_d;
  for (Index a = 0; a < r; ++a) logdet += 2 * std::log(L(a, a));
  x.head(r) = root_w.head(r).cwiseProduct(h.head(r));
  L.triangularView<Eigen::Lower>().solveInPlace(x.head(r));
  vmv = vdv + x.head(r).squaredNorm();
  return true;
}

FactorModel::FactorModel(const RefitData& d) : d_(d) {
  const auto m = static_cast<Index>(d.levels), patterns = d.pattern_count.cols();
  for (auto& g : g_) g.allocate(m, patterns);
  mu_[0].resize(m);
  mu_[1].resize(m);
  B_.resize(m, 2 * patterns);
  H_.resize(2 * patterns, 2 * patterns);
}

bool FactorModel::label(const std::vector<char>& in_b) {
  for (auto& g : g_) {
    std::fill(g.people.begin(), g.people.end(), 0.0);
    std::fill(g.sy.begin(), g.sy.end(), 0.0);
    g.s.setZero();
  }
  for (std::size_t i = 0; i < in_b.size(); ++i) {
    FactorGroup& g = g_[in_b[i] ? 1 : 0];
    g.people[d_.pattern[i]] += 1;
    g.sy[d_.pattern[i]] += d_.sy[i];
    g.s += d_.sum.col(static_cast<Index>(i));
  }
  return g_[0].prepare(d_) && g_[1].prepare(d_);
}

// The two conditions' terms are added as a + b, which equals b + a bitwise: a labelling and its
// mirror image give the same criterion, so the same theta and the same statistics.
double FactorModel::criterion(double t2) {
  w_.at(d_, t2);
  for (auto& g : g_)
    if (!g.evaluate(d_, w_)) return kInf;
  return reml_tail(df(), rss(), w_.logdet_v + (g_[0].logdet + g_[1].logdet));
}

// SS_B of the participants' means about their condition's, SS_W of the trials about their
// participant's mean and their cell's deviation from its condition's mean, (P - 2)(m - 1) df.
std::optional<double> FactorModel::complete_theta2() const {
  if (!d_.complete || d_.levels < 2) return std::nullopt;
  const double m = static_cast<double>(d_.levels), P = static_cast<double>(d_.n.size());
  double between[2], within[2];
  for (int k = 0; k < 2; ++k) {
    const double K = g_[k].people[0], Y = g_[k].s.sum();
    between[k] = Y * Y / (m * K);
    within[k] = g_[k].s.squaredNorm() / K - between[k];
  }
  return stratum_theta2(d_.sy2 / m - (between[0] + between[1]),
                        (d_.syy - d_.sy2 / m) - (within[0] + within[1]), P, m, (P - 2) * (m - 1));
}

// Each condition's cell means mu = (X'V^-1 X)^-1 v = D^-1 (v + U W^1/2 K^-1 W^1/2 h).
void FactorModel::cell_means() {
  for (int k = 0; k < 2; ++k) {
    FactorGroup& g = g_[k];
    const Index r = g.r;
    Eigen::VectorXd& mu = mu_[k];
    mu = g.s;
    for (Index a = 0; a < r; ++a) mu -= g.wz(a) * g.U.col(a);  // v = s - U W z
    g.h.head(r) = g.x.head(r);
    g.K.topLeftCorner(r, r).triangularView<Eigen::Lower>().transpose().solveInPlace(g.h.head(r));
    for (Index a = 0; a < r; ++a) mu += (g.root_w(a) * g.h(a)) * g.U.col(a);
    mu = mu.cwiseProduct(g.d_inv);
  }
}

// With S = Cov(delta) / sigma^2 = Lambda + B C B' (Lambda = D_0^-1 + D_1^-1, B = [D_k^-1 U_k W_k^1/2],
// C = diag(K_0^-1, K_1^-1)), Woodbury gives S^-1 = Lambda^-1 - Lambda^-1 B H^-1 B' Lambda^-1 with
// H = diag(K_0, K_1) + B' Lambda^-1 B: no matrix of the size of the levels is factorised.
void FactorModel::statistics(double t2, const Wanted& want, Statistics& out) {
  if (!(want.interaction || want.condition) || !std::isfinite(criterion(t2))) return;
  cell_means();
  const double sigma2 = rss() / df();
  const Eigen::VectorXd delta = mu_[1] - mu_[0];
  const Eigen::ArrayXd lambda = g_[0].d_inv.array() + g_[1].d_inv.array();
  const Index r0 = g_[0].r, R = r0 + g_[1].r;
  double t2sum[2] = {0, 0};  // 1'S1 = sum(lambda) + |L_0^-1 B_0'1|^2 + |L_1^-1 B_1'1|^2
  H_.topLeftCorner(R, R).setZero();
  for (int k = 0; k < 2; ++k) {
    const FactorGroup& g = g_[k];
    const Index off = k ? r0 : 0;
    for (Index a = 0; a < g.r; ++a) {
      B_.col(off + a) = g.root_w(a) * g.U.col(a).cwiseProduct(g.d_inv);
      for (Index b = 0; b <= a; ++b)
        H_(off + a, off + b) = (a == b ? 1.0 : 0.0) - g.root_w(a) * g.G(a, b) * g.root_w(b);
    }
    Eigen::VectorXd t = B_.middleCols(off, g.r).colwise().sum().transpose();
    g.K.topLeftCorner(g.r, g.r).triangularView<Eigen::Lower>().solveInPlace(t);
    t2sum[k] = t.squaredNorm();
  }
  const double s11 = lambda.sum() + (t2sum[0] + t2sum[1]);
  if (want.condition && s11 > 0) out.condition_f = finite(delta.sum() * delta.sum() / (sigma2 * s11));
  // Interaction: delta constant over the iterations; the Wald F of delta's deviation from its GLS
  // constant, delta'S^-1 delta - (1'S^-1 delta)^2 / 1'S^-1 1.
  if (!want.interaction || d_.levels < 2) return;
  const auto b = B_.leftCols(R);
  H_.topLeftCorner(R, R).triangularView<Eigen::Lower>() += b.transpose() * (lambda.inverse().matrix().asDiagonal() * b);
  auto L = H_.topLeftCorner(R, R);
  if (!cholesky(L)) return;
  Eigen::VectorXd zd = b.transpose() * (delta.array() / lambda).matrix();
  Eigen::VectorXd z1 = b.transpose() * lambda.inverse().matrix();
  L.triangularView<Eigen::Lower>().solveInPlace(zd);
  L.triangularView<Eigen::Lower>().solveInPlace(z1);
  const double dd = (delta.array().square() / lambda).sum() - zd.squaredNorm();
  const double d1 = (delta.array() / lambda).sum() - zd.dot(z1);
  const double one = lambda.inverse().sum() - z1.squaredNorm();
  if (!(one > 0)) return;
  const double w = (dd - d1 * d1 / one) / sigma2;
  out.interaction_f = finite(std::max(0.0, w) / static_cast<double>(d_.levels - 1));
}

TrendModel::TrendModel(const RefitData& d) : d_(d) {
  for (auto& s : sums_) s.resize(d.class_n.size());
}

void TrendModel::label(const std::vector<char>& in_b) {
  for (auto& s : sums_) std::fill(s.begin(), s.end(), TrendSums{});
  for (std::size_t i = 0; i < in_b.size(); ++i) {
    TrendSums& t = sums_[in_b[i] ? 1 : 0][d_.size_class[i]];
    t.people += 1;
    t.st += d_.st[i];
    t.stt += d_.stt[i];
    t.st2 += d_.st[i] * d_.st[i];
    t.sy += d_.sy[i];
    t.sty += d_.sty[i];
    t.stsy += d_.st[i] * d_.sy[i];
  }
}

// SS_B as the factor model's; SS_W of the trials about their participant's mean less each
// condition's within-participant slope, P (m - 1) - 2 df (time centred at every participant's mean).
std::optional<double> TrendModel::complete_theta2() const {
  if (!d_.complete || d_.levels < 2) return std::nullopt;
  const double m = static_cast<double>(d_.levels), P = static_cast<double>(d_.n.size()), stt = d_.stt[0];
  double between[2], within[2];
  for (int k = 0; k < 2; ++k) {
    const TrendSums& t = sums_[k][0];
    between[k] = t.sy * t.sy / (m * t.people);
    within[k] = t.sty * t.sty / (t.people * stt);
  }
  return stratum_theta2(d_.sy2 / m - (between[0] + between[1]),
                        (d_.syy - d_.sy2 / m) - (within[0] + within[1]), P, m, P * (m - 1) - 2);
}

double TrendModel::criterion(double t2, std::optional<double>* slope_t) {
  w_.at(d_, t2);
  double fitted[2] = {0, 0}, logdet_m[2] = {0, 0}, slope[2] = {0, 0}, var[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    Eigen::Matrix2d M = Eigen::Matrix2d::Zero();
    Eigen::Vector2d v = Eigen::Vector2d::Zero();
    for (std::size_t c = 0; c < sums_[k].size(); ++c) {
      const TrendSums& t = sums_[k][c];
      const double n = d_.class_n[c], cw = w_.c[c], e = w_.e[c];
      M(0, 0) += t.people * n * e;
      M(0, 1) += t.st * e;
      M(1, 1) += t.stt - cw * t.st2;
      v(0) += t.sy * e;
      v(1) += t.sty - cw * t.stsy;
    }
    M(1, 0) = M(0, 1);
    const double det = M(0, 0) * M(1, 1) - M(0, 1) * M(0, 1);
    // A condition whose trials all share one time (or nearly so) has no slope.
    if (!(det > 1e-12 * M(0, 0) * M(1, 1)) || !(M(0, 0) > 0)) return kInf;
    logdet_m[k] = std::log(det);
    const Eigen::Matrix2d inv = M.inverse();
    const Eigen::Vector2d b = inv * v;
    fitted[k] = v.dot(b);
    slope[k] = b(1);
    var[k] = inv(1, 1);
  }
  // a + b, not (x + a) + b: a labelling and its mirror image give the same criterion bitwise.
  const double df = d_.N - 4.0, q = w_.yvy - (fitted[0] + fitted[1]);
  const double crit = reml_tail(df, q, w_.logdet_v + (logdet_m[0] + logdet_m[1]));
  const double v = var[0] + var[1];
  if (slope_t && std::isfinite(crit) && v > 0) *slope_t = finite((slope[1] - slope[0]) / std::sqrt(q / df * v));
  return crit;
}

Statistics refit_statistics(FactorModel& factor, TrendModel& trend, const std::vector<char>& in_b, const Wanted& want) {
  Statistics s;
  if ((want.interaction || want.condition) && factor.label(in_b)) {
    const auto t2 = factor.complete_theta2();
    factor.statistics(t2 ? *t2 : reml_theta2([&](double x) { return factor.criterion(x); }), want, s);
  }
  if (want.slope) {
    trend.label(in_b);
    const auto t2 = trend.complete_theta2();
    trend.criterion(t2 ? *t2 : reml_theta2([&](double x) { return trend.criterion(x); }), &s.slope_t);
  }
  return s;
}

namespace {

// The distinct trial-count patterns and size classes of the participants (`counts`: levels x
// participants).
void group_participants(RefitData& d, const Eigen::MatrixXd& counts) {
  std::map<std::vector<double>, std::size_t> patterns;
  std::map<double, std::size_t> classes;
  const std::size_t P = d.n.size();
  d.pattern.resize(P);
  d.size_class.resize(P);
  std::vector<Eigen::Index> first;
  for (std::size_t i = 0; i < P; ++i) {
    const auto col = counts.col(static_cast<Index>(i));
    const auto [cl, new_class] = classes.emplace(d.n[i], d.class_n.size());
    if (new_class) {
      d.class_n.push_back(d.n[i]);
      d.class_people.push_back(0);
      d.class_sy2.push_back(0);
    }
    d.size_class[i] = cl->second;
    d.class_people[cl->second] += 1;
    d.class_sy2[cl->second] += d.sy[i] * d.sy[i];
    const auto [pt, new_pattern] = patterns.emplace(std::vector<double>(col.begin(), col.end()), first.size());
    if (new_pattern) {
      first.push_back(static_cast<Index>(i));
      d.pattern_class.push_back(cl->second);
    }
    d.pattern[i] = pt->second;
  }
  d.pattern_count.resize(counts.rows(), static_cast<Index>(first.size()));
  for (std::size_t p = 0; p < first.size(); ++p) d.pattern_count.col(static_cast<Index>(p)) = counts.col(first[p]);
  for (const double x : d.class_sy2) d.sy2 += x;
  d.complete = first.size() == 1 && (d.pattern_count.array() == 1).all();
}

}  // namespace

// Each participant's sums of centred time and y, per iteration level and in all.
RefitData summarise(const LongData& data, const std::vector<std::size_t>& row_person, std::size_t people) {
  const std::size_t n = data.y.size(), P = people;
  const std::set<double> level_set(data.time.begin(), data.time.end());
  const std::vector<double> levels(level_set.begin(), level_set.end());
  double ybar = 0, tbar = 0;
  for (std::size_t r = 0; r < n; ++r) {
    ybar += data.y[r];
    tbar += data.time[r];
  }
  ybar /= static_cast<double>(n);
  tbar /= static_cast<double>(n);
  RefitData d;
  d.levels = levels.size();
  d.N = static_cast<double>(n);
  for (auto* v : {&d.n, &d.sy, &d.st, &d.stt, &d.sty}) v->assign(P, 0.0);
  const auto L = static_cast<Index>(d.levels);
  d.sum = Eigen::MatrixXd::Zero(L, static_cast<Index>(P));
  Eigen::MatrixXd counts = Eigen::MatrixXd::Zero(L, static_cast<Index>(P));
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = row_person[r];
    const double y = data.y[r] - ybar, t = data.time[r] - tbar;
    const auto j = static_cast<Index>(std::lower_bound(levels.begin(), levels.end(), data.time[r]) - levels.begin());
    const auto col = static_cast<Index>(i);
    d.n[i] += 1;
    d.sy[i] += y;
    d.st[i] += t;
    d.stt[i] += t * t;
    d.sty[i] += t * y;
    counts(j, col) += 1;
    d.sum(j, col) += y;
    d.syy += y * y;
  }
  group_participants(d, counts);
  return d;
}

}  // namespace feint::models::detail

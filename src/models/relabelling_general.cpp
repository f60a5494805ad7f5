// Relabelling p-values of the random-intercept models for conditions within participants and for
// three or more conditions between participants: see relabelling_general.hpp and
// feint/models/model_relabelling.hpp.
//
// A labelling maps each participant's own conditions to new ones (within: a permutation of the
// conditions the participant saw; between: the participant's one condition, the group sizes kept).
// Under a labelling, participant i contributes X_i'X_i, X_i'1 = u_i and X_i'y_i, its blocks per
// condition moved to their new condition, and with V_i^-1 = (I - c_i 1 1') / sigma^2
// (c = theta^2 / (1 + n_i theta^2), the Fuller–Battese weight):
//
//     X'V^-1 X = sum_i X_i'X_i - sum_k c_k A_k,  A_k = sum_{i of size n_k} u_i u_i'
//     X'V^-1 y = sum_i X_i'y_i - sum_k c_k b_k,  b_k = sum_{i of size n_k} (1'y_i) u_i
//
// so one labelling's theta-free sums are built once and each REML evaluation (Brent's method over
// theta) factorises one K x K matrix: K = conditions x iterations (the factor model, cell means) or
// 2 x conditions (the trend model, an intercept and a slope per condition).
#include "relabelling_general.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/rng.hpp"
#include "feint/stats/permutation.hpp"

namespace feint::models::detail {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kInf = std::numeric_limits<double>::infinity();

std::optional<double> finite(double x) {
  if (std::isfinite(x)) return x;
  return std::nullopt;
}

/// One participant's trials in one of its (original) conditions: the factor model's counts and
/// sums per iteration level, the trend model's sums (time and y centred on the grand means).
struct Block {
  VectorXd count, sum;
  double n = 0, st = 0, stt = 0, sy = 0, sty = 0;
};

/// The study, reduced to blocks per participant and condition.
struct Study {
  std::size_t C = 0, m = 0;
  double N = 0, syy = 0;
  std::vector<std::vector<int>> seen;           // per participant: its conditions, ascending
  std::vector<std::map<int, Block>> blocks;     // per participant: condition -> block
  std::vector<double> n, sy;                    // per participant
  std::vector<std::size_t> size_class;          // per participant
  std::vector<double> class_n, class_people, class_sy2;
};

Study summarise_study(const LongData& data, const std::vector<std::string>& levels, bool within) {
  Study s;
  s.C = levels.size();
  const std::set<double> tset(data.time.begin(), data.time.end());
  const std::vector<double> times(tset.begin(), tset.end());
  s.m = times.size();
  const std::size_t rows = data.y.size();
  double ybar = 0, tbar = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    ybar += data.y[r] / static_cast<double>(rows);
    tbar += data.time[r] / static_cast<double>(rows);
  }
  s.N = static_cast<double>(rows);
  std::map<std::string, std::size_t> person;
  for (std::size_t r = 0; r < rows; ++r) {
    const auto g = std::find(levels.begin(), levels.end(), data.group[r]) - levels.begin();
    if (g == static_cast<long>(levels.size()))
      throw InvalidData(fmt::format("participant {}: condition '{}' is not one of the conditions compared",
                                    data.participant[r], data.group[r]));
    const auto [it, added] = person.emplace(data.participant[r], s.blocks.size());
    if (added) s.blocks.emplace_back();
    auto& mine = s.blocks[it->second];
    if (!within && !mine.empty() && !mine.count(static_cast<int>(g)))
      throw InvalidData(fmt::format("participant {} has trials in two conditions: whole participants cannot be "
                                    "relabelled between the conditions (a within design swaps them instead)",
                                    data.participant[r]));
    auto [b, fresh] = mine.try_emplace(static_cast<int>(g));
    if (fresh) b->second.count = b->second.sum = VectorXd::Zero(static_cast<Index>(s.m));
    const auto j = std::lower_bound(times.begin(), times.end(), data.time[r]) - times.begin();
    const double y = data.y[r] - ybar, t = data.time[r] - tbar;
    Block& k = b->second;
    k.count(j) += 1;
    k.sum(j) += y;
    k.n += 1;
    k.st += t;
    k.stt += t * t;
    k.sy += y;
    k.sty += t * y;
    s.syy += y * y;
  }
  std::map<double, std::size_t> classes;
  for (const auto& mine : s.blocks) {
    double n = 0, sy = 0;
    s.seen.emplace_back();
    for (const auto& [g, b] : mine) {
      n += b.n;
      sy += b.sy;
      s.seen.back().push_back(g);
    }
    const auto [cl, fresh] = classes.emplace(n, s.class_n.size());
    if (fresh) {
      s.class_n.push_back(n);
      s.class_people.push_back(0);
      s.class_sy2.push_back(0);
    }
    s.n.push_back(n);
    s.sy.push_back(sy);
    s.size_class.push_back(cl->second);
    s.class_people[cl->second] += 1;
    s.class_sy2[cl->second] += sy * sy;
  }
  return s;
}

/// A labelling: per participant, the new condition of each of its conditions (map[i][g]).
using Labelling = std::vector<std::vector<int>>;

/// One model's theta-free sums under a labelling, and its REML criterion and fit at theta^2.
class DenseModel {
 public:
  DenseModel(const Study& s, bool trend) : s_(s), trend_(trend) {
    K_ = static_cast<Index>(trend ? 2 * s.C : s.C * s.m);
    A0_.resize(K_, K_);
    a0_.resize(K_);
    A_.assign(s.class_n.size(), MatrixXd(K_, K_));
    b_.assign(s.class_n.size(), VectorXd(K_));
    u_.resize(K_);
  }

  /// Sets the labelling; false when it leaves a cell empty (factor) or a condition without two
  /// distinct times (trend).
  bool label(const Labelling& map);
  /// -2 REML up to a constant at theta^2 = t2 (sigma profiled out); infinite when not estimable.
  double criterion(double t2);
  Index K() const { return K_; }
  /// At the last criterion(): the coefficients, (X'V^-1 X)^-1 and sigma^2.
  VectorXd beta() const { return llt_.solve(v_); }
  MatrixXd inverse() const { return llt_.solve(MatrixXd::Identity(K_, K_)); }
  double sigma2() const { return q_ / (s_.N - static_cast<double>(K_)); }

 private:
  const Study& s_;
  bool trend_;
  Index K_ = 0;
  MatrixXd A0_, M_;
  VectorXd a0_, v_, u_;
  std::vector<MatrixXd> A_;
  std::vector<VectorXd> b_;
  Eigen::LLT<MatrixXd> llt_;
  double q_ = 0;
};

bool DenseModel::label(const Labelling& map) {
  A0_.setZero();
  a0_.setZero();
  for (auto& A : A_) A.setZero();
  for (auto& b : b_) b.setZero();
  const auto C = static_cast<Index>(s_.C), m = static_cast<Index>(s_.m);
  for (std::size_t i = 0; i < s_.blocks.size(); ++i) {
    u_.setZero();
    for (const auto& [g, b] : s_.blocks[i]) {
      const Index c = map[i][static_cast<std::size_t>(g)];
      if (trend_) {
        A0_(c, c) += b.n;
        A0_(c, C + c) += b.st;
        A0_(C + c, c) += b.st;
        A0_(C + c, C + c) += b.stt;
        a0_(c) += b.sy;
        a0_(C + c) += b.sty;
        u_(c) += b.n;
        u_(C + c) += b.st;
      } else {
        A0_.diagonal().segment(c * m, m) += b.count;
        a0_.segment(c * m, m) += b.sum;
        u_.segment(c * m, m) += b.count;
      }
    }
    const std::size_t k = s_.size_class[i];
    A_[k].selfadjointView<Eigen::Lower>().rankUpdate(u_);
    b_[k] += s_.sy[i] * u_;
  }
  for (auto& A : A_) A.triangularView<Eigen::StrictlyUpper>() = A.transpose();
  if (!trend_) return (A0_.diagonal().array() > 0).all();
  for (Index c = 0; c < C; ++c) {
    const double n = A0_(c, c), st = A0_(c, C + c), stt = A0_(C + c, C + c);
    if (!(n > 0) || !(n * stt - st * st > 1e-12 * n * stt)) return false;
  }
  return true;
}

double DenseModel::criterion(double t2) {
  M_ = A0_;
  v_ = a0_;
  double logdet_v = 0, yvy = s_.syy;
  for (std::size_t k = 0; k < s_.class_n.size(); ++k) {
    const double c = t2 / (1 + s_.class_n[k] * t2);
    logdet_v += s_.class_people[k] * std::log1p(s_.class_n[k] * t2);
    yvy -= c * s_.class_sy2[k];
    M_.noalias() -= c * A_[k];
    v_.noalias() -= c * b_[k];
  }
  llt_.compute(M_);
  if (llt_.info() != Eigen::Success) return kInf;
  const MatrixXd& L = llt_.matrixLLT();
  double logdet_m = 0;
  for (Index a = 0; a < K_; ++a) logdet_m += 2 * std::log(L(a, a));
  q_ = yvy - v_.dot(llt_.solve(v_));
  const double df = s_.N - static_cast<double>(K_);
  if (!(q_ > 0) || !(df > 0)) return kInf;
  return logdet_v + logdet_m + df * std::log(q_);
}

/// theta^2 at the REML optimum over theta >= 0 (as relabelling_refit.cpp: Brent on
/// s = theta / (1 + theta), and the boundary theta = 0 when it is lower).
double reml_theta2(DenseModel& model) {
  auto at = [&](double s) {
    const double th = s / (1 - s);
    return model.criterion(th * th);
  };
  std::uintmax_t iterations = 200;
  const auto r = boost::math::tools::brent_find_minima(at, 0.0, 1 - 1e-9, 26, iterations);
  double s = r.first;
  if (at(0.0) <= r.second) s = 0;
  const double th = s / (1 - s);
  return th * th;
}

/// The Wald F of L beta = 0 (rows of L: the hypothesis), as lmerTest's type III F.
std::optional<double> wald_f(const MatrixXd& L, const VectorXd& beta, const MatrixXd& inv, double sigma2) {
  const VectorXd e = L * beta;
  const Eigen::LDLT<MatrixXd> ldlt(L * inv * L.transpose());
  if (ldlt.info() != Eigen::Success || !(sigma2 > 0)) return std::nullopt;
  return finite(e.dot(ldlt.solve(e)) / (sigma2 * static_cast<double>(L.rows())));
}

/// The statistics of one labelling: 0 interaction F, 1 condition F, 2.. each condition's slope
/// minus the first's (t). `want[k]` false: not computed.
std::vector<std::optional<double>> statistics(DenseModel& factor, DenseModel& trend, const Study& s,
                                              const Labelling& map, const std::vector<bool>& want) {
  std::vector<std::optional<double>> out(want.size());
  const auto C = static_cast<Index>(s.C), m = static_cast<Index>(s.m);
  if ((want[0] || want[1]) && factor.label(map)) {
    const double t2 = reml_theta2(factor);
    if (std::isfinite(factor.criterion(t2))) {
      const VectorXd beta = factor.beta();
      const MatrixXd inv = factor.inverse();
      MatrixXd Lc = MatrixXd::Zero(C - 1, factor.K());
      for (Index c = 1; c < C; ++c) {
        Lc.row(c - 1).segment(c * m, m).setConstant(1.0 / static_cast<double>(m));
        Lc.row(c - 1).segment(0, m).setConstant(-1.0 / static_cast<double>(m));
      }
      if (want[1]) out[1] = wald_f(Lc, beta, inv, factor.sigma2());
      if (want[0] && m > 1) {
        MatrixXd Li = MatrixXd::Zero((C - 1) * (m - 1), factor.K());
        for (Index c = 1; c < C; ++c)
          for (Index j = 1; j < m; ++j) {
            auto row = Li.row((c - 1) * (m - 1) + (j - 1));
            row(c * m + j) += 1;
            row(j) -= 1;
            row(c * m) -= 1;
            row(0) += 1;
          }
        out[0] = wald_f(Li, beta, inv, factor.sigma2());
      }
    }
  }
  bool slopes = false;
  for (std::size_t k = 2; k < want.size(); ++k) slopes = slopes || want[k];
  if (slopes && trend.label(map)) {
    const double t2 = reml_theta2(trend);
    if (std::isfinite(trend.criterion(t2))) {
      const VectorXd beta = trend.beta();
      const MatrixXd inv = trend.inverse();
      for (Index c = 1; c < C; ++c) {
        const double v = inv(C + c, C + c) + inv(C, C) - 2 * inv(C + c, C);
        if (v > 0 && want[static_cast<std::size_t>(c + 1)])
          out[static_cast<std::size_t>(c + 1)] = finite((beta(C + c) - beta(C)) / std::sqrt(trend.sigma2() * v));
      }
    }
  }
  return out;
}

/// One test's count, as model_relabelling.cpp's: over every labelling, or Besag & Clifford's
/// sequential p-value over the drawn ones.
struct Tally {
  double threshold = kInf;
  std::uint64_t reached = 0, visited = 0;
  std::optional<stats::SequentialPValue> sampled;
  bool wanted() const { return std::isfinite(threshold) && !(sampled && sampled->done()); }
  void add(bool reaches) {
    if (sampled) sampled->add(reaches);
    else {
      ++visited;
      reached += reaches;
    }
  }
};


/// The number of labellings, or `cap` when there are at least that many.
std::uint64_t count_labellings(const Study& s, const std::vector<int>& group, bool within, std::uint64_t cap) {
  double log_count = 0;
  if (within) {
    for (const auto& seen : s.seen) log_count += std::lgamma(static_cast<double>(seen.size()) + 1);
  } else {
    std::vector<double> size(s.C, 0);
    for (const int g : group) size[static_cast<std::size_t>(g)] += 1;
    log_count = std::lgamma(static_cast<double>(group.size()) + 1);
    for (const double k : size) log_count -= std::lgamma(k + 1);
  }
  if (log_count > std::log(static_cast<double>(cap)) + 1) return cap;
  const double c = std::round(std::exp(log_count));
  return c >= static_cast<double>(cap) ? cap : static_cast<std::uint64_t>(c);
}

/// Visits every labelling (exact) or the observed one and `permutations` uniform draws; `visit`
/// answers whether to go on (ignored when exact).
template <class Visit>
void for_each_labelling(const Study& s, const std::vector<int>& group, bool within, bool exact,
                        const RelabellingOptions& o, const Visit& visit) {
  const std::size_t P = s.blocks.size();
  Labelling map(P, std::vector<int>(s.C, 0));
  auto set_between = [&](const std::vector<int>& g) {
    for (std::size_t i = 0; i < P; ++i) map[i][static_cast<std::size_t>(s.seen[i][0])] = g[i];
  };
  auto set_within = [&](const std::vector<std::vector<int>>& to) {
    for (std::size_t i = 0; i < P; ++i)
      for (std::size_t a = 0; a < s.seen[i].size(); ++a) map[i][static_cast<std::size_t>(s.seen[i][a])] = to[i][a];
  };
  if (!within) {
    std::vector<int> g = group;
    if (exact) {
      std::sort(g.begin(), g.end());
      do {
        set_between(g);
        visit(map);
      } while (std::next_permutation(g.begin(), g.end()));
      return;
    }
    set_between(g);
    if (!visit(map)) return;
    Rng rng(o.seed);
    for (std::uint64_t b = 0; b < o.permutations; ++b) {
      for (std::size_t i = P; i > 1; --i) std::swap(g[i - 1], g[rng.bounded(static_cast<std::uint32_t>(i))]);
      set_between(g);
      if (!visit(map)) return;
    }
    return;
  }
  std::vector<std::vector<int>> to = s.seen;  // the identity: the observed labelling
  if (exact) {
    // A mixed-radix counter over the participants, each digit one permutation of its conditions.
    while (true) {
      set_within(to);
      visit(map);
      std::size_t i = 0;
      while (i < P && !std::next_permutation(to[i].begin(), to[i].end())) ++i;  // wraps to sorted
      if (i == P) return;
    }
  }
  set_within(to);
  if (!visit(map)) return;
  Rng rng(o.seed);
  for (std::uint64_t b = 0; b < o.permutations; ++b) {
    for (std::size_t i = 0; i < P; ++i) {
      to[i] = s.seen[i];
      for (std::size_t a = to[i].size(); a > 1; --a)
        std::swap(to[i][a - 1], to[i][rng.bounded(static_cast<std::uint32_t>(a))]);
    }
    set_within(to);
    if (!visit(map)) return;
  }
}

void fill(RelabelledConditionTests& out, const std::vector<Tally>& tally, bool exact) {
  const std::size_t tests = tally.size();
  out.exact = exact;
  out.slope_differences_t.resize(tests - 2);
  out.p_slope_differences.assign(tests - 2, std::nullopt);
  out.labellings_slopes.assign(tests - 2, 0);
  out.stopped_slopes.assign(tests - 2, false);
  for (std::size_t k = 0; k < tests; ++k) {
    const Tally& t = tally[k];
    if (!std::isfinite(t.threshold)) continue;
    const double p = t.sampled ? t.sampled->p() : static_cast<double>(t.reached) / static_cast<double>(t.visited);
    const std::uint64_t n = t.sampled ? t.sampled->labellings() : t.visited;
    const bool stopped = t.sampled && t.sampled->stopped_early();
    if (k == 0) {
      out.p_interaction = p;
      out.labellings_interaction = n;
      out.stopped_interaction = stopped;
    } else if (k == 1) {
      out.p_condition = p;
      out.labellings_condition = n;
      out.stopped_condition = stopped;
    } else {
      out.p_slope_differences[k - 2] = p;
      out.labellings_slopes[k - 2] = n;
      out.stopped_slopes[k - 2] = stopped;
    }
  }
}

}  // namespace

RelabelledConditionTests relabel_general(const LongData& data, const std::vector<std::string>& group_levels,
                                         const RelabellingOptions& options) {
  const Study s = summarise_study(data, group_levels, options.within);
  const std::size_t P = s.blocks.size();
  std::vector<int> group(P);
  std::vector<std::size_t> size(s.C, 0);
  for (std::size_t i = 0; i < P; ++i) {
    group[i] = s.seen[i][0];
    ++size[static_cast<std::size_t>(group[i])];
  }
  if (!options.within && std::count(size.begin(), size.end(), std::size_t{0}) > 0)
    throw UsageError("relabel_condition_tests: every condition needs at least one participant");
  DenseModel factor(s, false), trend(s, true);
  const std::size_t tests = 2 + s.C - 1;
  const Labelling identity = [&] {
    Labelling id(P, std::vector<int>(s.C));
    for (auto& row : id) std::iota(row.begin(), row.end(), 0);
    return id;
  }();
  const auto observed = statistics(factor, trend, s, identity, std::vector<bool>(tests, true));
  RelabelledConditionTests out;
  out.interaction_f = observed[0];
  out.condition_f = observed[1];
  out.slope_differences_t.assign(observed.begin() + 2, observed.end());
  const std::uint64_t count = count_labellings(s, group, options.within, options.permutations + 2);
  const bool exact = count <= options.permutations + 1;
  std::vector<Tally> tally(tests);
  for (std::size_t k = 0; k < tests; ++k) {
    tally[k].threshold = relabelling_threshold(k < 2 ? observed[k] : observed[k] ? std::optional(std::fabs(*observed[k])) : std::nullopt);
    if (!exact) tally[k].sampled.emplace(options.exceedances, options.permutations + 1);
  }
  bool first = !exact;  // sampling visits the observed labelling first; SequentialPValue counts it
  std::uint64_t visited = 0;
  for_each_labelling(s, group, options.within, exact, options, [&](const Labelling& map) {
    ++visited;
    if (first) {
      first = false;
      return true;
    }
    std::vector<bool> want(tests);
    for (std::size_t k = 0; k < tests; ++k) want[k] = tally[k].wanted();
    const auto v = statistics(factor, trend, s, map, want);
    bool missing = false, more = false;
    for (std::size_t k = 0; k < tests; ++k) {
      if (!want[k]) continue;
      const std::optional<double> x = k < 2 ? v[k] : v[k] ? std::optional(std::fabs(*v[k])) : std::nullopt;
      missing = missing || !x;
      tally[k].add(!x || *x >= tally[k].threshold);
      more = more || tally[k].wanted();
    }
    if (missing) ++out.not_computable;
    return more;
  });
  out.labellings = visited;
  out.exceedances = exact ? 0 : options.exceedances;
  fill(out, tally, exact);
  out.slope_differences_t.assign(observed.begin() + 2, observed.end());
  out.slope_difference_t = out.slope_differences_t[0];
  out.p_slope_difference = out.p_slope_differences[0];
  out.labellings_slope = out.labellings_slopes[0];
  out.stopped_slope = out.stopped_slopes[0];
  return out;
}

double relabelling_threshold(const std::optional<double>& s) {
  return s ? *s - 1e-6 * std::max(1.0, std::fabs(*s)) : std::numeric_limits<double>::infinity();
}

}  // namespace feint::models::detail

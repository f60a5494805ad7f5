// Relabelling p-values of the random-intercept models' condition tests: see
// feint/models/model_relabelling.hpp.
#include "feint/models/model_relabelling.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/stats/permutation.hpp"

namespace feint::models {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// One participant's trials, reduced to what the REML criterion of either model needs.
struct Person {
  double n = 0, sy = 0, syy = 0, st = 0, stt = 0, sty = 0;  // time and y centred
  Eigen::VectorXd count, sum;  // per iteration level: trials and the sum of y
  bool complete = false;       // exactly one trial in every level
};

struct Data {
  std::size_t levels = 0;
  double N = 0, syy = 0;
  std::vector<Person> people;
  std::map<double, double> sizes;  // n_i -> participants with it (log|V| and c_i by class)
  std::vector<double> sy2_by_person;  // sy_i^2
};

/// Fuller–Battese weight of a participant with n trials: V_i^-1 = (I - c 1 1') / sigma^2.
inline double weight(double n, double t2) { return t2 / (1 + n * t2); }

/// The label-free part of -2 REML: log|V| and y'V^-1 y (both over every participant).
void label_free(const Data& d, double t2, double& logdet_v, double& yvy) {
  logdet_v = 0;
  for (const auto& [n, k] : d.sizes) logdet_v += k * std::log1p(n * t2);
  yvy = d.syy;
  for (std::size_t i = 0; i < d.people.size(); ++i) yvy -= weight(d.people[i].n, t2) * d.sy2_by_person[i];
}

/// The end of -2 REML (sigma profiled out) for residual df `df`, residual sum of squares `q` and
/// the log-determinants; sets sigma^2 = q / df in `out`. Infinite when the data leave no residual.
template <class Fit>
double reml_tail(double df, double q, double logdets, Fit* out) {
  if (!(q > 0) || !(df > 0)) return kInf;
  if (out) {
    out->sigma2 = q / df;
    out->ok = true;
  }
  return logdets + df * std::log(q);
}

/// theta-free sums of one condition under a labelling, for the factor model.
struct FactorGroup {
  Eigen::VectorXd count, sum;  // over the condition's participants
  double complete = 0, complete_sy = 0;
  std::vector<std::size_t> partial;  // participants with missing (or repeated) trials
};

struct FactorFit {
  bool ok = false;
  Eigen::VectorXd mu[2];
  Eigen::MatrixXd minv[2];
  double sigma2 = 0;
};

class FactorModel {
 public:
  explicit FactorModel(const Data& d) : d_(d) {}

  /// Sets the labelling (in_b[i]: participant i in the second condition); false when it empties
  /// a condition x iteration cell.
  bool label(const std::vector<char>& in_b) {
    for (auto& g : g_) {
      g.count = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(d_.levels));
      g.sum = g.count;
      g.complete = g.complete_sy = 0;
      g.partial.clear();
    }
    for (std::size_t i = 0; i < d_.people.size(); ++i) {
      FactorGroup& g = g_[in_b[i] ? 1 : 0];
      const Person& p = d_.people[i];
      g.count += p.count;
      g.sum += p.sum;
      if (p.complete) {
        g.complete += 1;
        g.complete_sy += p.sy;
      } else {
        g.partial.push_back(i);
      }
    }
    for (const auto& g : g_)
      if ((g.count.array() <= 0).any()) return false;
    return true;
  }

  /// -2 REML log-likelihood up to a constant (sigma profiled out), at theta^2 = t2.
  double criterion(double t2, FactorFit* out = nullptr) const {
    double logdet_v, q;
    label_free(d_, t2, logdet_v, q);
    const auto m = static_cast<Eigen::Index>(d_.levels);
    const double cm = weight(static_cast<double>(d_.levels), t2);
    double logdet_m = 0;
    for (int k = 0; k < 2; ++k) {
      const FactorGroup& g = g_[k];
      Eigen::MatrixXd M = g.count.asDiagonal();
      M.array() -= cm * g.complete;
      Eigen::VectorXd v = g.sum.array() - cm * g.complete_sy;
      for (const std::size_t i : g.partial) {
        const Person& p = d_.people[i];
        const double c = weight(p.n, t2);
        M.noalias() -= c * p.count * p.count.transpose();
        v.noalias() -= (c * p.sy) * p.count;
      }
      const Eigen::LLT<Eigen::MatrixXd> llt(M);
      if (llt.info() != Eigen::Success) return kInf;
      const Eigen::MatrixXd& L = llt.matrixLLT();
      for (Eigen::Index j = 0; j < m; ++j) logdet_m += 2 * std::log(L(j, j));
      const Eigen::VectorXd w = llt.matrixL().solve(v);
      q -= w.squaredNorm();
      if (out) {
        out->mu[k] = llt.solve(v);
        out->minv[k] = llt.solve(Eigen::MatrixXd::Identity(m, m));
      }
    }
    return reml_tail(d_.N - 2.0 * static_cast<double>(d_.levels), q, logdet_v + logdet_m, out);
  }

 private:
  const Data& d_;
  FactorGroup g_[2];
};

/// theta-free sums of one condition for the linear-trend model.
struct TrendFit {
  bool ok = false;
  Eigen::Vector2d beta[2];  // intercept, slope per condition
  Eigen::Matrix2d minv[2];
  double sigma2 = 0;
};

class TrendModel {
 public:
  explicit TrendModel(const Data& d) : d_(d) {}
  void label(const std::vector<char>& in_b) { in_b_ = &in_b; }

  double criterion(double t2, TrendFit* out = nullptr) const {
    double logdet_v, q;
    label_free(d_, t2, logdet_v, q);
    Eigen::Matrix2d M[2] = {Eigen::Matrix2d::Zero(), Eigen::Matrix2d::Zero()};
    Eigen::Vector2d v[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
    for (std::size_t i = 0; i < d_.people.size(); ++i) {
      const Person& p = d_.people[i];
      const int k = (*in_b_)[i] ? 1 : 0;
      const double c = weight(p.n, t2);
      M[k](0, 0) += p.n - c * p.n * p.n;
      M[k](0, 1) += p.st - c * p.n * p.st;
      M[k](1, 1) += p.stt - c * p.st * p.st;
      v[k](0) += p.sy - c * p.n * p.sy;
      v[k](1) += p.sty - c * p.st * p.sy;
    }
    double logdet_m = 0;
    for (int k = 0; k < 2; ++k) {
      M[k](1, 0) = M[k](0, 1);
      const double det = M[k](0, 0) * M[k](1, 1) - M[k](0, 1) * M[k](0, 1);
      // A condition whose trials all share one time (or a nearly so) has no slope.
      if (!(det > 1e-12 * M[k](0, 0) * M[k](1, 1)) || !(M[k](0, 0) > 0)) return kInf;
      logdet_m += std::log(det);
      const Eigen::Matrix2d inv = M[k].inverse();
      const Eigen::Vector2d b = inv * v[k];
      q -= v[k].dot(b);
      if (out) {
        out->beta[k] = b;
        out->minv[k] = inv;
      }
    }
    return reml_tail(d_.N - 4.0, q, logdet_v + logdet_m, out);
  }

 private:
  const Data& d_;
  const std::vector<char>* in_b_ = nullptr;
};

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

struct Statistics {
  std::optional<double> interaction_f, condition_f, slope_t;
};

std::optional<double> finite(double x) {
  if (std::isfinite(x)) return x;
  return std::nullopt;
}

Statistics statistics(FactorModel& factor, TrendModel& trend, const std::vector<char>& in_b, std::size_t levels) {
  Statistics s;
  if (factor.label(in_b)) {
    FactorFit f;
    const double t2 = reml_theta2([&](double x) { return factor.criterion(x); });
    factor.criterion(t2, &f);
    if (f.ok) {
      const Eigen::VectorXd delta = f.mu[1] - f.mu[0];
      const Eigen::MatrixXd S = f.sigma2 * (f.minv[0] + f.minv[1]);
      const auto m = static_cast<Eigen::Index>(levels);
      const Eigen::VectorXd one = Eigen::VectorXd::Ones(m);
      // Condition (type III, every iteration weighted equally): (1'delta)^2 / 1'S1.
      const double s11 = one.dot(S * one);
      if (s11 > 0) s.condition_f = finite(delta.sum() * delta.sum() / s11);
      // Interaction: delta constant over the iterations; the Wald F of delta's deviation from
      // its GLS constant.
      if (levels >= 2) {
        const Eigen::LLT<Eigen::MatrixXd> llt(S);
        if (llt.info() == Eigen::Success) {
          const Eigen::VectorXd sd = llt.solve(delta), s1 = llt.solve(one);
          const double w = delta.dot(sd) - std::pow(one.dot(sd), 2) / one.dot(s1);
          s.interaction_f = finite(std::max(0.0, w) / static_cast<double>(levels - 1));
        }
      }
    }
  }
  trend.label(in_b);
  {
    TrendFit f;
    const double t2 = reml_theta2([&](double x) { return trend.criterion(x); });
    trend.criterion(t2, &f);
    if (f.ok) {
      const double var = f.sigma2 * (f.minv[0](1, 1) + f.minv[1](1, 1));
      if (var > 0) s.slope_t = finite((f.beta[1](1) - f.beta[0](1)) / std::sqrt(var));
    }
  }
  return s;
}

void check_arguments(const LongData& data, const std::vector<std::string>& group_levels,
                     const RelabellingOptions& options) {
  if (group_levels.size() != 2)
    throw UsageError(fmt::format("relabel_condition_tests: needs two conditions, got {}", group_levels.size()));
  if (options.permutations == 0) throw UsageError("relabel_condition_tests: permutations must be >= 1");
  const std::size_t n = data.y.size();
  if (data.participant.size() != n || data.group.size() != n || data.time.size() != n)
    throw UsageError("relabel_condition_tests: participant, group, time and y differ in length");
}

/// Participants in first-appearance order: each one's condition (1 = the second level), each
/// row's participant, and the participants of the second condition.
struct Membership {
  std::vector<char> in_b;
  std::vector<std::size_t> row_person;
  std::vector<std::size_t> members;
};

// Each participant must stay in one condition: relabelling moves whole participants.
Membership assign_participants(const LongData& data, const std::vector<std::string>& group_levels) {
  const std::size_t n = data.y.size();
  std::map<std::string, std::size_t> index;
  Membership m;
  m.row_person.resize(n);
  for (std::size_t r = 0; r < n; ++r) {
    int g = -1;
    if (data.group[r] == group_levels[0]) g = 0;
    else if (data.group[r] == group_levels[1]) g = 1;
    if (g < 0)
      throw InvalidData(fmt::format("participant {}: condition '{}' is neither '{}' nor '{}'", data.participant[r],
                                    data.group[r], group_levels[0], group_levels[1]));
    auto [it, added] = index.emplace(data.participant[r], m.in_b.size());
    if (added)
      m.in_b.push_back(static_cast<char>(g));
    else if (m.in_b[it->second] != g)
      throw InvalidData(fmt::format("participant {} has trials in both conditions ('{}' and '{}'): whole "
                                    "participants cannot be relabelled",
                                    data.participant[r], group_levels[0], group_levels[1]));
    m.row_person[r] = it->second;
  }
  for (std::size_t i = 0; i < m.in_b.size(); ++i)
    if (m.in_b[i]) m.members.push_back(i);
  if (m.members.empty() || m.members.size() == m.in_b.size())
    throw UsageError("relabel_condition_tests: both conditions need at least one participant");
  return m;
}

// Each participant's sums of centred time and y (the statistics do not depend on either origin;
// sums of squares keep their digits).
Data summarise(const LongData& data, const Membership& m) {
  const std::size_t n = data.y.size();
  const std::set<double> level_set(data.time.begin(), data.time.end());
  const std::vector<double> levels(level_set.begin(), level_set.end());
  double ybar = 0, tbar = 0;
  for (std::size_t r = 0; r < n; ++r) {
    ybar += data.y[r];
    tbar += data.time[r];
  }
  ybar /= static_cast<double>(n);
  tbar /= static_cast<double>(n);
  Data d;
  d.levels = levels.size();
  d.N = static_cast<double>(n);
  d.people.resize(m.in_b.size());
  const auto L = static_cast<Eigen::Index>(d.levels);
  for (auto& p : d.people) {
    p.count = Eigen::VectorXd::Zero(L);
    p.sum = Eigen::VectorXd::Zero(L);
  }
  for (std::size_t r = 0; r < n; ++r) {
    Person& p = d.people[m.row_person[r]];
    const double y = data.y[r] - ybar, t = data.time[r] - tbar;
    const auto j = static_cast<Eigen::Index>(std::lower_bound(levels.begin(), levels.end(), data.time[r]) - levels.begin());
    p.n += 1;
    p.sy += y;
    p.syy += y * y;
    p.st += t;
    p.stt += t * t;
    p.sty += t * y;
    p.count(j) += 1;
    p.sum(j) += y;
    d.syy += y * y;
  }
  for (auto& p : d.people) {
    p.complete = (p.count.array() == 1).all();
    d.sizes[p.n] += 1;
    d.sy2_by_person.push_back(p.sy * p.sy);
  }
  return d;
}

// Just below the observed statistic, so that a relabelling equal to it up to rounding reaches it;
// none (infinite) when the observed one is missing.
double threshold(const std::optional<double>& s) {
  return s ? *s - 1e-9 * std::max(1.0, std::fabs(*s)) : kInf;
}

std::optional<double> magnitude(const std::optional<double>& t) {
  return t ? std::optional<double>(std::fabs(*t)) : std::nullopt;
}

// Every relabelling's statistics against the observed ones; a relabelling whose statistic cannot
// be computed counts as reaching it (and as not computable).
void relabelling_p_values(FactorModel& factor, TrendModel& trend, const Membership& m,
                          std::size_t levels, const RelabellingOptions& options,
                          const Statistics& observed, RelabelledConditionTests& out) {
  const double th_int = threshold(observed.interaction_f), th_cond = threshold(observed.condition_f);
  const double th_slope = threshold(magnitude(observed.slope_t));
  std::uint64_t reach_int = 0, reach_cond = 0, reach_slope = 0;
  std::vector<char> labels(m.in_b.size());
  const stats::Labellings l = stats::for_each_labelling(
      m.in_b.size(), m.members, options.permutations, options.seed,
      [&](std::span<const std::size_t> b) {
        std::fill(labels.begin(), labels.end(), 0);
        for (const std::size_t i : b) labels[i] = 1;
        const Statistics s = statistics(factor, trend, labels, levels);
        bool missing = false;
        auto reach = [&](const std::optional<double>& v, double th, std::uint64_t& count) {
          if (!std::isfinite(th)) return;
          if (!v) {
            missing = true;
            ++count;
          } else if (*v >= th) {
            ++count;
          }
        };
        reach(s.interaction_f, th_int, reach_int);
        reach(s.condition_f, th_cond, reach_cond);
        reach(magnitude(s.slope_t), th_slope, reach_slope);
        if (missing) ++out.not_computable;
      });
  out.labellings = l.total;
  out.exact = l.exact;
  const double total = static_cast<double>(l.total);
  if (observed.interaction_f) out.p_interaction = static_cast<double>(reach_int) / total;
  if (observed.condition_f) out.p_condition = static_cast<double>(reach_cond) / total;
  if (observed.slope_t) out.p_slope_difference = static_cast<double>(reach_slope) / total;
}

}  // namespace

RelabelledConditionTests relabel_condition_tests(const LongData& data,
                                                 const std::vector<std::string>& group_levels,
                                                 const RelabellingOptions& options) {
  check_arguments(data, group_levels, options);
  const Membership m = assign_participants(data, group_levels);
  const Data d = summarise(data, m);
  FactorModel factor(d);
  TrendModel trend(d);
  RelabelledConditionTests out;
  const Statistics observed = statistics(factor, trend, m.in_b, d.levels);
  out.interaction_f = observed.interaction_f;
  out.condition_f = observed.condition_f;
  out.slope_difference_t = observed.slope_t;
  relabelling_p_values(factor, trend, m, d.levels, options, observed, out);
  return out;
}

}  // namespace feint::models

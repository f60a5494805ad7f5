// Refits of the two random-intercept models under one labelling of the participants, for the
// relabelling p-values of feint/models/model_relabelling.hpp (which states the method): the
// participants' sums, the factor model's REML criterion by Woodbury on the few patterns of trials,
// the trend model's 2 x 2 blocks, and theta in closed form with complete data, else by Brent.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "feint/models/mixed_model.hpp"

namespace feint::models::detail {

using Eigen::Index;

/// The participants' trials, reduced to what the REML criterion of either model needs (time and y
/// centred: the statistics depend on neither origin, and sums of squares keep their digits). A
/// participant's trials per iteration level are one of a few patterns (every level once; the first
/// k levels of a dropout), and participants with the same number of trials share one
/// Fuller–Battese weight: the criterion is a function of these few groups.
struct RefitData {
  std::size_t levels = 0;
  double N = 0, syy = 0;
  std::vector<double> n, sy, st, stt, sty;       // per participant
  std::vector<std::size_t> pattern, size_class;  // per participant
  Eigen::MatrixXd sum;                           // levels x participants: sum of y per level
  Eigen::MatrixXd pattern_count;                 // levels x patterns: trials per level
  std::vector<std::size_t> pattern_class;        // size class of each pattern
  std::vector<double> class_n, class_people, class_sy2;  // per size class: n, participants, sum sy^2
  double sy2 = 0;         // sum over participants of sy^2
  bool complete = false;  // every participant has one trial in every level
};

/// The trials of `data` summarised per participant (`row_person[r]`: row r's participant, of
/// `people`).
RefitData summarise(const LongData& data, const std::vector<std::size_t>& row_person, std::size_t people);

/// What every term of one REML evaluation at theta^2 = t2 shares: per size class the Fuller–Battese
/// weight c = t2 / (1 + n t2) (V_i^-1 = (I - c 1 1') / sigma^2) and e = 1 - n c = 1 / (1 + n t2);
/// and the label-free log|V| and y'V^-1 y (times sigma^2).
struct Weights {
  std::vector<double> c, e;
  double logdet_v = 0, yvy = 0;
  void at(const RefitData& d, double t2);
};

/// One condition of the factor model (a mean per iteration level) under a labelling. With D the
/// trials per cell, s the sums of y per cell, U the count patterns present (columns), W = diag(c_p
/// x participants with pattern p) and z their sums of y: X'V^-1 X = D - U W U' and
/// X'V^-1 y = s - U W z (times sigma^2). By Woodbury, with G = U'D^-1 U (theta-free) and
/// K = I - W^1/2 G W^1/2 (r x r, r = patterns present):
///     log|X'V^-1 X| = log|D| + log|K|,
///     v'(X'V^-1 X)^-1 v = v'D^-1 v + |L^-1 W^1/2 h|^2,  v = s - U W z, h = U'D^-1 v, K = L L',
/// so an evaluation costs O(r^3) instead of O(levels^3); r = 1 when every participant has every trial.
struct FactorGroup {
  std::vector<double> people, sy;  // per pattern: participants, their sum of y
  std::vector<std::size_t> present;
  Eigen::VectorXd d_inv, s;  // per cell
  double logdet_d = 0, sds = 0, logdet = 0;
  Eigen::MatrixXd U, G;  // levels x r, r x r (leading blocks used)
  Eigen::VectorXd g;     // U'D^-1 s
  // At the last evaluation: W^1/2, W z, h, and L^-1 W^1/2 h; L in K's lower triangle.
  Eigen::VectorXd root_w, wz, h, x;
  Eigen::MatrixXd K;
  double vmv = 0;
  Index r = 0;

  void allocate(Index levels, Index patterns);
  /// The theta-free parts once people, sy and s hold the labelling's; false when a cell is empty.
  bool prepare(const RefitData& d);
  /// Sets logdet = log|X'V^-1 X| and vmv; false when X'V^-1 X is not positive definite.
  bool evaluate(const RefitData& d, const Weights& w);
};

/// The models' own statistics under one labelling (empty: not computable).
struct Statistics {
  std::optional<double> interaction_f, condition_f, slope_t;
};

/// Which statistics a refit computes (a test whose sequential p-value has stopped needs none).
struct Wanted {
  bool interaction = true, condition = true, slope = true;
};

/// y ~ condition * iteration + (1 | participant), iteration as a factor.
class FactorModel {
 public:
  explicit FactorModel(const RefitData& d);
  /// Sets the labelling (in_b[i]: participant i in the second condition); false when it empties
  /// a condition x iteration cell.
  bool label(const std::vector<char>& in_b);
  /// -2 REML log-likelihood up to a constant (sigma profiled out), at theta^2 = t2.
  double criterion(double t2);
  /// The REML theta^2 in closed form when every participant is complete, else empty.
  std::optional<double> complete_theta2() const;
  /// The condition F and the interaction F wanted, at theta^2 = t2 (the REML estimate).
  void statistics(double t2, const Wanted& want, Statistics& out);

 private:
  double df() const { return d_.N - 2.0 * static_cast<double>(d_.levels); }
  double rss() const { return w_.yvy - (g_[0].vmv + g_[1].vmv); }
  void cell_means();

  const RefitData& d_;
  FactorGroup g_[2];
  Weights w_;
  Eigen::VectorXd mu_[2];
  Eigen::MatrixXd B_, H_;
};

/// Sums over one condition's participants of one size class (n trials) for the trend model.
struct TrendSums {
  double people = 0, st = 0, stt = 0, st2 = 0, sy = 0, sty = 0, stsy = 0;
};

/// y ~ condition * iteration + (1 | participant), iteration as a linear trend: X'V^-1 X and
/// X'V^-1 y are 2 x 2 and 2 x 1 per condition, sums over the size classes of the participants' sums.
class TrendModel {
 public:
  explicit TrendModel(const RefitData& d);
  void label(const std::vector<char>& in_b);
  /// -2 REML up to a constant at theta^2 = t2; with `slope_t`, also the t of the slope difference.
  double criterion(double t2, std::optional<double>* slope_t = nullptr);
  /// The REML theta^2 in closed form when every participant is complete, else empty.
  std::optional<double> complete_theta2() const;

 private:
  const RefitData& d_;
  std::array<std::vector<TrendSums>, 2> sums_;
  Weights w_;
};

/// The statistics `want`ed of labelling `in_b` (a test whose p-value has stopped needs no refit).
Statistics refit_statistics(FactorModel& factor, TrendModel& trend, const std::vector<char>& in_b, const Wanted& want);

}  // namespace feint::models::detail

// Mixed ANOVA in closed form (see mixed_anova.hpp for the formulas and references).
#include "feint/models/mixed_anova.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <cctype>
#include <algorithm>
#include <cmath>

#include "anova_detail.hpp"
#include "feint/error.hpp"

namespace feint::models {

namespace detail {

/// Upper tail of F(df1, df2) at f (Boost complement: no cancellation for small p).
double f_upper(double f, double df1, double df2) {
  if (!(f >= 0) || !std::isfinite(f)) return std::isinf(f) ? 0.0 : 1.0;
  return boost::math::cdf(boost::math::complement(boost::math::fisher_f(df1, df2), f));
}

double chisq_upper(double x, double df) {
  if (!(x > 0)) return 1.0;
  if (std::isinf(x)) return 0.0;
  return boost::math::cdf(boost::math::complement(boost::math::chi_squared(df), x));
}

/// Orthonormal Helmert contrasts, k x (k - 1): column j compares level j+1 with levels 1..j.
Eigen::MatrixXd orthonormal_contrasts(Eigen::Index k) {
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(k, k - 1);
  for (Eigen::Index j = 1; j < k; ++j) {
    const double s = std::sqrt(static_cast<double>(j) * static_cast<double>(j + 1));
    for (Eigen::Index i = 0; i < j; ++i) p(i, j - 1) = 1.0 / s;
    p(j, j - 1) = -static_cast<double>(j) / s;
  }
  return p;
}

SphericityStatistics sphericity_statistics(const Eigen::VectorXd& lambda, double dfe,
                                           double columns) {
  const auto p = static_cast<double>(lambda.size());
  SphericityStatistics out;
  const double s1 = lambda.sum(), s2 = lambda.squaredNorm();
  out.gg = (s1 / p) * (s1 / p) / (s2 / p);
  out.hf = ((dfe + 1) * p * out.gg - 2) / (p * (dfe - p * out.gg));
  // car:::summary.Anova.mlm's mauchly(); `3 * columns` (not 3 * p) as car has it.
  const double logw = lambda.array().log().sum() - p * std::log(s1 / p);
  const double rho = 1 - (2 * p * p + p + 2) / (6 * p * dfe);
  const double w2 = (p + 2) * (p - 1) * (p - 2) * (2 * p * p * p + 6 * p * p + 3 * columns + 2) /
                    (288 * std::pow(dfe * p * rho, 2));
  const double z = -dfe * rho * logw;
  const double f = p * (p + 1) / 2 - 1;
  const double pr1 = chisq_upper(z, f), pr2 = chisq_upper(z, f + 4);
  out.mauchly_w = std::exp(logw);
  // Box's second-order term can carry the sum outside [0, 1] when the effect has nearly as many
  // contrasts as error df (p = 19 iterations, 23 df: car prints p = 1.0155); a probability it is
  // not, so it is kept within [0, 1] (docs/anova-power.md, "Where R is wrong").
  out.mauchly_p = std::clamp(pr1 + w2 * (pr2 - pr1), 0.0, 1.0);
  return out;
}

}  // namespace detail

SphericityCorrection parse_sphericity_correction(std::string_view text) {
  std::string t;
  for (char c : text) t += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (t == "none") return SphericityCorrection::none;
  if (t == "gg") return SphericityCorrection::GG;
  if (t == "hf") return SphericityCorrection::HF;
  throw UsageError(fmt::format("--correction '{}': expected none, GG or HF", text));
}

std::string_view to_string(SphericityCorrection correction) noexcept {
  switch (correction) {
    case SphericityCorrection::none:
      return "none";
    case SphericityCorrection::GG:
      return "GG";
    case SphericityCorrection::HF:
      return "HF";
  }
  return "none";
}

namespace {

/// The sums of squares of the three effects and of the two error strata.
struct SumsOfSquares {
  double condition = 0, iteration = 0, interaction = 0;
  double error_between = 0, error_within = 0;
  Eigen::MatrixXd E;  ///< error SSP of the within effects, in orthonormal contrasts
};

/// Sphericity of E: the GG and HF epsilons and Mauchly's test (k > 2 and E regular only).
struct Sphericity {
  std::optional<double> gg, hf;
  MauchlyTest mauchly;
  std::string note;  ///< why the test and corrections are not computable (E singular)
};

/// What every effect's row needs besides its own sum of squares.
struct EffectContext {
  double error_between, error_within, total_error, p, dfe;
  Eigen::Index k;
  SphericityCorrection correction;
  const Sphericity& sphericity;
};

/// The result's description of the design (everything but the tests).
MixedAnova describe_design(const WideDesign& d, SphericityCorrection correction,
                           const std::vector<std::size_t>& sizes) {
  MixedAnova out;
  out.metric = d.metric;
  out.conditions = d.conditions;
  out.group_sizes = sizes;
  out.iterations = d.iterations;
  out.n_participants = d.n();
  out.excluded = d.excluded;
  out.dropped_conditions = d.dropped_conditions;
  out.correction = correction;
  return out;
}

SumsOfSquares sums_of_squares(const WideDesign& d, const std::vector<std::size_t>& sizes) {
  const auto n = static_cast<Eigen::Index>(d.n());
  const auto k = static_cast<Eigen::Index>(d.k());
  const auto a = static_cast<Eigen::Index>(d.conditions.size());
  SumsOfSquares ss;
  Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> y(
      d.y.data(), n, k);

  // Cell means (condition profiles), their weighted and unweighted means.
  Eigen::MatrixXd profile = Eigen::MatrixXd::Zero(a, k);
  for (Eigen::Index i = 0; i < n; ++i)
    profile.row(static_cast<Eigen::Index>(d.group[i])) += y.row(i);
  Eigen::VectorXd ng(a);
  for (Eigen::Index g = 0; g < a; ++g) {
    ng(g) = static_cast<double>(sizes[static_cast<std::size_t>(g)]);
    profile.row(g) /= ng(g);
  }
  const Eigen::RowVectorXd weighted = (ng.transpose() * profile) / static_cast<double>(n);
  const Eigen::RowVectorXd unweighted = profile.colwise().mean();
  const double c = ng.cwiseInverse().sum() / static_cast<double>(a * a);

  // Residual SSP (k x k) around the condition profiles.
  Eigen::MatrixXd resid(n, k);
  for (Eigen::Index i = 0; i < n; ++i)
    resid.row(i) = y.row(i) - profile.row(static_cast<Eigen::Index>(d.group[i]));
  const Eigen::MatrixXd sspe_full = resid.transpose() * resid;

  const double kd = static_cast<double>(k);
  // Between stratum: participant sums.
  const Eigen::VectorXd rsum = resid.rowwise().sum();
  ss.error_between = rsum.squaredNorm() / kd;
  const Eigen::VectorXd prof_sum = profile.rowwise().sum();
  const double mean_sum = weighted.sum();
  for (Eigen::Index g = 0; g < a; ++g) ss.condition += ng(g) * std::pow(prof_sum(g) - mean_sum, 2);
  ss.condition /= kd;

  // Within stratum.
  const Eigen::MatrixXd P = detail::orthonormal_contrasts(k);
  ss.E = P.transpose() * sspe_full * P;
  ss.error_within = ss.E.trace();
  ss.iteration = (unweighted.array() - unweighted.mean()).square().sum() / c;
  for (Eigen::Index g = 0; g < a; ++g) {
    const Eigen::RowVectorXd dev = profile.row(g) - weighted;
    ss.interaction += ng(g) * (dev * P).squaredNorm();
  }
  return ss;
}

// Sphericity: eigenvalues of E.
Sphericity sphericity_of(const Eigen::MatrixXd& E, double dfe, Eigen::Index n, Eigen::Index k,
                         Eigen::Index a) {
  const double kd = static_cast<double>(k);
  const double p = kd - 1;
  Sphericity out;
  if (k <= 2) return out;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(E, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd lambda = eig.eigenvalues();
  const bool regular = dfe >= p && lambda.minCoeff() > lambda.maxCoeff() * 1e-12;
  if (!regular) {
    out.note = fmt::format(
        "sphericity test and corrections not computable: the {}x{} error SSP matrix of the "
        "within effects is singular ({} complete participants give {} error df for {} "
        "iteration contrasts); the within tests assume sphericity",
        k - 1, k - 1, n, n - a, k - 1);
    out.mauchly.note = "error SSP matrix singular";
    return out;
  }
  // car's nrow(P) is k here: the response has one column per iteration.
  const detail::SphericityStatistics s = detail::sphericity_statistics(lambda, dfe, kd);
  out.gg = s.gg;
  out.hf = s.hf;
  out.mauchly.statistic = s.mauchly_w;
  out.mauchly.p_value = s.mauchly_p;
  return out;
}

/// One effect's row: its F test, with the sphericity corrections for a within effect.
AnovaEffect make_effect(const EffectContext& c, std::string name, bool within, double ss,
                        double num_df) {
  const std::optional<double>& gg = c.sphericity.gg;
  const std::optional<double>& hf = c.sphericity.hf;
  AnovaEffect e;
  e.effect = std::move(name);
  e.within = within;
  e.ss = ss;
  e.error_ss = within ? c.error_within : c.error_between;
  e.num_df = num_df * (within ? c.p : 1);
  e.den_df = c.dfe * (within ? c.p : 1);
  e.f = (e.ss / e.num_df) / (e.error_ss / e.den_df);
  e.p_value = detail::f_upper(e.f, e.num_df, e.den_df);
  e.ges = ss / (ss + c.total_error);
  e.pes = ss / (ss + e.error_ss);
  if (within && gg) {
    e.gg_eps = gg;
    e.hf_eps = hf;
    e.p_gg = detail::f_upper(e.f, *gg * e.num_df, *gg * e.den_df);
    const double hfc = std::min(1.0, *hf);
    e.p_hf = detail::f_upper(e.f, hfc * e.num_df, hfc * e.den_df);
  }
  e.report_num_df = e.num_df;
  e.report_den_df = e.den_df;
  e.report_p = e.p_value;
  if (within && c.k > 2 && c.correction != SphericityCorrection::none) {
    if (gg) {
      const double eps = c.correction == SphericityCorrection::GG ? *gg : std::min(1.0, *hf);
      e.report_eps = eps;
      e.report_num_df = eps * e.num_df;
      e.report_den_df = eps * e.den_df;
      e.report_p = c.correction == SphericityCorrection::GG ? *e.p_gg : *e.p_hf;
    } else {
      e.correction_note = fmt::format("{} correction not computable (singular error SSP matrix)",
                                      to_string(c.correction));
    }
  }
  e.mse = e.error_ss / e.report_den_df;
  return e;
}

}  // namespace

MixedAnova mixed_anova(const WideDesign& d, SphericityCorrection correction) {
  const auto n = static_cast<Eigen::Index>(d.n());
  const auto k = static_cast<Eigen::Index>(d.k());
  const auto a = static_cast<Eigen::Index>(d.conditions.size());
  const std::vector<std::size_t> sizes = d.group_sizes();
  MixedAnova out = describe_design(d, correction, sizes);
  const double dfe = static_cast<double>(n - a);
  if (dfe < 1) {
    throw InvalidData(fmt::format(
        "{}: metric '{}': {} complete participant(s) in {} condition(s) leave no error degrees "
        "of freedom; the ANOVA needs more participants than conditions",
        d.source, d.metric, n, a));
  }
  const SumsOfSquares ss = sums_of_squares(d, sizes);
  if (!(ss.error_within > 0)) {
    throw InvalidData(fmt::format(
        "{}: metric '{}': no within-participant variation left (every participant's profile "
        "equals its condition's mean profile); the F tests are undefined",
        d.source, d.metric));
  }
  const Sphericity sph = sphericity_of(ss.E, dfe, n, k, a);
  out.sphericity_note = sph.note;

  const EffectContext c{ss.error_between, ss.error_within, ss.error_between + ss.error_within,
                        static_cast<double>(k) - 1, dfe, k, correction, sph};
  const double a1 = static_cast<double>(a - 1);
  if (a > 1) out.effects.push_back(make_effect(c, "condition", false, ss.condition, a1));
  out.effects.push_back(make_effect(c, "iteration", true, ss.iteration, 1));
  if (a > 1) out.effects.push_back(make_effect(c, "condition:iteration", true, ss.interaction, a1));
  // Both within effects share E, hence the one Mauchly test (as car reports it).
  if (k > 2) {
    for (const auto& e : out.effects) {
      if (!e.within) continue;
      MauchlyTest m = sph.mauchly;
      m.effect = e.effect;
      out.sphericity.push_back(m);
    }
  }
  return out;
}

}  // namespace feint::models

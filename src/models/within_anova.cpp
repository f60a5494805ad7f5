// The all-within repeated-measures ANOVA in closed form (see within_anova.hpp for the formulas and
// references): the design from long observations, then one multivariate error per effect.
#include "feint/models/within_anova.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <unordered_map>
#include <utility>

#include "anova_detail.hpp"
#include "feint/error.hpp"

namespace feint::models {

namespace {

// ---- the design --------------------------------------------------------------------------------

struct CellValue {
  std::optional<double> value;
  std::uint64_t line = 0;
};

struct Person {
  std::map<std::pair<std::size_t, long long>, CellValue> cells;  // (condition, iteration)
};

struct People {
  std::vector<std::string> order;  // participants in order of first appearance
  std::unordered_map<std::string, Person> by_name;
  std::map<std::pair<std::size_t, long long>, std::size_t> with_value;  // cell -> values present
  std::vector<long long> iterations;                                    // ascending
};

// One pass over the rows: conditions in order of first appearance (into d), each participant's
// cells, and how many values each cell has. A second value for a cell stops here.
People collect_people(std::span<const Observation> observations, const std::string& source,
                      const std::string& metric, WithinDesign& d) {
  People people;
  for (const Observation& o : observations) {
    auto c = std::find(d.conditions.begin(), d.conditions.end(), o.condition);
    const auto ci = static_cast<std::size_t>(c - d.conditions.begin());
    if (c == d.conditions.end()) d.conditions.push_back(o.condition);
    auto [it, fresh] = people.by_name.try_emplace(o.participant);
    if (fresh) people.order.push_back(o.participant);
    auto [cell, added] =
        it->second.cells.try_emplace({ci, o.iteration}, CellValue{o.value, o.line});
    if (!added) {
      throw InvalidData(fmt::format(
          "{}:{}: metric '{}': participant '{}' has a second value for condition '{}' at "
          "iteration {} (the first is on line {}); the within-participant ANOVA needs one value "
          "per participant, condition and iteration (aggregate repeated trials first)",
          source, o.line, metric, o.participant, o.condition, o.iteration, cell->second.line));
    }
    auto& count = people.with_value[{ci, o.iteration}];
    if (o.value) ++count;
  }
  std::map<long long, bool> iterations;
  for (const auto& [cell, count] : people.with_value) iterations[cell.second] = true;
  for (const auto& [iteration, unused] : iterations) people.iterations.push_back(iteration);
  return people;
}

// At least two levels of one factor, and a value in every condition x iteration cell.
void require_crossed_cells(const People& people, const std::string& source,
                           const std::string& metric, WithinDesign& d) {
  d.iterations = people.iterations;
  if (d.a() < 2 && d.k() < 2) {
    throw InvalidData(fmt::format(
        "{}: metric '{}': one condition ('{}') and one iteration ({}); a repeated-measures "
        "ANOVA needs at least two conditions or two iterations",
        source, metric, d.conditions.front(), d.iterations.front()));
  }
  for (std::size_t c = 0; c < d.a(); ++c) {
    for (long long it : d.iterations) {
      auto n = people.with_value.find({c, it});
      if (n != people.with_value.end() && n->second > 0) continue;
      throw InvalidData(fmt::format(
          "{}: metric '{}': condition '{}' has no value at iteration {} for any participant; "
          "with conditions within participants every participant needs every condition at "
          "every iteration (conditions and iterations crossed)",
          source, metric, d.conditions[c], it));
    }
  }
}

// Complete cases in order of first appearance; the rest are excluded. At least two are needed.
void take_complete_cases(const People& people, const std::string& source, const std::string& metric,
                         WithinDesign& d) {
  for (const std::string& name : people.order) {
    const Person& p = people.by_name.at(name);
    std::vector<double> row;  // cell c * k + j, as the loops run
    for (std::size_t c = 0; c < d.a(); ++c) {
      for (long long it : d.iterations) {
        auto v = p.cells.find({c, it});
        if (v != p.cells.end() && v->second.value) row.push_back(*v->second.value);
      }
    }
    if (row.size() < d.cells()) {  // some cell missing or empty
      d.excluded.push_back(name);
      continue;
    }
    d.participants.push_back(name);
    d.y.insert(d.y.end(), row.begin(), row.end());
  }
  if (d.participants.size() < 2) {
    throw InvalidData(fmt::format(
        "{}: metric '{}': {} participant(s) have a value for every one of the {} condition x "
        "iteration cells ({} conditions, iterations {} to {}); the within-participant ANOVA uses "
        "complete cases only and needs at least two{}",
        source, metric, d.participants.size(), d.cells(), d.a(), d.iterations.front(),
        d.iterations.back(),
        d.participants.empty() ? ""
                               : fmt::format(" ('{}' is the only one)", d.participants.front())));
  }
}

void require_variance(const std::string& source, const std::string& metric, const WithinDesign& d) {
  const auto [lo, hi] = std::minmax_element(d.y.begin(), d.y.end());
  if (*lo == *hi) {
    throw InvalidData(fmt::format(
        "{}: metric '{}' has no variance: every value of the {} complete participants is {}; an "
        "ANOVA of a constant is undefined",
        source, metric, d.n(), *lo));
  }
}

// ---- the analysis ------------------------------------------------------------------------------

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Eigen::MatrixXd kronecker(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  Eigen::MatrixXd out(a.rows() * b.rows(), a.cols() * b.cols());
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j)
      out.block(i * b.rows(), j * b.cols(), b.rows(), b.cols()) = a(i, j) * b;
  return out;
}

Eigen::MatrixXd normalised_mean(Eigen::Index m) {
  return Eigen::MatrixXd::Constant(m, 1, 1.0 / std::sqrt(static_cast<double>(m)));
}

/// One effect's hypothesis and error in its orthonormal contrasts L (a k x q).
struct Stratum {
  std::string name;
  double ss = 0;      ///< N ||z.||^2
  Eigen::MatrixXd E;  ///< error SSP, q x q
  double error_ss() const { return E.trace(); }
  Eigen::Index q() const { return E.rows(); }
};

Stratum stratum(const std::string& name, const RowMatrix& y, const Eigen::MatrixXd& L) {
  const Eigen::MatrixXd z = y * L;
  const Eigen::RowVectorXd mean = z.colwise().mean();
  const Eigen::MatrixXd centred = z.rowwise() - mean;
  return {name, static_cast<double>(y.rows()) * mean.squaredNorm(), centred.transpose() * centred};
}

/// The participant stratum first (the intercept's error), then the effects of the design.
std::vector<Stratum> strata(const WithinDesign& d) {
  const auto n = static_cast<Eigen::Index>(d.n());
  const auto a = static_cast<Eigen::Index>(d.a());
  const auto k = static_cast<Eigen::Index>(d.k());
  const Eigen::Map<const RowMatrix> y(d.y.data(), n, a * k);
  std::vector<Stratum> out;
  out.push_back(stratum("participant", y, normalised_mean(a * k)));
  if (a > 1)
    out.push_back(
        stratum("condition", y, kronecker(detail::orthonormal_contrasts(a), normalised_mean(k))));
  if (k > 1)
    out.push_back(
        stratum("iteration", y, kronecker(normalised_mean(a), detail::orthonormal_contrasts(k))));
  if (a > 1 && k > 1)
    out.push_back(
        stratum("condition:iteration", y,
                kronecker(detail::orthonormal_contrasts(a), detail::orthonormal_contrasts(k))));
  return out;
}

/// Sphericity of one effect's E (q > 1): its Mauchly test, and the epsilons when E is regular.
struct EffectSphericity {
  std::optional<double> gg, hf;
  MauchlyTest mauchly;
  std::string note;  ///< why not computable (E singular)
};

EffectSphericity sphericity_of(const Stratum& s, double dfe, double columns) {
  EffectSphericity out;
  out.mauchly.effect = s.name;
  const auto q = static_cast<double>(s.q());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(s.E, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd lambda = eig.eigenvalues();
  if (!(dfe >= q && lambda.minCoeff() > lambda.maxCoeff() * 1e-12)) {
    out.note = fmt::format(
        "sphericity test and corrections of {} not computable: its {}x{} error SSP matrix is "
        "singular ({} complete participants give {} error df for {} contrasts); its test "
        "assumes sphericity",
        s.name, s.q(), s.q(), dfe + 1, dfe, s.q());
    out.mauchly.note = "error SSP matrix singular";
    return out;
  }
  const detail::SphericityStatistics st = detail::sphericity_statistics(lambda, dfe, columns);
  out.gg = st.gg;
  out.hf = st.hf;
  out.mauchly.statistic = st.mauchly_w;
  out.mauchly.p_value = st.mauchly_p;
  return out;
}

/// One effect's row: its F test against its own error, corrected under `correction` when q > 1.
AnovaEffect make_effect(const Stratum& s, const EffectSphericity* sph, double dfe,
                        double total_error, SphericityCorrection correction) {
  AnovaEffect e;
  e.effect = s.name;
  e.within = true;
  e.ss = s.ss;
  e.error_ss = s.error_ss();
  e.num_df = static_cast<double>(s.q());
  e.den_df = dfe * e.num_df;
  e.f = (e.ss / e.num_df) / (e.error_ss / e.den_df);
  e.p_value = detail::f_upper(e.f, e.num_df, e.den_df);
  e.ges = e.ss / (e.ss + total_error);
  e.pes = e.ss / (e.ss + e.error_ss);
  if (sph && sph->gg) {
    e.gg_eps = sph->gg;
    e.hf_eps = sph->hf;
    e.p_gg = detail::f_upper(e.f, *sph->gg * e.num_df, *sph->gg * e.den_df);
    const double hfc = std::min(1.0, *sph->hf);
    e.p_hf = detail::f_upper(e.f, hfc * e.num_df, hfc * e.den_df);
  }
  e.report_num_df = e.num_df;
  e.report_den_df = e.den_df;
  e.report_p = e.p_value;
  if (sph && correction != SphericityCorrection::none) {
    if (sph->gg) {
      const bool gg = correction == SphericityCorrection::GG;
      const double eps = gg ? *sph->gg : std::min(1.0, *sph->hf);
      e.report_eps = eps;
      e.report_num_df = eps * e.num_df;
      e.report_den_df = eps * e.den_df;
      e.report_p = gg ? *e.p_gg : *e.p_hf;
    } else {
      e.correction_note = fmt::format("{} correction not computable (singular error SSP matrix)",
                                      to_string(correction));
    }
  }
  e.mse = e.error_ss / e.report_den_df;
  return e;
}

/// The result's description of the design (everything but the tests).
MixedAnova describe_design(const WithinDesign& d, SphericityCorrection correction) {
  MixedAnova out;
  out.metric = d.metric;
  out.conditions = d.conditions;
  out.group_sizes.assign(d.a(), d.n());
  out.iterations = d.iterations;
  out.n_participants = d.n();
  out.excluded = d.excluded;
  out.correction = correction;
  return out;
}

}  // namespace

WithinDesign make_within_design(std::span<const Observation> observations,
                                const std::string& metric, const std::string& source) {
  WithinDesign d;
  d.source = source;
  d.metric = metric;
  if (observations.empty()) {
    throw InvalidData(fmt::format("{}: metric '{}': no data rows", source, metric));
  }
  const People people = collect_people(observations, source, metric, d);
  require_crossed_cells(people, source, metric, d);
  take_complete_cases(people, source, metric, d);
  require_variance(source, metric, d);
  return d;
}

MixedAnova within_anova(const WithinDesign& d, SphericityCorrection correction) {
  MixedAnova out = describe_design(d, correction);
  if (d.n() < 2) {
    throw InvalidData(fmt::format(
        "{}: metric '{}': {} complete participant(s) leave no error degrees of freedom; the "
        "within-participant ANOVA needs at least two",
        d.source, d.metric, d.n()));
  }
  const std::vector<Stratum> all = strata(d);
  // The strata partition the total sum of squares around the grand mean.
  double total_error = 0, total = 0;
  for (const Stratum& s : all) {
    total_error += s.error_ss();
    total += s.error_ss() + (&s == &all.front() ? 0.0 : s.ss);
  }
  const double dfe = static_cast<double>(d.n()) - 1;
  const double columns = static_cast<double>(d.cells());
  std::vector<std::string> notes;
  for (std::size_t i = 1; i < all.size(); ++i) {
    const Stratum& s = all[i];
    // Rounding leaves ~1e-16 of the total where the error is exactly zero.
    if (!(s.error_ss() > 1e-13 * total)) {
      throw InvalidData(fmt::format(
          "{}: metric '{}': no {} x participant variation (every participant shows the same "
          "{} effect); its F test is undefined",
          d.source, d.metric, s.name, s.name));
    }
    std::optional<EffectSphericity> sph;
    if (s.q() > 1) {
      sph = sphericity_of(s, dfe, columns);
      out.sphericity.push_back(sph->mauchly);
      if (!sph->note.empty()) notes.push_back(sph->note);
    }
    out.effects.push_back(make_effect(s, sph ? &*sph : nullptr, dfe, total_error, correction));
  }
  for (const auto& note : notes)
    out.sphericity_note += (out.sphericity_note.empty() ? "" : "; ") + note;
  return out;
}

}  // namespace feint::models

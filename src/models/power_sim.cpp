// Simulation-based power of the 2 x k design (see power_sim.hpp).
#include "feint/models/power_sim.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <optional>
#include <thread>

#include "feint/error.hpp"
#include "feint/rng.hpp"

namespace feint::models {

namespace detail {
namespace {

/// Standard normal deviates from the simulator's generator, stream `index` of `seed`
/// (feint/rng.hpp), by Marsaglia's polar method keeping the second deviate of each pair
/// (Rng::normal drops it; keeping it halves the uniforms drawn per study).
class Normals {
 public:
  Normals(std::uint64_t seed, std::uint64_t index) noexcept : rng_(Rng::stream(seed, index)) {}
  double next() noexcept {
    if (spare_) {
      const double z = *spare_;
      spare_.reset();
      return z;
    }
    double u, v, s;
    do {
      u = 2 * rng_.uniform() - 1;
      v = 2 * rng_.uniform() - 1;
      s = u * u + v * v;
    } while (s >= 1 || s == 0);
    const double f = std::sqrt(-2 * std::log(s) / s);
    spare_ = v * f;
    return u * f;
  }

 private:
  Rng rng_;
  std::optional<double> spare_;
};

double f_upper(double f, double df1, double df2) {
  if (!(f > 0)) return 1;
  if (std::isinf(f)) return 0;
  return boost::math::cdf(boost::math::complement(boost::math::fisher_f(df1, df2), f));
}

}  // namespace

/// Counts of rejections of one thread.
struct Tally {
  std::size_t interaction = 0, condition = 0, any = 0;
  std::vector<std::size_t> iteration;
  double eps_sum = 0;
};

namespace {

/// One simulated study, analysed; adds its rejections to `t`. Buffers are reused across studies.
struct Study {
  const SimulationDesign& d;
  const SimulationOptions& o;
  std::size_t k, n;
  std::vector<double> y, mean_a, mean_b, var_a, var_b, e, row, rm;
  std::vector<std::optional<double>> p;
  StudyAnalysis last;

  Study(const SimulationDesign& design, const SimulationOptions& options)
      : d(design),
        o(options),
        k(design.means_a.size()),
        n(design.n_a + design.n_b),
        y(n * k),
        mean_a(k),
        mean_b(k),
        var_a(k),
        var_b(k),
        e(k * k),
        row(k),
        rm(k),
        p(k) {}

  void run(std::uint64_t index, Tally& t) {
    draw(index);
    const double between_error = residuals();
    const Centred c = double_centre();
    const double kd = static_cast<double>(k), pdim = kd - 1, dfe = static_cast<double>(n) - 2;
    const double gg = c.tr * c.tr / (pdim * c.frob);
    t.eps_sum += gg;
    const double eps = epsilon(gg, pdim, dfe);
    const double f_int = (interaction_ss() / pdim) / (c.tr / (dfe * pdim));
    last.f_interaction = f_int;
    last.gg_eps = gg;
    last.p_interaction = f_upper(f_int, eps * pdim, eps * dfe * pdim);
    if (last.p_interaction < o.alpha) ++t.interaction;
    test_condition(between_error, dfe, t);
    test_iterations(t);
  }

 private:
  /// Trace and squared Frobenius norm of the doubly centred residual SSP C E C.
  struct Centred {
    double tr = 0, frob = 0;
  };

  /// The study's data: participant i's row is mu + u_i + residuals.
  void draw(std::uint64_t index) {
    Normals normal(o.seed, index);
    for (std::size_t i = 0; i < n; ++i) {
      const auto& mu = i < d.n_a ? d.means_a : d.means_b;
      const double u = d.sd_participant * normal.next();
      double* row = &y[i * k];
      for (std::size_t j = 0; j < k; ++j) row[j] = mu[j] + u + d.sd_residual * normal.next();
    }
  }

  // Condition profiles (two-pass: means, then residual SSP and variances); returns the sum of
  // squared participant-sum residuals.
  double residuals() {
    const double na = static_cast<double>(d.n_a), nb = static_cast<double>(d.n_b);
    std::fill(mean_a.begin(), mean_a.end(), 0.0);
    std::fill(mean_b.begin(), mean_b.end(), 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      auto& m = i < d.n_a ? mean_a : mean_b;
      for (std::size_t j = 0; j < k; ++j) m[j] += y[i * k + j];
    }
    for (std::size_t j = 0; j < k; ++j) {
      mean_a[j] /= na;
      mean_b[j] /= nb;
    }
    std::fill(e.begin(), e.end(), 0.0);
    std::fill(var_a.begin(), var_a.end(), 0.0);
    std::fill(var_b.begin(), var_b.end(), 0.0);
    double between_error = 0;  // sum of squared participant-sum residuals
    std::vector<double>& r = row;
    for (std::size_t i = 0; i < n; ++i) {
      const bool in_a = i < d.n_a;
      const auto& m = in_a ? mean_a : mean_b;
      auto& v = in_a ? var_a : var_b;
      double rs = 0;
      for (std::size_t j = 0; j < k; ++j) {
        r[j] = y[i * k + j] - m[j];
        v[j] += r[j] * r[j];
        rs += r[j];
      }
      between_error += rs * rs;
      for (std::size_t j = 0; j < k; ++j) {
        const double rj = r[j];
        double* ej = &e[j * k];
        for (std::size_t l = 0; l <= j; ++l) ej[l] += rj * r[l];
      }
    }
    for (std::size_t j = 0; j < k; ++j) {
      for (std::size_t l = 0; l < j; ++l) e[l * k + j] = e[j * k + l];
    }
    return between_error;
  }

  // Double centring: CEC.
  Centred double_centre() {
    double grand = 0;
    std::fill(rm.begin(), rm.end(), 0.0);
    for (std::size_t j = 0; j < k; ++j) {
      for (std::size_t l = 0; l < k; ++l) rm[j] += e[j * k + l];
      rm[j] /= static_cast<double>(k);
      grand += rm[j];
    }
    grand /= static_cast<double>(k);
    Centred c;
    for (std::size_t j = 0; j < k; ++j) {
      for (std::size_t l = 0; l < k; ++l) {
        const double v = e[j * k + l] - rm[j] - rm[l] + grand;
        c.frob += v * v;
        if (j == l) c.tr += v;
      }
    }
    return c;
  }

  /// The sphericity correction's epsilon (1: none, or k = 2).
  double epsilon(double gg, double pdim, double dfe) const {
    double eps = 1;
    if (o.correction == SphericityCorrection::GG) eps = gg;
    if (o.correction == SphericityCorrection::HF) {
      eps = std::min(1.0, ((dfe + 1) * pdim * gg - 2) / (pdim * (dfe - pdim * gg)));
    }
    if (k == 2) eps = 1;
    return eps;
  }

  // Interaction SS: n_g || C (profile_g - weighted profile) ||^2.
  double interaction_ss() {
    const double na = static_cast<double>(d.n_a), nb = static_cast<double>(d.n_b);
    const double kd = static_cast<double>(k);
    double ss_int = 0;
    double ca = 0, cb = 0;
    std::vector<double>& da = rm;  // scratch: A's deviation from the weighted profile
    for (std::size_t j = 0; j < k; ++j) {
      const double w = (na * mean_a[j] + nb * mean_b[j]) / (na + nb);
      da[j] = mean_a[j] - w;
      ca += da[j];
      cb += mean_b[j] - w;
    }
    ca /= kd;
    cb /= kd;
    for (std::size_t j = 0; j < k; ++j) {
      const double w = (na * mean_a[j] + nb * mean_b[j]) / (na + nb);
      ss_int += na * std::pow(da[j] - ca, 2) + nb * std::pow(mean_b[j] - w - cb, 2);
    }
    return ss_int;
  }

  // Condition: participant sums.
  void test_condition(double between_error, double dfe, Tally& t) {
    const double na = static_cast<double>(d.n_a), nb = static_cast<double>(d.n_b);
    const double kd = static_cast<double>(k);
    double sa = 0, sb = 0;
    for (std::size_t j = 0; j < k; ++j) {
      sa += mean_a[j];
      sb += mean_b[j];
    }
    const double sw = (na * sa + nb * sb) / (na + nb);
    const double ss_cond = (na * (sa - sw) * (sa - sw) + nb * (sb - sw) * (sb - sw)) / kd;
    const double f_cond = ss_cond / (between_error / kd / dfe);
    last.f_condition = f_cond;
    if (f_upper(f_cond, 1, dfe) < o.alpha) ++t.condition;
  }

  // Per-iteration Welch t, adjusted for multiplicity.
  void test_iterations(Tally& t) {
    const double na = static_cast<double>(d.n_a), nb = static_cast<double>(d.n_b);
    for (std::size_t j = 0; j < k; ++j) {
      const double va = var_a[j] / (na - 1) / na, vb = var_b[j] / (nb - 1) / nb;
      const double se2 = va + vb;
      const double tt = (mean_a[j] - mean_b[j]) / std::sqrt(se2);
      const double df = se2 * se2 / (va * va / (na - 1) + vb * vb / (nb - 1));
      p[j] =
          2 * boost::math::cdf(boost::math::complement(boost::math::students_t(df), std::abs(tt)));
    }
    const auto adjusted = stats::p_adjust(p, o.p_adjust);
    last.p_iteration.assign(k, 0.0);
    for (std::size_t j = 0; j < k; ++j) last.p_iteration[j] = *p[j];
    bool any = false;
    for (std::size_t j = 0; j < k; ++j) {
      if (adjusted[j] && *adjusted[j] < o.alpha) {
        ++t.iteration[j];
        any = true;
      }
    }
    if (any) ++t.any;
  }
};

}  // namespace

StudyAnalysis analyse_simulated_study(const SimulationDesign& design,
                                      const SimulationOptions& options, std::uint64_t index) {
  Tally t;
  t.iteration.assign(design.means_a.size(), 0);
  Study study(design, options);
  study.run(index, t);
  StudyAnalysis a = study.last;
  a.y = study.y;
  return a;
}

namespace {

SimulatedPower proportion(std::size_t count, std::size_t total) {
  const double p = static_cast<double>(count) / static_cast<double>(total);
  return {p, std::sqrt(p * (1 - p) / static_cast<double>(total))};
}

}  // namespace
}  // namespace detail

SimulationDesign design_from_pilot(const WideDesign& pilot) {
  if (pilot.conditions.size() != 2) {
    throw InvalidData(fmt::format(
        "{}: metric '{}': the pilot has {} condition(s) with complete participants; simulation "
        "power needs exactly two (condition A and B)",
        pilot.source, pilot.metric, pilot.conditions.size()));
  }
  const std::size_t k = pilot.k();
  SimulationDesign d;
  d.means_a.assign(k, 0.0);
  d.means_b.assign(k, 0.0);
  const auto sizes = pilot.group_sizes();
  d.n_a = sizes[0];
  d.n_b = sizes[1];
  for (std::size_t i = 0; i < pilot.n(); ++i) {
    auto& m = pilot.group[i] == 0 ? d.means_a : d.means_b;
    for (std::size_t j = 0; j < k; ++j) m[j] += pilot.at(i, j);
  }
  for (std::size_t j = 0; j < k; ++j) {
    d.means_a[j] /= static_cast<double>(d.n_a);
    d.means_b[j] /= static_cast<double>(d.n_b);
  }
  const MixedAnova a = mixed_anova(pilot, SphericityCorrection::none);
  const double dfe = static_cast<double>(pilot.n()) - 2;
  const double kd = static_cast<double>(k);
  const double ms_within = a.effects[1].error_ss / (dfe * (kd - 1));
  const double ms_between = a.effects[0].error_ss / dfe;
  d.sd_residual = std::sqrt(ms_within);
  d.sd_participant = std::sqrt(std::max(0.0, (ms_between - ms_within) / kd));
  return d;
}

SimulationPowerResult simulate_power(const SimulationDesign& design,
                                     const SimulationOptions& options) {
  const std::size_t k = design.means_a.size();
  if (k < 2 || design.means_b.size() != k) {
    throw UsageError(
        fmt::format("the means of A and B need the same number (>= 2) of iterations; got {} and {}",
                    k, design.means_b.size()));
  }
  if (design.n_a < 2 || design.n_b < 2)
    throw UsageError("simulation power needs at least 2 participants per condition");
  if (!(design.sd_residual > 0) || !(design.sd_participant >= 0) ||
      !std::isfinite(design.sd_residual) || !std::isfinite(design.sd_participant)) {
    throw UsageError("the residual sd must be positive and the participant sd non-negative");
  }
  for (double m : design.means_a)
    if (!std::isfinite(m)) throw UsageError("the means must be finite numbers");
  for (double m : design.means_b)
    if (!std::isfinite(m)) throw UsageError("the means must be finite numbers");
  if (options.studies == 0) throw UsageError("--studies must be at least 1");
  if (!(options.alpha > 0 && options.alpha < 1)) throw UsageError("--alpha must be in (0, 1)");

  const unsigned threads =
      std::max(1u, std::min<unsigned>(options.threads, static_cast<unsigned>(options.studies)));
  std::vector<detail::Tally> tallies(threads);
  auto work = [&](unsigned t) {
    detail::Tally& tally = tallies[t];
    tally.iteration.assign(k, 0);
    detail::Study study(design, options);
    for (std::size_t s = t; s < options.studies; s += threads) study.run(s, tally);
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();

  detail::Tally total;
  total.iteration.assign(k, 0);
  for (const auto& t : tallies) {
    total.interaction += t.interaction;
    total.condition += t.condition;
    total.any += t.any;
    total.eps_sum += t.eps_sum;
    for (std::size_t j = 0; j < k; ++j) total.iteration[j] += t.iteration[j];
  }
  SimulationPowerResult r;
  r.design = design;
  r.options = options;
  r.interaction = detail::proportion(total.interaction, options.studies);
  r.condition = detail::proportion(total.condition, options.studies);
  r.any_iteration = detail::proportion(total.any, options.studies);
  for (std::size_t j = 0; j < k; ++j)
    r.iteration.push_back(detail::proportion(total.iteration[j], options.studies));
  r.mean_gg_eps = total.eps_sum / static_cast<double>(options.studies);
  return r;
}

}  // namespace feint::models

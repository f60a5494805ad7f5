// Power settings -> the models' specifications (see feint/commands/power_options.hpp).
#include "feint/commands/power_options.hpp"

#include <fmt/format.h>

#include <vector>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/tables/anova.hpp"
#include "feint/stats/htest.hpp"
#include "feint/stats/p_adjust.hpp"

namespace feint::commands {

namespace {

std::vector<double> parse_means(const std::string& text, const char* option) {
  std::vector<double> out;
  for (const auto& f : io::split_csv_line(text)) {
    const auto v = io::parse_double(io::trim(f));
    if (!v)
      throw UsageError(fmt::format("{} '{}': expected comma-separated numbers, one per iteration",
                                   option, text));
    out.push_back(*v);
  }
  return out;
}

}  // namespace

models::TTestPowerSpec t_test_power_spec(const TTestPowerOptions& a) {
  models::TTestPowerSpec s;
  s.design = models::parse_t_test_design(a.type);
  if (a.d && (a.delta || a.sd)) {
    throw UsageError("--d is Cohen's d (delta with sd = 1): give --d, or --delta with --sd");
  }
  s.n = a.n;
  s.delta = a.d ? a.d : a.delta;
  s.power = a.power;
  s.sd = a.sd.value_or(1.0);
  s.sd2 = a.sd2;
  s.ratio = a.ratio;
  s.welch = a.welch;
  s.alpha = a.alpha;
  s.tests = a.tests;
  try {
    s.alternative = stats::parse_alternative(a.alternative);
  } catch (const UsageError&) {
    throw UsageError(
        fmt::format("--alternative '{}': expected two.sided, greater or less", a.alternative));
  }
  return s;
}

models::SimulationDesign power_design(const PowerSimulationOptions& a) {
  models::SimulationDesign d;
  if (!a.pilot.empty()) {
    if (!a.means_a.empty() || !a.means_b.empty()) {
      throw UsageError("--means-a/--means-b replace a pilot file: give one or the other");
    }
    io::ScoresOptions so = a.columns;
    so.metrics = {a.metric};
    const io::ScoresTable scores = io::load_scores(a.pilot, so);
    const auto obs = tables::observations(scores, a.metric);
    d = models::design_from_pilot(models::make_wide_design(obs, a.metric, scores.path));
  } else {
    if (a.means_a.empty() || a.means_b.empty() || !a.sd_residual) {
      throw UsageError(
          "without a pilot file give --means-a, --means-b (one mean per iteration) and "
          "--sd-residual (and optionally --sd-participant, --n-per-group)");
    }
    d.means_a = parse_means(a.means_a, "--means-a");
    d.means_b = parse_means(a.means_b, "--means-b");
    d.n_a = d.n_b = 30;
  }
  if (a.sd_participant) d.sd_participant = *a.sd_participant;
  if (a.sd_residual) d.sd_residual = *a.sd_residual;
  if (a.n_per_group) d.n_a = d.n_b = *a.n_per_group;
  if (a.null) {
    // The null: both conditions follow the same (average) profile.
    for (std::size_t j = 0; j < d.means_a.size() && j < d.means_b.size(); ++j) {
      d.means_a[j] = d.means_b[j] = (d.means_a[j] + d.means_b[j]) / 2;
    }
  }
  return d;
}

models::SimulationOptions power_simulation_options(const PowerSimulationOptions& a) {
  models::SimulationOptions o;
  o.studies = a.studies;
  o.seed = a.seed;
  o.threads = a.threads;
  if (!(a.alpha > 0 && a.alpha < 1))
    throw UsageError(fmt::format("--alpha {}: expected a number in (0, 1)", a.alpha));
  o.alpha = a.alpha;
  o.correction = models::parse_sphericity_correction(a.correction);
  try {
    o.p_adjust = stats::parse_p_adjust(a.p_adjust);
  } catch (const UsageError&) {
    throw UsageError(
        fmt::format("--p-adjust '{}': expected none, bonferroni, holm, hochberg, hommel, BH or BY",
                    a.p_adjust));
  }
  return o;
}

}  // namespace feint::commands

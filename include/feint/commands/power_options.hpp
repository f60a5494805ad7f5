// feint/commands/power_options.hpp - the settings of `feint power t-test` and `feint power
// simulate` as the command line spells them, and their conversion (with the checks that name
// the option) into the models' power specifications (docs/anova-power.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "feint/io/scores.hpp"
#include "feint/models/power.hpp"
#include "feint/models/power_sim.hpp"

namespace feint::commands {

struct TTestPowerOptions {
  std::string type = "two-sample";
  std::optional<double> n, delta, d, power, sd, sd2;
  double ratio = 1.0;
  bool welch = false;
  double alpha = 0.05;
  int tests = 1;
  std::string alternative = "two.sided";
};

/// Throws UsageError for --d with --delta/--sd, an unknown --type or --alternative.
models::TTestPowerSpec t_test_power_spec(const TTestPowerOptions& options);

struct PowerSimulationOptions {
  std::string pilot;
  std::string metric = "error";
  std::string means_a, means_b;
  std::optional<double> sd_participant, sd_residual;
  std::optional<std::size_t> n_per_group;
  std::size_t studies = 10000;
  std::uint64_t seed = 1;
  unsigned threads = 2;
  double alpha = 0.05;
  std::string correction = "GG";
  std::string p_adjust = "holm";
  bool null = false;
  io::ScoresOptions columns;  // --participant-column, --iteration-column, --condition-column
};

/// The simulated design: from the pilot scores file (its means and variance components), or from
/// --means-a/--means-b/--sd-residual; --sd-participant, --sd-residual and --n-per-group override;
/// --null gives both conditions the average profile. Throws UsageError, InvalidData (pilot).
models::SimulationDesign power_design(const PowerSimulationOptions& options);

/// Studies, seed, threads, alpha, correction and p-value adjustment. Throws UsageError.
models::SimulationOptions power_simulation_options(const PowerSimulationOptions& options);

}  // namespace feint::commands

// feint/sim/sweep.hpp - the simulations `feint simulate selection` runs: one algorithm, all four
// on the same settings (--compare), or the adaptive one over a grid of lambda (--sweep-lambda).
#pragma once

#include <string>
#include <vector>

#include "feint/sim/simulation.hpp"

namespace feint::sim {

/// "FROM:TO:STEP" -> FROM, FROM + STEP, ... <= TO (0 <= FROM <= TO <= 1, STEP > 0; at most 100000
/// values; each rounded to 12 significant digits so that 0.1 steps print as 0.3, not
/// 0.30000000000000004). Throws UsageError naming --sweep-lambda.
std::vector<double> parse_lambda_sweep(const std::string& text);

/// `base` alone; with `compare`, random, fixed-block, fixed-balanced and then adaptive; with
/// `lambdas`, the adaptive algorithm at each (after the three others when `compare`).
std::vector<SimulationSettings> selection_grid(const SimulationSettings& base, bool compare,
                                               const std::vector<double>& lambdas);

}  // namespace feint::sim

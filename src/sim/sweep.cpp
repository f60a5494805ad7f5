// Grids of selection simulations (see feint/sim/sweep.hpp).
#include "feint/sim/sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

namespace feint::sim {

std::vector<double> parse_lambda_sweep(const std::string& text) {
  const auto parts = io::split_csv_line(text, ':');
  auto bad = [&](const std::string& why) {
    return UsageError(fmt::format("--sweep-lambda '{}': {} (expected FROM:TO:STEP, e.g. 0:1:0.05)",
                                  text, why));
  };
  if (parts.size() != 3) throw bad("three numbers are needed");
  std::array<double, 3> v{};
  for (std::size_t i = 0; i < 3; ++i) {
    const auto d = io::parse_double(parts[i]);
    if (!d) throw bad(fmt::format("'{}' is not a number", parts[i]));
    v[i] = *d;
  }
  const double from = v[0], to = v[1], step = v[2];
  if (!(from >= 0 && to <= 1 && from <= to)) throw bad("need 0 <= FROM <= TO <= 1");
  if (!(step > 0)) throw bad("STEP must be > 0");
  std::vector<double> out;
  for (long i = 0;; ++i) {
    const double x = from + static_cast<double>(i) * step;
    if (x > to + step * 1e-6) break;
    const double rounded = *io::parse_double(fmt::format("{:.12g}", x));
    out.push_back(std::min(rounded, 1.0));
    if (out.size() > 100000) throw bad("more than 100000 values");
  }
  return out;
}

std::vector<SimulationSettings> selection_grid(const SimulationSettings& base, bool compare,
                                               const std::vector<double>& lambdas) {
  std::vector<SimulationSettings> all;
  auto with = [&](Algorithm a, double lambda) {
    SimulationSettings s = base;
    s.run.algorithm = a;
    s.run.lambda = lambda;
    all.push_back(s);
  };
  if (compare) {
    for (auto a : {Algorithm::random, Algorithm::fixed_block, Algorithm::fixed_balanced}) {
      with(a, base.run.lambda);
    }
  }
  if (!lambdas.empty()) {
    for (double l : lambdas) with(Algorithm::adaptive, l);
  } else if (compare) {
    with(Algorithm::adaptive, base.run.lambda);
  } else {
    all.push_back(base);
  }

  return all;
}

}  // namespace feint::sim

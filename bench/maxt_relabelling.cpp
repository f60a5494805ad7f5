// maxt_relabelling: the per-iteration maxT adjustment on a study's own scores when the null holds
// exactly (docs/findings.md, "What the 2 000 studies show"). The participants of SCORES are
// relabelled between two groups of the observed sizes at random, RELABELLINGS times; each time the
// 20 (or however many) per-iteration Welch tests of METRIC are maxT-adjusted with PERMUTATIONS
// relabellings, and the share of min adjusted p below .05, .10, .20 and .50 is printed. It must
// not exceed those levels beyond sampling error. Own main (a driver, not a Google Benchmark):
//
//   maxt_relabelling SCORES.csv METRIC [RELABELLINGS=2000] [PERMUTATIONS=999] [SEED=42]
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include "feint/io/scores.hpp"
#include "feint/rng.hpp"
#include "feint/stats/permutation.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    fmt::print(stderr, "usage: maxt_relabelling SCORES.csv METRIC [RELABELLINGS=2000] [PERMUTATIONS=999] [SEED=42]\n");
    return 64;
  }
  const std::string metric = argv[2];
  const int relabellings = argc > 3 ? std::atoi(argv[3]) : 2000;
  feint::stats::MaxTOptions o;
  o.permutations = argc > 4 ? std::strtoull(argv[4], nullptr, 10) : 999;
  feint::Rng rng(argc > 5 ? std::strtoull(argv[5], nullptr, 10) : 42);
  feint::io::ScoresOptions so;
  so.metrics = {metric};
  const auto scores = feint::io::load_scores(argv[1], so);
  const auto iterations = scores.iterations();
  std::map<long long, std::size_t> column;
  for (std::size_t j = 0; j < iterations.size(); ++j) column[iterations[j]] = j;
  std::map<std::string, std::vector<double>> rows;
  for (const auto& r : scores.records) {
    auto& v = rows[r.participant];
    if (v.empty()) v.assign(iterations.size(), std::nan(""));
    v[column[r.iteration]] = r.values[0].value_or(std::nan(""));
  }
  std::vector<double> flat;
  for (const auto& [p, v] : rows) flat.insert(flat.end(), v.begin(), v.end());
  const std::size_t P = rows.size();
  std::vector<int> group(P, 0);
  for (std::size_t i = 0; i < P / 2; ++i) group[i] = 1;
  const double levels[] = {0.05, 0.10, 0.20, 0.50};
  int below[4] = {0, 0, 0, 0};
  for (int r = 0; r < relabellings; ++r) {
    for (std::size_t i = 0; i + 1 < P; ++i) {  // Fisher–Yates
      const std::size_t j = i + rng.bounded(static_cast<std::uint32_t>(P - i));
      std::swap(group[i], group[j]);
    }
    o.seed = 1000 + static_cast<std::uint64_t>(r);
    const auto m = feint::stats::maxt_step_down(flat, iterations.size(), group, o);
    double smallest = 2;
    for (const auto& p : m.p_adjusted)
      if (p && *p < smallest) smallest = *p;
    for (int k = 0; k < 4; ++k) below[k] += smallest < levels[k];
  }
  fmt::print("{}: {} participants x {} iterations, {} random relabellings, {} permutations each\n", metric, P,
             iterations.size(), relabellings, o.permutations);
  for (int k = 0; k < 4; ++k)
    fmt::print("  min adjusted p < {:.2f}: {:.1f} %\n", levels[k], 100.0 * below[k] / relabellings);
  return 0;
}

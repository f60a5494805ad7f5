// exposure_counts(): see feint/models/exposure.hpp.
#include "feint/models/exposure.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace feint::models {

std::vector<double> exposure_counts(std::span<const std::string> participant,
                                    std::span<const double> iteration,
                                    std::span<const std::string> strategy) {
  const std::size_t n = participant.size();
  if (iteration.size() != n || strategy.size() != n)
    throw std::invalid_argument("exposure_counts: columns of different lengths");
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (participant[a] != participant[b]) return participant[a] < participant[b];
    return iteration[a] < iteration[b];
  });
  std::vector<double> out(n, 0.0);
  std::map<std::pair<std::string, std::string>, double> seen;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k];
    if (k > 0 && participant[order[k - 1]] == participant[i] &&
        iteration[order[k - 1]] == iteration[i])
      throw std::invalid_argument("exposure_counts: participant " + participant[i] +
                                  " has two trials at one iteration");
    double& count = seen[{participant[i], strategy[i]}];
    out[i] = count;
    count += 1;
  }
  return out;
}

}  // namespace feint::models

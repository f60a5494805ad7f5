// feint/models/exposure.hpp - how often a participant had already seen a trial's strategy.
#pragma once

#include <span>
#include <string>
#include <vector>

namespace feint::models {

/// For each trial i, the number of earlier trials (smaller iteration) of the same participant with
/// the same strategy: 0 at a participant's first exposure to a strategy, 1 at the second, ...
/// Trials are counted whether or not their metric is missing (seeing a strategy is the exposure,
/// not scoring it). Equal iterations of one participant throw std::invalid_argument (the scores
/// loader already rejects duplicate keys). In R: ave(seq_along(s), participant, strategy,
/// FUN = seq_along) - 1 after sorting by participant and iteration.
std::vector<double> exposure_counts(std::span<const std::string> participant,
                                    std::span<const double> iteration,
                                    std::span<const std::string> strategy);

}  // namespace feint::models

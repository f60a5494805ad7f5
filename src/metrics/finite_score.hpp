// finite_score.hpp - the last check of every trial score (private to the metrics module).
#pragma once

#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::metrics::detail {

/// A score that is not a finite number must never be written: the trial is invalid (e.g. a
/// segment moving faster than the largest double per second, for the raw confusion). `Score` has
/// error, confusion, n_samples and duration (TrialScore, BeliefPointScore).
template <typename Score>
void reject_non_finite(const Score& s) {
  for (const auto& [name, value] : {std::pair<const char*, double>{"error", s.error}, {"confusion", s.confusion}}) {
    if (!std::isfinite(value)) {
      throw InvalidData(fmt::format("{} is not a finite number ({}; the trial's {} samples span {} s)", name, value,
                                    s.n_samples, s.duration));
    }
  }
}

}  // namespace feint::metrics::detail

// src/models/observer_study_detail.hpp - what the study fits of the pad (observer_study.cpp) and of
// the pointer (pointer_observer_fit.cpp, pointer_observer_agreement.cpp) share beyond the
// optimisers (observer_optimise.hpp): each trial's exposure, the agreement table's cells and their
// sums, the notes without their unit (docs/observer.md, "Model–human agreement", "Learning").
#pragma once

#include <algorithm>
#include <array>
#include <map>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "feint/models/observer_fit.hpp"

namespace feint::models::detail::observer {

/// Sorts trials by condition, participant and iteration, and counts each trial's exposure: its
/// participant's earlier trials of the same strategy (in that condition).
template <typename Trial>
void count_exposure(std::vector<Trial>& trials) {
  std::stable_sort(trials.begin(), trials.end(), [](const Trial& a, const Trial& b) {
    return std::tie(a.condition, a.participant, a.iteration) < std::tie(b.condition, b.participant, b.iteration);
  });
  std::map<std::tuple<std::string, std::string, std::string>, int> seen;
  for (auto& tr : trials) tr.exposure = seen[{tr.condition, tr.participant, tr.strategy}]++;
}

/// A note without its leading "unit: " (the issue list names the unit already).
std::string without_unit(const std::string& note, const std::string& unit);

/// Running sums for a Pearson correlation and an RMSE of pairs (x = human, y = model).
struct PairSums {
  double n = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, sdd = 0;
  void add(double x, double y) {
    n += 1; sx += x; sy += y; sxx += x * x; syy += y * y; sxy += x * y; sdd += (x - y) * (x - y);
  }
  double r() const;     // NaN with fewer than 3 pairs or no variance
  double rmse() const;  // NaN without a pair
  double mean_x() const;
  double mean_y() const;
};

/// One trial's human and model scores (the same scoring for both) and its traces compared sample
/// by sample (the pad's position, or the pointer's distance to the true target).
struct TrialAgreement {
  double human_error = 0, model_error = 0;
  double human_confusion = 0, model_confusion = 0;
  std::span<const double> human_trace, model_trace;  // as long as each other
};

/// The agreement table's cells: each trial counts in its (condition, strategy, iteration) cell and
/// in the "all" margins (an empty condition is "all", an empty strategy "unknown", iteration 0
/// every iteration).
class AgreementCells {
 public:
  void add(const std::string& condition, const std::string& strategy, long long iteration, const TrialAgreement& trial);
  /// One row per cell, ordered by (condition, strategy, iteration).
  std::vector<AgreementRow> rows() const;

 private:
  std::map<std::tuple<std::string, std::string, long long>, std::array<PairSums, 3>> cells_;
};

}  // namespace feint::models::detail::observer

// src/metrics/score_detail.hpp - what score.cpp shares with score_pointer.cpp (not public).
#pragma once

#include <string>
#include <vector>

#include "feint/io/trace.hpp"
#include "feint/metrics/trial_metrics.hpp"

namespace feint::metrics::detail {

/// The columns written after score_columns() for logs of K targets and a pointer: mousetrap's
/// measures of the pointer trace (docs/pointer-measures.md, "In the scores table").
const std::vector<std::string>& pointer_score_columns();

/// A trial of a K-target log scored as a belief point, with its pointer measures (score.pointer).
/// Throws InvalidData naming the trial's file and line.
TrialScore score_pointer_trial(const io::Trial& t, const MetricSettings& m);

}  // namespace feint::metrics::detail

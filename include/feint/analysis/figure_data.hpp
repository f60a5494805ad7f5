// feint/analysis/figure_data.hpp - the data of the figures that need more than the tables: the
// strategies each participant saw (from the scores), the mean pad traces per strategy and, for
// logs of K targets and a pointer, the map (mean robot paths and pointers), both from the logs,
// read by the analysis. They are computed in metrics (feint/metrics/mean_trace.hpp,
// feint/metrics/mean_map.hpp); the plot module draws them and never reads a file.
#pragma once

#include "feint/metrics/mean_map.hpp"
#include "feint/metrics/mean_trace.hpp"

namespace feint::analysis {

using metrics::kTracePoints;
using metrics::mean_map;
using metrics::mean_traces;
using metrics::MeanMap;
using metrics::read_trial_labels;
using metrics::TraceCurve;
using metrics::TrialLabel;

}  // namespace feint::analysis

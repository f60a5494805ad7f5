// feint/analysis/figure_data.hpp - the data of the figures that need more than the tables: the
// strategies each participant saw (from the scores) and the mean pad traces per strategy (from the
// logs, read once by the analysis). They are computed in metrics (feint/metrics/mean_trace.hpp);
// the plot module draws them and never reads a file.
#pragma once

#include "feint/metrics/mean_trace.hpp"

namespace feint::analysis {

using metrics::kTracePoints;
using metrics::mean_traces;
using metrics::read_trial_labels;
using metrics::TraceCurve;
using metrics::TrialLabel;

}  // namespace feint::analysis

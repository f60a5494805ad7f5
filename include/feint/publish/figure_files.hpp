// feint/publish/figure_files.hpp - one figure of `feint plot`: read the scores file (or the
// questionnaire, and the logs for the traces), compute its data with the analysis functions,
// and draw it with feint/plot.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "feint/analysis/settings.hpp"
#include "feint/plot/canvas.hpp"

namespace feint::publish {

struct FigureRequest {
  std::string input;   ///< scores CSV, or questionnaire CSV (likert, likert-means)
  std::string figure;  ///< a metric column, participants, strategies, traces, likert, likert-means
  std::vector<std::string> metrics;  ///< NAME=REF (default error=0.5 confusion=0.95)
  std::string compare;               ///< "A,B": mark the iterations where A differs from B
  bool var_equal = false;
  bool paired = false;
  std::vector<std::string> logs;  ///< pad-trace logs (traces)
  std::string scale = "1-7";      ///< questionnaire scale
  std::optional<double> reference;
  std::vector<std::string> items;
};

/// Throws UsageError for an unknown figure or a missing --logs, InvalidData for bad files.
plot::Figure figure_from_files(const FigureRequest& request,
                               const analysis::ResolvedReportOptions& tests);

}  // namespace feint::publish

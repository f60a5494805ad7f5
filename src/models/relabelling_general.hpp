// Relabelling p-values for the designs the two-condition fast refit (relabelling_refit.hpp) does
// not cover: the conditions within participants (each participant's conditions permuted among
// themselves, all of a condition's trials moving together), and three or more conditions between
// participants (whole participants permuted between the conditions, group sizes kept). Each
// labelling is a dense REML refit of both random-intercept models in the cell-means
// parametrisation; see feint/models/model_relabelling.hpp for the method.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "feint/models/model_relabelling.hpp"

namespace feint::models::detail {

/// The relabelling p-values of `data` under `options.within` (swaps within participants) or
/// between participants with any number (>= 2) of conditions `group_levels`.
RelabelledConditionTests relabel_general(const LongData& data, const std::vector<std::string>& group_levels,
                                         const RelabellingOptions& options);

/// Just below the observed statistic `s`, so that a relabelling reaching it counts toward the p-value;
/// infinity when the observed statistic is missing. The margin, 1e-6 relative (absolute below 1),
/// is wider than the fits' precision: Brent stops theta at 26 bits, which moves F and t by about
/// 1e-8 relative, so a labelling that ties the observed one exactly (e.g. the mirror swap of a
/// within design) would otherwise be missed now and then, and p would fall short by one labelling.
double relabelling_threshold(const std::optional<double>& s);

}  // namespace feint::models::detail

// feint/metrics/trial_layout.hpp - the map of one trial of a log of K targets and a pointer.
#pragma once

#include "feint/io/trace.hpp"
#include "feint/metrics/layout.hpp"

namespace feint::metrics {

/// The trial's layout as its log wrote it: the start (start_x, start_y) and the targets
/// (target0_x, target0_y, ...), unchecked (validate() and the scorers check it).
Layout trial_layout(const io::Trial& t);

}  // namespace feint::metrics

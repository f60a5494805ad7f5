// feint/tables/observer_render.hpp - the goal-inference observer fitted to pad-trace logs (`feint
// observer fit`; docs/observer.md) as text or JSON: per-participant and pooled fits with their
// profile-likelihood CIs, the learning test, model-human agreement and the trials left out.
#pragma once

#include <string>

#include "feint/models/observer_fit.hpp"
#include "feint/sim/observer_logs.hpp"

namespace feint::tables {

/// Aligned text tables; `settings` are the fit's (noise, thinning, level, whether the prior was
/// fitted), stated in the first line and in the columns.
std::string render_observer_fit_text(const sim::ObserverLogFit& fit,
                                     const models::ObserverFitSettings& settings);

/// One JSON object: method, path, conf.level, participants, conditions, learning, agreement,
/// issues.
std::string render_observer_fit_json(const sim::ObserverLogFit& fit,
                                     const models::ObserverFitSettings& settings);

}  // namespace feint::tables

// feint/tables/observer_render.hpp - the goal-inference observer fitted to pad-trace logs (`feint
// observer fit`; docs/observer.md) as text or JSON: per-participant and pooled fits with their
// profile-likelihood CIs, the learning test, model-human agreement and the trials left out; and
// the K-goal observer fitted to pointer logs (its fits, learning test, model-human agreement on the
// pointer, comparisons and trials left out). Each
// output names its model: JSON "model" is "pad" or "pointer".
#pragma once

#include <string>

#include "feint/models/observer_fit.hpp"
#include "feint/models/pointer_observer_fit.hpp"
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

/// The K-goal observer fitted to pointer logs (models::fit_pointer_study), as text: the model
/// (targets, layouts, noise, sigma in layout scales) in the first line, then the fits, the learning
/// test and the agreement table (the pad's columns, in layout scales).
/// `rejected_rows` trials were left out while reading; `path_source` says where the paths came from.
std::string render_pointer_observer_fit_text(const models::PointerStudyObserverFit& fit,
                                             const models::ObserverFitSettings& settings, std::size_t rejected_rows,
                                             const std::string& path_source);

/// The same as one JSON object: model ("pointer"), method, noise, targets (min, max), layouts,
/// sigma.unit, path, conf.level, participants, conditions, learning, agreement (the pad's keys),
/// comparisons, issues.
std::string render_pointer_observer_fit_json(const models::PointerStudyObserverFit& fit,
                                             const models::ObserverFitSettings& settings,
                                             const std::string& path_source);

}  // namespace feint::tables

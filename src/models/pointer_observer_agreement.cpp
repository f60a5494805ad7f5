// Model-human agreement of the K-goal observer fitted to pointer traces
// (feint/models/pointer_observer_fit.hpp, docs/observer.md "Agreement and learning on pointer
// traces"): the model's mean at each participant's fit is a belief-point trace, scored as the
// pointer is; the cells and their sums are the pad's (observer_study_detail.hpp).
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/metrics/belief_point.hpp"
#include "feint/models/pointer_observer_fit.hpp"
#include "observer_study_detail.hpp"

namespace feint::models {

namespace {

/// Distance of each point to `goal`, in layout scales `scale`.
std::vector<double> distances(std::span<const metrics::MapPoint> points, metrics::MapPoint goal, double scale) {
  std::vector<double> out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back(std::hypot(p.x - goal.x, p.y - goal.y) / scale);
  return out;
}

}  // namespace

std::vector<AgreementRow> pointer_agreement(std::span<const PointerObservedTrial> trials,
                                            std::span<const ObserverFit> participants,
                                            const ObserverFitSettings& settings, std::vector<TrialIssue>& issues) {
  std::map<std::pair<std::string, std::string>, std::pair<double, double>> fitted;  // (beta, tau)
  for (const auto& f : participants)
    fitted[{f.condition, f.unit}] = {f.parameter("beta").estimate, f.parameter("tau").estimate};
  detail::observer::AgreementCells cells;
  for (const auto& tr : trials) {
    const auto it = fitted.find({tr.condition, tr.participant});
    if (it == fitted.end()) continue;  // the participant's fit failed (named in the issues already)
    std::vector<metrics::MapPoint> human(tr.times.size());
    for (std::size_t i = 0; i < human.size(); ++i) human[i] = {tr.x[i], tr.y[i]};
    const double v = tr.pointer_speed.value_or(settings.pad_speed);
    std::vector<metrics::MapPoint> model;
    metrics::BeliefPointScore hs, ms;
    try {
      model = pointer_observer_means(tr, it->second.first, it->second.second);
      hs = metrics::score_belief_points(tr.times, human, tr.layout, tr.target, v, settings.metric);
      ms = metrics::score_belief_points(tr.times, model, tr.layout, tr.target, v, settings.metric);
    } catch (const Error& e) {
      issues.push_back({tr.label, fmt::format("left out of the agreement tables: {}", e.what())});
      continue;
    }
    const metrics::MapPoint goal = tr.layout.targets[tr.target];
    const double scale = metrics::layout_scale(tr.layout);
    const std::vector<double> hd = distances(human, goal, scale), md = distances(model, goal, scale);
    cells.add(tr.condition, tr.strategy, tr.iteration, {hs.error, ms.error, hs.confusion, ms.confusion, hd, md});
  }
  return cells.rows();
}

}  // namespace feint::models

// The map's data: the canonical frame of a trial, the mean paths, and the logs streamed into them
// (see feint/metrics/mean_map.hpp).
#include "feint/metrics/mean_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "feint/error.hpp"
#include "feint/io/pointer_trace.hpp"
#include "feint/metrics/pointer_measures.hpp"
#include "feint/metrics/trial_layout.hpp"

namespace feint::metrics {

MapPoint CanonicalFrame::operator()(MapPoint p) const noexcept {
  const double vx = p.x - start.x, vy = p.y - start.y;
  const double d2 = direction.x * direction.x + direction.y * direction.y;
  const double x = (vx * direction.y - vy * direction.x) / d2;
  const double y = (vx * direction.x + vy * direction.y) / d2;
  return {mirrored ? -x : x, y};
}

CanonicalFrame canonical_frame(const Layout& layout, std::size_t true_target) {
  if (true_target >= layout.targets.size()) {
    throw InvalidData(fmt::format("true target {} is not a target of the layout (K = {})",
                                  true_target, layout.targets.size()));
  }
  const MapPoint g = layout.targets[true_target];
  CanonicalFrame f{layout.start, {g.x - layout.start.x, g.y - layout.start.y}, false};
  const double d2 = f.direction.x * f.direction.x + f.direction.y * f.direction.y;
  if (!(d2 > 0) || !std::isfinite(d2)) {
    throw InvalidData(fmt::format(
        "true target {} ({:g}, {:g}) is at the start or not a finite point: no frame to map it to",
        true_target, g.x, g.y));
  }
  // The decoy nearest in bearing: the one a feint toward is hardest to tell from the true target.
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < layout.targets.size(); ++k) {
    if (k == true_target) continue;
    const MapPoint c = f(layout.targets[k]);
    const double bearing = std::fabs(std::atan2(c.x, c.y));
    if (bearing < best) {
      best = bearing;
      f.mirrored = c.x > 0;
    }
  }
  return f;
}

std::vector<MapPoint> normalised_path(const std::vector<double>& times,
                                      const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != times.size() || y.size() != times.size()) {
    throw InvalidData(fmt::format("a path of {} times has {} x and {} y positions", times.size(),
                                  x.size(), y.size()));
  }
  std::vector<PointerSample> trace(times.size());
  for (std::size_t i = 0; i < times.size(); ++i) trace[i] = {times[i], x[i], y[i]};
  const auto norm = time_normalize(trace, static_cast<int>(kMapPoints));
  std::vector<MapPoint> out(norm.size());
  for (std::size_t i = 0; i < norm.size(); ++i) out[i] = {norm[i].x, norm[i].y};
  return out;
}

namespace {

std::vector<double> flattened(const Layout& l) {
  std::vector<double> v = {l.start.x, l.start.y};
  for (const auto& t : l.targets) {
    v.push_back(t.x);
    v.push_back(t.y);
  }
  return v;
}

template <typename Map>
void add_path(std::vector<MapPoint>& sum, const std::vector<MapPoint>& path, const Map& map) {
  for (std::size_t i = 0; i < kMapPoints; ++i) {
    const MapPoint p = map(path[i]);
    sum[i].x += p.x;
    sum[i].y += p.y;
  }
}

// One trial's paths (the robot's may be empty) into a group's sums, through `map`.
template <typename Sums, typename Map>
void add_sums(Sums& sums, const std::vector<MapPoint>& pointer, const std::vector<MapPoint>& robot,
              const Map& map) {
  ++sums.n;
  add_path(sums.pointer, pointer, map);
  if (robot.empty()) return;
  ++sums.n_robot;
  add_path(sums.robot, robot, map);
}

std::vector<MapPoint> divided(const std::vector<MapPoint>& sum, std::size_t n) {
  std::vector<MapPoint> out(sum.size());
  const auto d = static_cast<double>(n);
  for (std::size_t i = 0; i < sum.size(); ++i) out[i] = {sum[i].x / d, sum[i].y / d};
  return out;
}

}  // namespace

void MapAccumulator::add(const MapTrial& t) {
  const bool robot = !t.robot_x.empty() || !t.robot_y.empty();
  // Every check before anything is added: a refused trial leaves the sums as they were.
  const CanonicalFrame frame = canonical_frame(t.layout, t.true_target);
  const std::vector<MapPoint> pointer = normalised_path(t.times, t.pointer_x, t.pointer_y);
  const std::vector<MapPoint> robot_path =
      robot ? normalised_path(t.times, t.robot_x, t.robot_y) : std::vector<MapPoint>{};
  add_sums(metres_[{t.strategy, t.variant, t.true_target}], pointer, robot_path,
           [](MapPoint p) { return p; });
  add_sums(canonical_[{t.strategy, t.variant, 0}], pointer, robot_path, frame);
  auto& decoys = decoys_[{t.strategy, t.variant}];
  for (std::size_t k = 0; k < t.layout.targets.size(); ++k) {
    if (k != t.true_target) decoys.push_back(frame(t.layout.targets[k]));
  }
  if (trials_ == 0) first_ = t.layout;
  layouts_.insert(flattened(t.layout));
  targets_ = std::max(targets_, t.layout.targets.size());
  ++trials_;
  if (frame.mirrored) ++mirrored_;
}

MeanMap MapAccumulator::data() const {
  MeanMap d;
  d.canonical = layouts_.size() > 1;
  d.targets = targets_;
  d.layouts = layouts_.size();
  d.trials = trials_;
  d.mirrored = d.canonical ? mirrored_ : 0;
  d.layout = d.canonical ? Layout{{0, 0}, {{0, 1}}} : first_;
  // The maps are ordered by (strategy, version, target): a panel's means are consecutive.
  for (const auto& [key, s] : d.canonical ? canonical_ : metres_) {
    const auto& [strategy, variant, target] = key;
    if (d.panels.empty() || d.panels.back().strategy != strategy ||
        d.panels.back().variant != variant) {
      MapPanel p;
      p.strategy = strategy;
      p.variant = variant;
      if (d.canonical) p.decoys = decoys_.at({strategy, variant});
      d.panels.push_back(std::move(p));
    }
    MapMean m;
    m.true_target = target;
    m.trials = s.n;
    m.robot_trials = s.n_robot;
    m.pointer = divided(s.pointer, s.n);
    if (s.n_robot > 0) m.robot = divided(s.robot, s.n_robot);
    d.panels.back().trials += s.n;
    d.panels.back().means.push_back(std::move(m));
  }
  return d;
}

MapTrial map_trial(io::Trial&& t) {
  MapTrial m;
  m.strategy = std::move(t.strategy);
  m.variant = std::move(t.variant);
  m.layout = trial_layout(t);
  m.true_target = t.target_index;
  m.times = std::move(t.times);
  m.pointer_x = std::move(t.belief_x);
  m.pointer_y = std::move(t.belief_y);
  m.robot_x = std::move(t.robot_x);
  m.robot_y = std::move(t.robot_y);
  return m;
}

std::optional<MeanMap> mean_map(const std::vector<std::string>& log_files, io::TraceOptions options,
                                const io::ScoresTable& scored) {
  if (log_files.empty() || !io::is_pointer_log(log_files.front(), options)) return std::nullopt;
  std::set<std::tuple<std::string, std::string, long long>> keys;
  for (const auto& s : scored.records) keys.emplace(s.participant, s.condition, s.iteration);
  options.on_reject = [](const io::Rejection&) {};  // rejected when scored: not in `scored`
  io::PointerTraceReader reader(log_files, std::move(options));
  MapAccumulator map;
  io::Trial t;
  while (reader.next(t)) {
    if (keys.count({t.participant, t.condition, t.iteration}) != 0) {
      map.add(map_trial(std::move(t)));
    }
  }
  return map.data();
}

}  // namespace feint::metrics

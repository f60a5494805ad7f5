// The map of a study with K targets: the fixed layout, the random layouts drawn per round, the
// map's bounds, the pointer log's header, and the checks of these settings (docs/collect.md
// "Many targets and a pointer").
#include <fmt/format.h>

#include <algorithm>

#include "feint/collect/study.hpp"
#include "feint/error.hpp"
#include "feint/rng.hpp"
#include "feint/sim/k_goal_paths.hpp"
#include "participant.hpp"

namespace feint::collect {

namespace detail {

namespace {

// A pointer study's round (participant i, kind, iteration) draws its layout from stream
// kLayoutStream + key and, for K > 2, its true target from kTargetStream + key (key below): far
// from the streams of study.cpp (assignment blocks, runs, practice), one stream per round, so a restart draws the same layouts.
constexpr std::uint64_t kLayoutStream = std::uint64_t{1} << 40;
constexpr std::uint64_t kTargetStream = std::uint64_t{1} << 41;
std::uint64_t round_key(std::size_t index, RoundKind kind, int iteration) {
  return static_cast<std::uint64_t>(index) * 2048 + (kind == RoundKind::practice ? 1024 : 0) +
         static_cast<std::uint64_t>(iteration);
}

}  // namespace

void place_round(Round& r, const Settings& s, std::size_t index) {
  if (s.belief == BeliefInput::pad) {
    r.layout = metrics::paper_layout(s.geometry.target_distance, s.geometry.target_height);
    r.target_index = r.target == sim::Target::left ? 0 : 1;
    return;
  }
  const std::uint64_t key = round_key(index, r.kind, r.iteration);
  if (s.layout == LayoutMode::random) {
    Rng rng = Rng::stream(s.seed, kLayoutStream + key);
    r.layout = metrics::draw_layout(rng, s.region, s.targets);
  } else {
    r.layout = fixed_layout(s);
  }
  if (s.targets == 2) {
    r.target_index = r.target == sim::Target::left ? 0 : 1;
  } else {
    Rng rng = Rng::stream(s.seed, kTargetStream + key);
    r.target_index = rng.bounded(static_cast<std::uint32_t>(s.targets));
  }
  sim::KGoalPathSettings ks;
  ks.geometry = s.geometry;
  r.waypoints = sim::k_goal_waypoints(r.layout, r.target_index, r.strategy, r.variant, ks);
  r.path = sim::k_goal_trajectory(r.layout, r.target_index, r.strategy, r.variant, ks);
}

void validate_design(const Settings& s) {
  if (s.targets < 2 || s.targets > 26) throw UsageError("targets must be in [2, 26]");
  if (s.belief == BeliefInput::pad && s.targets != 2) {
    throw UsageError(fmt::format(
        "--targets {}: the pad shows a belief between two targets only; use --belief pointer",
        s.targets));
  }
  if (s.belief == BeliefInput::pad && s.layout == LayoutMode::random) {
    throw UsageError("--layout random: the pad needs the paper's fixed layout; use --belief pointer");
  }
  if (s.belief == BeliefInput::pointer) {
    metrics::validate(s.region);
    if (s.layout == LayoutMode::fixed) {
      try {
        metrics::validate(collect::fixed_layout(s), s.region.min_spacing,
                          s.region.min_start_distance);
      } catch (const UsageError& e) {
        throw UsageError(fmt::format(
            "--targets {} in a row of --target-distance {} m: {}; widen the row, or use "
            "--layout random",
            s.targets, s.geometry.target_distance, e.what()));
      }
    } else {
      Rng probe = Rng::stream(s.seed, kLayoutStream);  // an impossible region fails here, at start
      (void)metrics::draw_layout(probe, s.region, s.targets);
    }
  }
}

}  // namespace detail

metrics::Layout fixed_layout(const Settings& s) {
  metrics::Layout l;
  const double d = s.geometry.target_distance, h = s.geometry.target_height;
  const double k = static_cast<double>(s.targets);
  for (std::size_t i = 0; i < s.targets; ++i)
    l.targets.push_back({-d / 2 + d * static_cast<double>(i) / (k - 1), h});
  return l;
}

MapBounds map_bounds(const Settings& s) {
  MapBounds b;
  if (s.layout == LayoutMode::random) {
    b = {s.region.x_min, s.region.x_max, s.region.y_min, s.region.y_max};
  } else {
    const auto l = fixed_layout(s);
    b = {l.targets.front().x, l.targets.back().x, s.geometry.target_height,
         s.geometry.target_height};
  }
  b = {std::min(b.x_min, 0.0) - 1, std::max(b.x_max, 0.0) + 1, std::min(b.y_min, 0.0) - 1,
       std::max(b.y_max, 0.0) + 1};
  return b;
}

std::string log_header(const Settings& s) {
  if (s.belief == BeliefInput::pad) return std::string(detail::kLogHeader);
  std::string h = "participant,condition,iteration,strategy,variant,target,t,belief_x,belief_y,"
                  "start_x,start_y";
  for (std::size_t k = 0; k < s.targets; ++k) h += fmt::format(",target{0}_x,target{0}_y", k);
  return h + ",robot_x,robot_y\n";
}

}  // namespace feint::collect

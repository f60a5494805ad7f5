// Deceptiveness measures of a robot path (feint/models/deceptiveness.hpp, docs/observer.md).
#include "feint/models/deceptiveness.hpp"

#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::models {

void validate_path(std::span<const PathSample> path) {
  if (path.size() < 2) {
    throw InvalidData(fmt::format("the robot path has {} sample(s); at least 2 are needed", path.size()));
  }
  for (std::size_t i = 0; i < path.size(); ++i) {
    const auto& s = path[i];
    if (!std::isfinite(s.t) || !std::isfinite(s.x) || !std::isfinite(s.y)) {
      throw InvalidData(fmt::format("robot path sample {} is not finite (t = {}, x = {}, y = {})", i + 1,
                                    s.t, s.x, s.y));
    }
    if (i > 0 && !(s.t > path[i - 1].t)) {
      throw InvalidData(fmt::format("robot path times must increase strictly: sample {} has t = {} after "
                                    "t = {}", i + 1, s.t, path[i - 1].t));
    }
  }
  if (!(path.back().t - path.front().t > 0)) {
    throw InvalidData("the robot path has zero duration");
  }
  const auto len = arc_lengths(path);
  if (!(len.back() > 0)) {
    throw InvalidData(fmt::format("the robot path never moves (every sample at ({}, {})): it carries no "
                                  "information about the goal",
                                  path.front().x, path.front().y));
  }
}

std::vector<double> arc_lengths(std::span<const PathSample> path) {
  std::vector<double> s(path.size(), 0.0);
  for (std::size_t i = 1; i < path.size(); ++i) {
    s[i] = s[i - 1] + std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
  }
  return s;
}

namespace {

void validate_pad_speed(double pad_speed) {
  if (!(pad_speed > 0) || !std::isfinite(pad_speed)) {
    throw UsageError(
        fmt::format("pad speed = {} is invalid: expected a finite number > 0 (pad units per "
                    "second)",
                    pad_speed));
  }
}

// Duration, lengths and the cost overhead of the path against the straight line.
void measure_lengths(std::span<const PathSample> path, const Position& start,
                     const std::vector<double>& arc, DeceptivenessMeasures& m) {
  const double t0 = path.front().t;
  m.duration = path.back().t - t0;
  m.path_length = arc.back();
  m.straight_length = std::hypot(path.back().x - start.x, path.back().y - start.y);
  if (!(m.straight_length > 0)) {
    throw InvalidData("the robot path ends where it started: the straight-line cost is 0, so the cost "
                      "overhead is undefined");
  }
  m.cost_overhead = m.path_length / m.straight_length - 1;
}

// p_i = P(G* | path up to sample i), no delay.
std::vector<double> goal_beliefs(std::span<const PathSample> path, const Position& start,
                                 bool right, const DeceptivenessSettings& settings) {
  const std::size_t n = path.size();
  std::vector<double> p(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double b = belief_right(start, {path[i].x, path[i].y}, settings.goals, settings.observer.beta,
                                  settings.observer.prior_right);
    p[i] = right ? b : 1.0 - b;
  }
  return p;
}

// Legibility: trapezoids of p f, divided by int f = T^2 / 2 (exact for the linear f); and the share
// of time deceived, both in one pass over the pieces.
void measure_legibility(std::span<const PathSample> path, const std::vector<double>& p,
                        DeceptivenessMeasures& m) {
  const std::size_t n = path.size();
  const double t0 = path.front().t;
  const double T = m.duration;
  double num = 0, deceived = 0;
  for (std::size_t i = 1; i < n; ++i) {
    const double dt = path[i].t - path[i - 1].t;
    const double f0 = T - (path[i - 1].t - t0), f1 = T - (path[i].t - t0);
    num += (p[i - 1] * f0 + p[i] * f1) / 2 * dt;
    // Time with p < 1/2 on the linear piece (a tie is not deceived).
    const double d0 = p[i - 1] - 0.5, d1 = p[i] - 0.5;
    if (d0 < 0 && d1 < 0) deceived += dt;
    else if (d0 < 0 && d1 >= 0) deceived += dt * (-d0) / (d1 - d0);
    else if (d0 >= 0 && d1 < 0) deceived += dt * (-d1) / (d0 - d1);
  }
  m.legibility = num / (T * T / 2);
  m.time_deceived = deceived / T;
}

// Last deceptive point: the last sample that is not truthful (p <= 1/2), then where p crosses 1/2
// on the next piece, as a share of the path length.
double last_deceptive_point(const std::vector<double>& p, const std::vector<double>& arc,
                            double path_length) {
  const std::size_t n = p.size();
  std::optional<std::size_t> last;
  for (std::size_t i = n; i-- > 0;) {
    if (p[i] - 0.5 <= 0) {
      last = i;
      break;
    }
  }
  if (!last) return 0;
  if (*last == n - 1) return 1;
  const std::size_t k = *last;
  const double d0 = p[k] - 0.5, d1 = p[k + 1] - 0.5;  // d0 <= 0 < d1
  const double frac = -d0 / (d1 - d0);
  return (arc[k] + frac * (arc[k + 1] - arc[k])) / path_length;
}

// Error and confusion of the delayed belief trace, scored as a pad.
void score_belief_trace(std::span<const PathSample> path, bool right,
                        const DeceptivenessSettings& settings, DeceptivenessMeasures& m) {
  const std::size_t n = path.size();
  std::vector<double> times(n);
  for (std::size_t i = 0; i < n; ++i) times[i] = path[i].t;
  const auto b = belief_trace(path, times, settings.goals, settings.observer);
  metrics::MetricSettings ms = settings.metric;
  ms.pad_speed.reset();
  const auto score = metrics::score_trace(times, b, right ? 1.0 : 0.0, settings.pad_speed, ms);
  m.belief_error = score.error;
  m.belief_confusion = score.confusion;
  m.belief_overspeed_segments = score.overspeed_segments;
}

}  // namespace

DeceptivenessMeasures deceptiveness(std::span<const PathSample> path, GoalSide goal,
                                    const DeceptivenessSettings& settings) {
  validate(settings.observer);
  validate_pad_speed(settings.pad_speed);
  validate_path(path);
  const Position start{path.front().x, path.front().y};
  const auto arc = arc_lengths(path);
  const bool right = goal == GoalSide::right;

  DeceptivenessMeasures m;
  measure_lengths(path, start, arc, m);
  const auto p = goal_beliefs(path, start, right, settings);
  m.final_belief = p.back();
  measure_legibility(path, p, m);
  m.last_deceptive_point = last_deceptive_point(p, arc, m.path_length);
  score_belief_trace(path, right, settings, m);
  return m;
}

}  // namespace feint::models

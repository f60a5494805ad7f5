// The simulated observer (see feint/sim/observer.hpp and docs/simulation.md).
#include "feint/sim/observer.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/models/goal_inference.hpp"

namespace feint::sim {

void validate(const ObserverParams& p) {
  auto nonneg = [](double v, const char* name) {
    if (!(v >= 0) || !std::isfinite(v)) throw UsageError(fmt::format("observer: {} must be >= 0, got {}", name, v));
  };
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw UsageError(fmt::format("observer: {} must be > 0, got {}", name, v));
  };
  nonneg(p.reaction_delay, "reaction_delay");
  positive(p.decision_interval, "decision_interval");
  nonneg(p.noise_sd, "noise_sd");
  positive(p.pad_speed, "pad_speed");
  nonneg(p.move_threshold, "move_threshold");
  positive(p.inference_gain, "inference_gain");
  positive(p.half_familiarity, "half_familiarity");
  positive(p.learning_shape, "learning_shape");
  positive(p.recognition_time, "recognition_time");
  positive(p.capture_radius, "capture_radius");
  nonneg(p.beta, "beta");
  nonneg(p.recognition_logodds, "recognition_logodds");
  if (!(p.memory_decay >= 0 && p.memory_decay <= 1)) {
    throw UsageError(fmt::format("observer: memory_decay must be in [0, 1], got {}", p.memory_decay));
  }
  if (!(p.optimal_suspicion >= 0 && p.optimal_suspicion <= 1)) {
    throw UsageError(fmt::format("observer: optimal_suspicion must be in [0, 1], got {}", p.optimal_suspicion));
  }
}

namespace {
struct NamedParameter {
  std::string_view name;
  double ObserverParams::*field;
};
constexpr NamedParameter kParameters[] = {
    {"beta", &ObserverParams::beta},
    {"recognition_logodds", &ObserverParams::recognition_logodds},
    {"reaction_delay", &ObserverParams::reaction_delay},
    {"decision_interval", &ObserverParams::decision_interval},
    {"noise_sd", &ObserverParams::noise_sd},
    {"pad_speed", &ObserverParams::pad_speed},
    {"move_threshold", &ObserverParams::move_threshold},
    {"inference_gain", &ObserverParams::inference_gain},
    {"half_familiarity", &ObserverParams::half_familiarity},
    {"learning_shape", &ObserverParams::learning_shape},
    {"memory_decay", &ObserverParams::memory_decay},
    {"recognition_time", &ObserverParams::recognition_time},
    {"optimal_suspicion", &ObserverParams::optimal_suspicion},
    {"capture_radius", &ObserverParams::capture_radius},
};
}  // namespace

ObserverParams goal_inference_observer() noexcept {
  ObserverParams p;
  p.model = ParticipantModel::goal_inference;
  p.beta = 0.3;
  p.recognition_logodds = 5.0;
  p.half_familiarity = 4.0;
  return p;
}

void set_parameter(ObserverParams& p, std::string_view key, double value) {
  for (const auto& np : kParameters) {
    if (np.name == key) {
      p.*(np.field) = value;
      return;
    }
  }
  std::string names;
  for (const auto& np : kParameters) names += fmt::format("{}{}", names.empty() ? "" : ", ", np.name);
  throw UsageError(fmt::format("unknown observer parameter '{}': expected one of {}", key, names));
}

namespace {
std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}
}  // namespace

void set_parameter(ObserverParams& p, std::string_view assignment) {
  const auto eq = assignment.find('=');
  const auto value = eq == std::string_view::npos ? std::nullopt
                                                  : io::parse_double(trim(assignment.substr(eq + 1)));
  if (!value) {
    throw UsageError(fmt::format("observer parameter '{}': expected NAME=NUMBER, e.g. beta=0.3", assignment));
  }
  set_parameter(p, trim(assignment.substr(0, eq)), *value);
}

void read_parameters(ObserverParams& p, const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError(fmt::format("{}: cannot open the observer parameter file", path));
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto hash = line.find('#');
    const std::string_view text = trim(std::string_view(line).substr(0, hash));
    if (text.empty()) continue;
    try {
      set_parameter(p, text);
    } catch (const UsageError& e) {
      throw UsageError(fmt::format("{}:{}: {}", path, number, e.what()));
    }
  }
}

ParticipantModel parse_participant_model(std::string_view name) {
  if (name == "heuristic") return ParticipantModel::heuristic;
  if (name == "goal-inference" || name == "goal_inference") return ParticipantModel::goal_inference;
  throw UsageError(fmt::format("participant model '{}': expected heuristic or goal-inference", name));
}

std::string_view to_string(ParticipantModel m) noexcept {
  return m == ParticipantModel::heuristic ? "heuristic" : "goal-inference";
}

Observer::Observer(ObserverParams params) : params_(params) { validate(params_); }

namespace {
std::size_t slot(Strategy s, Variant v) noexcept {
  return static_cast<std::size_t>(s) * 2 + static_cast<std::size_t>(v);
}
constexpr double kGrid = 1e4;  // pad positions are whole multiples of 1e-4

/// Robot position at time t (linear between samples; the start before t = 0).
Point position_at(const std::vector<TrajectorySample>& path, double t) noexcept {
  if (t <= path.front().t) return {path.front().x, path.front().y};
  if (t >= path.back().t) return {path.back().x, path.back().y};
  const auto it = std::upper_bound(path.begin(), path.end(), t,
                                   [](double v, const TrajectorySample& s) { return v < s.t; });
  const auto& b = *it;
  const auto& a = *(it - 1);
  const double f = (t - a.t) / (b.t - a.t);
  return {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)};
}
}  // namespace

double Observer::familiarity(Strategy s, Variant v) const noexcept {
  // Hill curve: learning needs a few exposures before it pays (convex start), then saturates.
  const double m = std::pow(memory_[slot(s, v)], params_.learning_shape);
  return m / (m + std::pow(params_.half_familiarity, params_.learning_shape));
}

Recognition Observer::recognition(Strategy s, Variant v) const noexcept {
  // Familiarity with the seen version argues for the true target, familiarity with the other
  // version (for optimal: with exaggerating, which starts alike) for the false one.
  const double f_same = familiarity(s, v);
  const double f_other = s == Strategy::optimal
                             ? params_.optimal_suspicion * familiarity(Strategy::exaggerating, Variant::main)
                             : familiarity(s, v == Variant::main ? Variant::v2 : Variant::main);
  return {f_same, f_other};
}

double recognition_progress(const ObserverParams& p, double t) noexcept {
  return std::clamp((t - p.reaction_delay) / p.recognition_time, 0.0, 1.0);
}

double learned_logodds(const ObserverParams& p, const Recognition& rec, double r) noexcept {
  return p.recognition_logodds * r * (rec.f_same - rec.f_other);
}

void Observer::remember(Strategy s, Variant v) noexcept {
  for (auto& m : memory_) m *= params_.memory_decay;
  memory_[slot(s, v)] += 1.0;
}

std::vector<PadSample> Observer::watch(const std::vector<TrajectorySample>& path, Strategy s,
                                       Variant v, Target true_target, const Geometry& g,
                                       Rng& rng) const {
  const auto& P = params_;
  const double T = true_target == Target::left ? 0.0 : 1.0;
  // Recognition weights (see the header): the heuristic mixes the endings with them, the
  // goal-inference observer shifts its log-odds by them.
  const Recognition rec = recognition(s, v);
  const double w_same = rec.f_same;
  const double w_other = rec.f_other * (1 - w_same);
  const double half = g.target_distance / 2;
  const models::Goals goals{{-half, g.target_height}, {half, g.target_height}};
  const models::Position start{path.front().x, path.front().y};
  auto bayes_belief = [&](double t) {
    // Path evidence in log-odds (feint/models/goal_inference.hpp), plus the learned prior: a
    // recognised strategy shifts the log-odds toward the target its ending is remembered to reach.
    const Point seen = position_at(path, t - P.reaction_delay);
    const double r = recognition_progress(P, t);
    const double toward_true = 2 * T - 1;
    const double learned = learned_logodds(P, rec, r) * toward_true;
    const double z = models::belief_logit(start, {seen.x, seen.y}, goals, P.beta, 0.5) + learned;
    return z >= 0 ? 1 / (1 + std::exp(-z)) : std::exp(z) / (1 + std::exp(z));
  };
  auto belief = [&](double t) {
    if (P.model == ParticipantModel::goal_inference) return bayes_belief(t);
    const Point seen = position_at(path, t - P.reaction_delay);
    const double naive = 0.5 + 0.5 * std::tanh(P.inference_gain * seen.x / half);
    const double r = recognition_progress(P, t);
    double b = (1 - r * (w_same + w_other)) * naive + r * w_same * T + r * w_other * (1 - T);
    const double dl = std::hypot(seen.x + half, seen.y - g.target_height);
    const double dr = std::hypot(seen.x - half, seen.y - g.target_height);
    const double c = std::clamp(1 - std::min(dl, dr) / P.capture_radius, 0.0, 1.0);
    return (1 - c) * b + c * (dl < dr ? 0.0 : 1.0);
  };

  std::vector<PadSample> out;
  out.reserve(path.size());
  long pad = static_cast<long>(0.5 * kGrid);
  long goal = pad;
  const long threshold = std::lround(P.move_threshold * kGrid);
  double next_decision = 0;
  double prev_t = path.front().t;
  for (const auto& smp : path) {
    const double dt = smp.t - prev_t;
    prev_t = smp.t;
    // move during (prev_t, t] toward the current goal at pad speed (whole grid steps only, so the
    // logged trace never exceeds the stated speed)
    if (std::labs(goal - pad) > threshold) {
      const long max_step = static_cast<long>(std::floor(P.pad_speed * dt * kGrid + 1e-9));
      const long diff = goal - pad;
      pad += diff > 0 ? std::min(max_step, diff) : -std::min(max_step, -diff);
    }
    out.push_back({smp.t, static_cast<double>(pad) / kGrid});
    if (smp.t >= next_decision) {
      const double noisy = std::clamp(belief(smp.t) + P.noise_sd * rng.normal(), 0.0, 1.0);
      goal = std::lround(noisy * kGrid);
      next_decision += P.decision_interval;
      while (next_decision <= smp.t) next_decision += P.decision_interval;
    }
  }
  return out;
}

}  // namespace feint::sim

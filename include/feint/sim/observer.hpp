// feint/sim/observer.hpp - a simulated study participant who watches trajectories and moves the pad.
//
// The model (docs/simulation.md, "The simulated observer"):
//   * Goal inference. A naive observer believes the robot goes where it is: its belief in the right
//     target is n = 0.5 + 0.5 tanh(inference_gain * x / (d/2)) of the robot's position x seen
//     `reaction_delay` seconds ago.
//   * Memory. A trace m per (strategy, version): after each trial every trace decays (m *= memory_decay)
//     and the seen one gains 1. Familiarity f = m^a / (m^a + half^a) (a Hill curve: a few exposures
//     are needed before learning pays, then it saturates): it grows with how often and how recently a
//     strategy was seen.
//   * Recognition. A familiar strategy is recognised: with weight w_same = f(seen version) the observer
//     expects the true target; with weight w_other = f(other version) (1 - w_same) it expects the other
//     version's ending, i.e. the false target (familiarity with the main strategy is what a v2 exploits).
//     For the optimal strategy, w_other = optimal_suspicion f(exaggerating, main) (1 - w_same): it
//     looks like the start of an exaggeration. Recognition grows linearly over `recognition_time`
//     seconds after the reaction delay: goal = (1 - R) n + r w_same T + r w_other (1 - T), R = r (w_same + w_other).
//   * The end is visible: within `capture_radius` metres of a target, belief moves linearly to it.
//   * Action. Every `decision_interval` seconds the observer picks a pad goal = belief + N(0, noise_sd),
//     clamped to [0, 1], and moves the pad toward it at `pad_speed` while it is farther than
//     `move_threshold` (a key is held, or not). The pad starts at 0.5 and stays in [0, 1].
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "feint/rng.hpp"
#include "feint/sim/selection.hpp"
#include "feint/sim/trajectory.hpp"

namespace feint::sim {

/// How a simulated participant infers the robot's goal from the path seen so far.
///   heuristic       the naive tanh of the robot's x (feint 0.1's model; kept for comparison);
///   goal_inference  the Bayesian goal-inference observer of feint/models/goal_inference.hpp
///                   (Dragan & Srinivasa 2013): P(right | path) with rationality `beta`, and
///                   learning as a change in the prior: a recognised strategy adds
///                   `recognition_logodds` x (w_same (2T-1) + w_other (1-2T)) to the log-odds.
enum class ParticipantModel { heuristic, goal_inference };

struct ObserverParams {
  ParticipantModel model = ParticipantModel::heuristic;
  double beta = 1.5;                // goal_inference: rationality (1/m)
  double recognition_logodds = 3.0; // goal_inference: prior shift (log-odds) of full recognition
  double reaction_delay = 0.3;     // s
  double decision_interval = 0.2;  // s between pad-goal decisions
  double noise_sd = 0.08;          // pad units, on each decided goal
  double pad_speed = 0.8;          // pad units per second (the GUI's constant key rate)
  double move_threshold = 0.05;    // pad units: closer than this to the goal, the key is released
  double inference_gain = 2.5;     // naive goal inference slope
  double half_familiarity = 3.0;   // memory trace at which familiarity is 1/2
  double learning_shape = 2.0;     // Hill exponent: f = m^a / (m^a + half^a)
  double memory_decay = 0.97;      // share of every memory trace kept per trial (recency)
  double recognition_time = 1.5;   // s for recognition to build up after the reaction delay
  double optimal_suspicion = 0.6;  // how much familiarity with exaggerating makes optimal suspect
  double capture_radius = 1.0;     // m: near a target, the observer sees where the robot ends
};

/// The calibrated goal-inference participant (docs/paper-scale.md): beta 0.3 /m,
/// recognition_logodds 5, half_familiarity 4, the rest as ObserverParams' defaults. With these the
/// demo study reproduces the paper's Table 1 on its own (raw confusion) scale.
ObserverParams goal_inference_observer() noexcept;

/// Throws UsageError naming the parameter when a setting is out of range.
void validate(const ObserverParams& p);

/// Sets the numeric parameter named `key` (a field name of ObserverParams, e.g. "beta",
/// "noise_sd"); throws UsageError listing the names when `key` is unknown.
void set_parameter(ObserverParams& p, std::string_view key, double value);

/// Applies one "NAME=VALUE" assignment (spaces around '=' allowed), e.g. "beta=0.3"; throws
/// UsageError for a malformed assignment, an unknown name or a value that is not a number.
void set_parameter(ObserverParams& p, std::string_view assignment);

/// Applies every `name = value` line of a parameter file (blank lines and '#' comments skipped),
/// e.g. one written from a fit to a pilot study. Throws IoError when the file cannot be read and
/// UsageError naming the file and line for a bad line.
void read_parameters(ObserverParams& p, const std::string& path);

/// "heuristic" or "goal-inference" (also "goal_inference"); throws UsageError otherwise.
ParticipantModel parse_participant_model(std::string_view name);
std::string_view to_string(ParticipantModel m) noexcept;

/// What a participant remembers of the strategy it watches (the memory and familiarity above):
/// f_same, the familiarity of the version shown, and f_other, that of the other version (for
/// optimal: optimal_suspicion x f(exaggerating, main), which starts alike). The pad observer and
/// the pointer participant (sim/pointer_participant.hpp) both learn from it.
struct Recognition {
  double f_same = 0;
  double f_other = 0;
};

/// How far recognition has built up at time t of a trial: r = clamp((t - reaction_delay) /
/// recognition_time, 0, 1).
double recognition_progress(const ObserverParams& p, double t) noexcept;

/// The learned log-odds toward the true target, recognition_logodds x r x (f_same - f_other)
/// (goal_inference; the pad multiplies it by 2T - 1, the pointer adds it to the true target's log
/// prior). 0 when recognition_logodds is 0 or nothing is familiar yet.
double learned_logodds(const ObserverParams& p, const Recognition& rec, double r) noexcept;

struct PadSample {
  double t = 0;
  double pad = 0.5;
};

class Observer {
 public:
  explicit Observer(ObserverParams params = {});

  /// Familiarity in [0, 1) of (strategy, version) now.
  double familiarity(Strategy s, Variant v) const noexcept;
  /// The familiarities that recognising (s, v) now weighs (see Recognition).
  Recognition recognition(Strategy s, Variant v) const noexcept;
  /// Watches one trial and returns the pad trace at the trajectory's sample times (pad positions
  /// on a 1e-4 grid, so that a logged trace never exceeds pad_speed). Does not update memory.
  std::vector<PadSample> watch(const std::vector<TrajectorySample>& path, Strategy s, Variant v,
                               Target true_target, const Geometry& g, Rng& rng) const;
  /// After the trial: decays every trace and adds one to (s, v).
  void remember(Strategy s, Variant v) noexcept;

  const ObserverParams& params() const noexcept { return params_; }

 private:
  ObserverParams params_;
  std::array<double, 8> memory_{};  // index strategy * 2 + variant
};

}  // namespace feint::sim

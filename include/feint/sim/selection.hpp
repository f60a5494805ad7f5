// feint/sim/selection.hpp - the strategy selection algorithms of selection.md (seed paper, sec. V).
//
// A run is a sequence of N iterations; each iteration gets a state (strategy), a version (main/v2,
// for the deceptive strategies) and a true target. Four algorithms choose the states:
//   random          every iteration draws a state uniformly and independently;
//   fixed-block     blocks of K iterations, each block a uniformly random permutation of the states;
//   fixed-balanced  each state floor(N/K) or ceil(N/K) times, in a uniformly random order;
//   adaptive(l)     a probability vector p (uniform at first) and an occurrence count c per state.
//                   Draw i from p; c_i += 1; L = the other states with c_j < c_i; if L is not empty,
//                   move l * p_i out of p_i and share it equally among L. Then, once min c >= 1,
//                   subtract 1 from every count (the paper's "reset to one iteration back").
// The paper prints eq. (2) as p_k = l (1 - p_{k-1}); its text (l p is moved away) is what is
// implemented, see docs/simulation.md.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "feint/rng.hpp"

namespace feint::sim {

/// The paper's four states S0..S3.
enum class Strategy : std::uint8_t { exaggerating = 0, switching = 1, ambiguous = 2, optimal = 3 };
/// main, or version 2 ("go back to the other target at the last moment"); optimal is always main.
enum class Variant : std::uint8_t { main = 0, v2 = 1 };
enum class Target : std::uint8_t { left = 0, right = 1 };

enum class Algorithm : std::uint8_t { random, fixed_block, fixed_balanced, adaptive };
/// How the true target of each iteration is chosen: independent fair coin flips, or a random order
/// of floor(N/2) / ceil(N/2) lefts and rights.
enum class TargetOrder : std::uint8_t { random, balanced };

inline constexpr int kStates = 4;     // the paper's K
inline constexpr int kMaxStates = 16; // the selector's capacity (K is a parameter of the library)

std::string_view to_string(Strategy s) noexcept;
std::string_view to_string(Variant v) noexcept;
std::string_view to_string(Target t) noexcept;
/// `random`, `fixed-block`, `fixed-balanced`, `adaptive`.
std::string_view to_string(Algorithm a) noexcept;
std::string_view to_string(TargetOrder o) noexcept;
/// Parses the names above (case-insensitive; `_` accepted for `-`). Throws UsageError otherwise.
Algorithm parse_algorithm(std::string_view name);
TargetOrder parse_target_order(std::string_view name);

/// The deterministic part of the adaptive algorithm: p and c, and the update after a choice.
/// Exposed so that a trace can be checked by hand.
struct AdaptiveState {
  int k = kStates;
  std::array<double, kMaxStates> p{};  // selection probabilities (sum 1)
  std::array<int, kMaxStates> c{};     // occurrence counts since the last reset

  explicit AdaptiveState(int states = kStates);
  /// Applies the update rule after state `chosen` occurred. Returns true when the counts were reset.
  bool observe(int chosen, double lambda) noexcept;
  /// Draws a state from p (inverse CDF on one Rng::uniform(); the sum of p is recomputed so that
  /// rounding drift can never select past the last state).
  int draw(Rng& rng) const noexcept;
};

/// One selection algorithm over K states for runs of N iterations: reset() at the start of each run,
/// then next() once per iteration. Allocation-free after construction.
class Selector {
 public:
  /// Throws UsageError for K outside [1, kMaxStates], N < 1, or lambda outside [0, 1].
  Selector(Algorithm algorithm, int states, int iterations, double lambda = 0.5);

  void reset(Rng& rng);
  /// The state of the next iteration (0 .. K-1). Calling it more than N times after reset() keeps
  /// going: fixed-balanced then starts a new balanced sequence.
  int next(Rng& rng);
  /// Probability with which the next call of next() returns each state, given the history so far.
  /// (random: 1/K; fixed-block: 1/remaining for the states still due in the block; fixed-balanced:
  /// remaining count / remaining iterations; adaptive: p.)
  std::array<double, kMaxStates> next_probabilities() const noexcept;

  Algorithm algorithm() const noexcept { return algorithm_; }
  int states() const noexcept { return k_; }
  int iterations() const noexcept { return n_; }
  double lambda() const noexcept { return lambda_; }
  const AdaptiveState& adaptive_state() const noexcept { return adaptive_; }

 private:
  void refill(Rng& rng);
  Algorithm algorithm_;
  int k_;
  int n_;
  double lambda_;
  AdaptiveState adaptive_;
  std::vector<std::uint8_t> plan_;  // fixed-*: the shuffled states of the block / run
  std::size_t pos_ = 0;             // fixed-*: next index in plan_
};

/// Shuffles data[0..n) with Fisher-Yates using Rng::bounded (portable, unlike std::shuffle).
template <class T>
void shuffle(T* data, std::size_t n, Rng& rng) noexcept {
  for (std::size_t i = n; i > 1; --i) {
    const auto j = rng.bounded(static_cast<std::uint32_t>(i));
    std::swap(data[i - 1], data[j]);
  }
}
template <class T>
void shuffle(std::vector<T>& v, Rng& rng) noexcept {
  shuffle(v.data(), v.size(), rng);
}

/// One iteration of a run.
struct Iteration {
  Strategy strategy;
  Variant variant;
  Target target;
};

struct RunSettings {
  Algorithm algorithm = Algorithm::adaptive;
  double lambda = 0.5;
  int iterations = 20;
  int states = kStates;  // the first `states` of S0..S3 (K = 4 in the paper); <= 4 for full runs
  TargetOrder targets = TargetOrder::random;
};

/// Generates one full run: the state sequence by `algorithm`; the version (main/v2) of each
/// deceptive state by the same algorithm over two versions with its own p and counts per strategy
/// (for fixed-balanced, balanced over that strategy's occurrences); the targets by `targets`.
/// The draws come from `rng` in a fixed, documented order: states, then versions per strategy
/// (S0, S1, S2), then targets.
std::vector<Iteration> generate_run(const RunSettings& settings, Rng& rng);

}  // namespace feint::sim

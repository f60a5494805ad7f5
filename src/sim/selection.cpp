// Strategy selection algorithms (selection.md; seed paper sec. V). See feint/sim/selection.hpp.
#include "feint/sim/selection.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/number.hpp"

namespace feint::sim {

std::string_view to_string(Strategy s) noexcept {
  switch (s) {
    case Strategy::exaggerating: return "exaggerating";
    case Strategy::switching: return "switching";
    case Strategy::ambiguous: return "ambiguous";
    case Strategy::optimal: return "optimal";
  }
  return "?";
}

std::string_view to_string(Variant v) noexcept { return v == Variant::main ? "main" : "v2"; }
std::string_view to_string(Target t) noexcept { return t == Target::left ? "left" : "right"; }

std::string_view to_string(Algorithm a) noexcept {
  switch (a) {
    case Algorithm::random: return "random";
    case Algorithm::fixed_block: return "fixed-block";
    case Algorithm::fixed_balanced: return "fixed-balanced";
    case Algorithm::adaptive: return "adaptive";
  }
  return "?";
}

std::string_view to_string(TargetOrder o) noexcept {
  return o == TargetOrder::random ? "random" : "balanced";
}

namespace {
std::string normalise_name(std::string_view name) {
  std::string s = io::to_lower(io::trim(name));
  std::replace(s.begin(), s.end(), '_', '-');
  return s;
}
}  // namespace

Algorithm parse_algorithm(std::string_view name) {
  const std::string s = normalise_name(name);
  for (auto a : {Algorithm::random, Algorithm::fixed_block, Algorithm::fixed_balanced,
                 Algorithm::adaptive}) {
    if (s == to_string(a)) return a;
  }
  throw UsageError(fmt::format(
      "unknown selection algorithm '{}' (expected random, fixed-block, fixed-balanced or adaptive)",
      name));
}

TargetOrder parse_target_order(std::string_view name) {
  const std::string s = normalise_name(name);
  if (s == "random") return TargetOrder::random;
  if (s == "balanced") return TargetOrder::balanced;
  throw UsageError(fmt::format("unknown target order '{}' (expected random or balanced)", name));
}

// ---------------------------------------------------------------------------------------------
AdaptiveState::AdaptiveState(int states) : k(states) {
  for (int i = 0; i < k; ++i) p[static_cast<std::size_t>(i)] = 1.0 / k;
}

namespace {

// The update and the draw with the number of states as a compile-time constant where it is the
// paper's K = 4 (the simulator's hot loop), else K = k at run time; both give identical results.
// Written without data-dependent branches; adding 0.0 to a probability that is not in L leaves it
// bit-for-bit unchanged.
template <int KC>
bool observe_impl(AdaptiveState& st, int kk, int chosen, double lambda) noexcept {
  const int k = KC > 0 ? KC : kk;
  const auto ci = static_cast<std::size_t>(chosen);
  const int count = ++st.c[ci];
  std::array<bool, kMaxStates> in_less{};
  int n_less = 0;
  int min_count = count;
  for (int j = 0; j < k; ++j) {
    const auto uj = static_cast<std::size_t>(j);
    in_less[uj] = j != chosen && st.c[uj] < count;
    n_less += in_less[uj] ? 1 : 0;
    min_count = std::min(min_count, st.c[uj]);
  }
  if (n_less > 0) {
    const double moved = lambda * st.p[ci];
    const double share = moved / n_less;
    for (int j = 0; j < k; ++j) {
      const auto uj = static_cast<std::size_t>(j);
      st.p[uj] += in_less[uj] ? share : 0.0;
    }
    st.p[ci] -= moved;
  }
  if (min_count >= 1) {  // every state has occurred: "reset to one iteration back"
    for (int j = 0; j < k; ++j) st.c[static_cast<std::size_t>(j)] -= 1;
    return true;
  }
  return false;
}

// Inverse CDF: the chosen state is the number of cumulative sums <= u (states with p = 0 have no
// width and are never chosen). u can round up to the total: then the last state with p > 0.
template <int KC>
int draw_impl(const AdaptiveState& st, int kk, Rng& rng) noexcept {
  const int k = KC > 0 ? KC : kk;
  std::array<double, kMaxStates> cum{};
  double total = 0;
  int last_positive = 0;
  for (int j = 0; j < k; ++j) {
    const double pj = st.p[static_cast<std::size_t>(j)];
    total += pj;
    cum[static_cast<std::size_t>(j)] = total;
    last_positive = pj > 0 ? j : last_positive;
  }
  const double u = rng.uniform() * total;
  int index = 0;
  for (int j = 0; j < k; ++j) index += cum[static_cast<std::size_t>(j)] <= u ? 1 : 0;
  return index < k ? index : last_positive;
}

}  // namespace

bool AdaptiveState::observe(int chosen, double lambda) noexcept {
  return k == 4 ? observe_impl<4>(*this, k, chosen, lambda) : observe_impl<0>(*this, k, chosen, lambda);
}

int AdaptiveState::draw(Rng& rng) const noexcept {
  return k == 4 ? draw_impl<4>(*this, k, rng) : draw_impl<0>(*this, k, rng);
}

// ---------------------------------------------------------------------------------------------
Selector::Selector(Algorithm algorithm, int states, int iterations, double lambda)
    : algorithm_(algorithm), k_(states), n_(iterations), lambda_(lambda),
      adaptive_(std::clamp(states, 1, kMaxStates)) {
  if (states < 1 || states > kMaxStates) {
    throw UsageError(fmt::format("number of states must be in [1, {}], got {}", kMaxStates, states));
  }
  if (iterations < 1) throw UsageError(fmt::format("iterations must be >= 1, got {}", iterations));
  if (!(lambda >= 0 && lambda <= 1)) {
    throw UsageError(fmt::format("lambda must be in [0, 1], got {}", io::format_double(lambda)));
  }
  if (algorithm_ == Algorithm::fixed_block) plan_.resize(static_cast<std::size_t>(k_));
  if (algorithm_ == Algorithm::fixed_balanced) plan_.resize(static_cast<std::size_t>(n_));
}

void Selector::refill(Rng& rng) {
  // fixed-block: one permutation of the K states; fixed-balanced: N iterations holding each state
  // floor(N/K) or ceil(N/K) times. Which states get the extra occurrence when K does not divide N
  // is itself uniformly random (a random permutation decides), so no state is favoured.
  if (algorithm_ == Algorithm::fixed_block) {
    for (int i = 0; i < k_; ++i) plan_[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(i);
  } else {
    std::array<std::uint8_t, kMaxStates> order{};
    for (int i = 0; i < k_; ++i) order[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(i);
    if (n_ % k_ != 0) shuffle(order.data(), static_cast<std::size_t>(k_), rng);
    for (int i = 0; i < n_; ++i) {
      plan_[static_cast<std::size_t>(i)] = order[static_cast<std::size_t>(i % k_)];
    }
  }
  shuffle(plan_, rng);
  pos_ = 0;
}

void Selector::reset(Rng& rng) {
  adaptive_ = AdaptiveState(k_);
  pos_ = plan_.size();  // fixed-*: refill lazily on the first next()
  (void)rng;
}

int Selector::next(Rng& rng) {
  switch (algorithm_) {
    case Algorithm::random:
      return static_cast<int>(rng.bounded(static_cast<std::uint32_t>(k_)));
    case Algorithm::fixed_block:
    case Algorithm::fixed_balanced:
      if (pos_ >= plan_.size()) refill(rng);
      return plan_[pos_++];
    case Algorithm::adaptive: {
      const int s = adaptive_.draw(rng);
      adaptive_.observe(s, lambda_);
      return s;
    }
  }
  return 0;
}

std::array<double, kMaxStates> Selector::next_probabilities() const noexcept {
  std::array<double, kMaxStates> out{};
  switch (algorithm_) {
    case Algorithm::random:
      for (int i = 0; i < k_; ++i) out[static_cast<std::size_t>(i)] = 1.0 / k_;
      break;
    case Algorithm::fixed_block:
    case Algorithm::fixed_balanced: {
      if (pos_ >= plan_.size()) {  // a new block / sequence starts: the next state is uniform
        for (int i = 0; i < k_; ++i) out[static_cast<std::size_t>(i)] = 1.0 / k_;
        break;
      }
      const double remaining = static_cast<double>(plan_.size() - pos_);
      for (std::size_t i = pos_; i < plan_.size(); ++i) out[plan_[i]] += 1.0 / remaining;
      break;
    }
    case Algorithm::adaptive: {
      double total = 0;
      for (int i = 0; i < k_; ++i) total += adaptive_.p[static_cast<std::size_t>(i)];
      for (int i = 0; i < k_; ++i) {
        out[static_cast<std::size_t>(i)] = adaptive_.p[static_cast<std::size_t>(i)] / total;
      }
      break;
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
std::vector<Iteration> generate_run(const RunSettings& settings, Rng& rng) {
  if (settings.states < 1 || settings.states > kStates) {
    throw UsageError(fmt::format("a run with strategies needs 1 to {} states, got {}", kStates,
                                 settings.states));
  }
  const int n = settings.iterations;
  Selector states(settings.algorithm, settings.states, n, settings.lambda);
  states.reset(rng);
  std::vector<Iteration> run(static_cast<std::size_t>(std::max(n, 0)));
  std::array<int, kStates> count{};
  for (auto& it : run) {
    const int s = states.next(rng);
    it.strategy = static_cast<Strategy>(s);
    it.variant = Variant::main;
    ++count[static_cast<std::size_t>(s)];
  }
  // Versions: per deceptive strategy, the same algorithm over two versions, over that strategy's
  // occurrences (its own p and counts; fixed-balanced balances main/v2 within the strategy).
  for (int s = 0; s < std::min(settings.states, 3); ++s) {
    const int occurrences = count[static_cast<std::size_t>(s)];
    if (occurrences == 0) continue;
    Selector versions(settings.algorithm, 2, occurrences, settings.lambda);
    versions.reset(rng);
    for (auto& it : run) {
      if (static_cast<int>(it.strategy) == s) it.variant = static_cast<Variant>(versions.next(rng));
    }
  }
  if (settings.targets == TargetOrder::random) {
    for (auto& it : run) it.target = static_cast<Target>(rng.bounded(2));
  } else {
    std::vector<std::uint8_t> t(run.size());
    for (std::size_t i = 0; i < t.size(); ++i) t[i] = static_cast<std::uint8_t>(i % 2);
    if (t.size() % 2 == 1) t.back() = static_cast<std::uint8_t>(rng.bounded(2));  // odd N: fair extra
    shuffle(t, rng);
    for (std::size_t i = 0; i < t.size(); ++i) run[i].target = static_cast<Target>(t[i]);
  }
  return run;
}

}  // namespace feint::sim

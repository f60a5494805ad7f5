// feint/rng.hpp - the documented, portable random number generator (foundation: used by sim and models).
//
// Every simulated number comes from here, so a run is reproducible bit for bit on any machine and
// with any standard library from its seed (std::uniform_*_distribution is not: its algorithm is
// implementation-defined). The pieces are published, fixed algorithms:
//   * SplitMix64 (Steele, Lea & Flood 2014) seeds the state and derives streams;
//   * xoshiro256** 1.0 (Blackman & Vigna 2018) generates 64-bit words;
//   * bounded integers in [0, n) by Lemire's nearly-divisionless method (Lemire 2019, "Fast random
//     integer generation in an interval", ACM TOMACS 29(1)), exact and unbiased;
//   * doubles in [0, 1) from the top 53 bits: (x >> 11) * 2^-53.
// Per-run streams: `Rng::stream(seed, index)` seeds run `index` of a simulation from (seed, index)
// alone, so results do not depend on how runs are spread over threads.
#pragma once

#include <cstdint>

namespace feint {

/// One SplitMix64 step: advances `state` by the golden-ratio increment and returns the mixed word.
constexpr std::uint64_t splitmix64(std::uint64_t& state) noexcept {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/// xoshiro256** with Lemire bounded integers and 53-bit doubles.
class Rng {
 public:
  using result_type = std::uint64_t;

  /// State = four SplitMix64 outputs from `seed` (never all zero).
  explicit constexpr Rng(std::uint64_t seed) noexcept : s_{} {
    std::uint64_t sm = seed;
    for (auto& w : s_) w = splitmix64(sm);
  }

  /// A generator with the raw xoshiro256** state `s` (not all zero), e.g. for reference vectors.
  static constexpr Rng from_state(std::uint64_t s0, std::uint64_t s1, std::uint64_t s2,
                                  std::uint64_t s3) noexcept {
    Rng r(0);
    r.s_[0] = s0;
    r.s_[1] = s1;
    r.s_[2] = s2;
    r.s_[3] = s3;
    return r;
  }

  /// The generator of stream `index` under `seed`: seeded with SplitMix64-mix(seed) XOR
  /// SplitMix64-mix(index + 1), two decorrelated 64-bit words, so (seed, index) pairs that differ
  /// in either part give unrelated streams.
  static constexpr Rng stream(std::uint64_t seed, std::uint64_t index) noexcept {
    std::uint64_t a = seed;
    std::uint64_t b = ~index;  // a different start from `a` even when seed == index
    const std::uint64_t ma = splitmix64(a);
    const std::uint64_t mb = splitmix64(b);
    return Rng(ma ^ (mb * 0xD1B54A32D192ED03ULL));
  }

  /// Next 64-bit word (xoshiro256** 1.0).
  constexpr std::uint64_t operator()() noexcept {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  /// Uniform integer in [0, n), n >= 1 (Lemire's multiply-and-reject; no modulo bias).
  constexpr std::uint32_t bounded(std::uint32_t n) noexcept {
    std::uint64_t m = static_cast<std::uint64_t>(static_cast<std::uint32_t>((*this)() >> 32)) * n;
    auto low = static_cast<std::uint32_t>(m);
    if (low < n) {
      const std::uint32_t threshold = static_cast<std::uint32_t>(-n) % n;  // 2^32 mod n
      while (low < threshold) {
        m = static_cast<std::uint64_t>(static_cast<std::uint32_t>((*this)() >> 32)) * n;
        low = static_cast<std::uint32_t>(m);
      }
    }
    return static_cast<std::uint32_t>(m >> 32);
  }

  /// Uniform double in [0, 1) with 53 random bits.
  constexpr double uniform() noexcept {
    return static_cast<double>((*this)() >> 11) * 0x1.0p-53;
  }

  /// Standard normal deviate (Marsaglia polar method; uses only uniform(), hence portable up to
  /// the libm's log/sqrt, which are correctly rounded or nearly so on every common platform).
  double normal() noexcept;

  static constexpr std::uint64_t min() noexcept { return 0; }
  static constexpr std::uint64_t max() noexcept { return ~std::uint64_t{0}; }

 private:
  static constexpr std::uint64_t rotl(std::uint64_t x, int k) noexcept {
    return (x << k) | (x >> (64 - k));
  }
  std::uint64_t s_[4];
};

}  // namespace feint

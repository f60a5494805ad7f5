// Many runs of a selection algorithm and their measures. See feint/sim/simulation.hpp.
#include "feint/sim/simulation.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::sim {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Welford accumulator; merge() is Chan et al.'s pairwise update (deterministic in merge order).
struct Acc {
  std::uint64_t n = 0;
  double mean = 0;
  double m2 = 0;
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();

  void add(double x) noexcept {
    ++n;
    const double d = x - mean;
    mean += d / static_cast<double>(n);
    m2 += d * (x - mean);
    min = std::min(min, x);
    max = std::max(max, x);
  }
  void merge(const Acc& o) noexcept {
    if (o.n == 0) return;
    if (n == 0) {
      *this = o;
      return;
    }
    const double na = static_cast<double>(n);
    const double nb = static_cast<double>(o.n);
    const double d = o.mean - mean;
    const double nt = na + nb;
    mean += d * nb / nt;
    m2 += o.m2 + d * d * na * nb / nt;
    n += o.n;
    min = std::min(min, o.min);
    max = std::max(max, o.max);
  }
  Spread spread() const noexcept {
    Spread s;
    s.n = n;
    s.mean = n > 0 ? mean : kNaN;
    s.sd = n > 1 ? std::sqrt(m2 / static_cast<double>(n - 1)) : kNaN;
    s.min = n > 0 ? min : kNaN;
    s.max = n > 0 ? max : kNaN;
    return s;
  }
};

/// Per-thread scratch for the measures of runs of N iterations: x log2 x for x = 0 .. N.
class Measurer {
 public:
  explicit Measurer(int n)
      : xlogx_(static_cast<std::size_t>(n) + 1), term_(static_cast<std::size_t>(n) + 1) {
    for (std::size_t x = 1; x < xlogx_.size(); ++x) {
      xlogx_[x] = static_cast<double>(x) * std::log2(static_cast<double>(x));
      // -(c/N) log2(c/N), computed as in eq. (1) so that e.g. c/N = 1/4 gives exactly 0.5
      const double p = static_cast<double>(x) / n;
      term_[x] = -p * std::log2(p);
    }
    for (std::size_t t = 1; t < inv_.size(); ++t) inv_[t] = 1.0 / static_cast<double>(t);
  }

  // states[0..n) in [0, k)
  RunMeasures measure(const std::uint8_t* states, int n, int k) noexcept {
    std::array<int, kMaxStates> count;
    std::fill_n(count.begin(), k, 0);
    std::fill_n(bigram_.begin(), k * k, 0);
    int repeats = 0;
    double hits = 0;
    // least-seen guesser: `least` = the smallest count so far, `ties` = how many states have it
    int least = 0;
    int ties = k;
    for (int i = 0; i < n; ++i) {
      const int s = states[i];
      int& cs = count[static_cast<std::size_t>(s)];
      if (cs == least) {
        hits += inv_[static_cast<std::size_t>(ties)];  // guessed right with probability 1/ties
        if (--ties == 0) {  // s was the last state at the minimum: the minimum rises by one
          ++least;
          for (int j = 0; j < k; ++j) ties += count[static_cast<std::size_t>(j)] == least ? 1 : 0;
          ties += 1;  // s itself, counted below
        }
      }
      ++cs;
      if (i > 0) {
        const int prev = states[i - 1];
        repeats += prev == s ? 1 : 0;
        ++bigram_[static_cast<std::size_t>(prev * k + s)];
      }
    }
    RunMeasures m;
    const double nn = n;
    double h = 0;
    for (int j = 0; j < k; ++j) h += term_[static_cast<std::size_t>(count[static_cast<std::size_t>(j)])];
    m.entropy = std::max(0.0, h);
    m.guess_accuracy = hits / nn;
    if (n < 2) {
      m.repetition = kNaN;
      m.conditional_entropy = kNaN;
      return m;
    }
    m.repetition = repeats / (nn - 1);
    // H(S_k|S_{k-1}) = (1/(N-1)) [sum_a n_a. log2 n_a. - sum_ab n_ab log2 n_ab]
    double rows = 0;
    double cells = 0;
    for (int a = 0; a < k; ++a) {
      int row = 0;
      for (int b = 0; b < k; ++b) {
        const int nab = bigram_[static_cast<std::size_t>(a * k + b)];
        row += nab;
        cells += xlogx_[static_cast<std::size_t>(nab)];
      }
      rows += xlogx_[static_cast<std::size_t>(row)];
    }
    m.conditional_entropy = std::max(0.0, (rows - cells) / (nn - 1));
    return m;
  }

 private:
  std::vector<double> xlogx_;
  std::vector<double> term_;
  std::array<double, kMaxStates + 1> inv_{};
  std::array<int, kMaxStates * kMaxStates> bigram_{};
};

struct ChunkResult {
  Acc entropy, repetition, conditional, guess;
};

void validate(const SimulationSettings& s) {
  Selector check(s.run.algorithm, s.run.states, s.run.iterations, s.run.lambda);  // throws
  (void)check;
  if (s.runs < 1) throw UsageError("the number of runs must be >= 1");
}

}  // namespace

double Spread::se() const noexcept {
  return n > 1 ? sd / std::sqrt(static_cast<double>(n)) : kNaN;
}

RunMeasures measure_run(const std::vector<int>& states, int k) {
  if (states.empty()) throw std::invalid_argument("measure_run: empty run");
  if (k < 1 || k > kMaxStates) throw std::invalid_argument("measure_run: bad number of states");
  std::vector<std::uint8_t> s(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (states[i] < 0 || states[i] >= k) throw std::invalid_argument("measure_run: state out of range");
    s[i] = static_cast<std::uint8_t>(states[i]);
  }
  Measurer m(static_cast<int>(s.size()));
  return m.measure(s.data(), static_cast<int>(s.size()), k);
}

double entropy_bits(const std::vector<std::uint64_t>& counts) {
  double total = 0;
  for (auto c : counts) total += static_cast<double>(c);
  if (total <= 0) return kNaN;
  double h = 0;
  for (auto c : counts) {
    if (c == 0) continue;
    const double p = static_cast<double>(c) / total;
    h -= p * std::log2(p);
  }
  return std::max(0.0, h);
}

double quantile7(std::vector<double>& values, double prob) {
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const double h = (static_cast<double>(values.size()) - 1) * prob;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (h - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

namespace {

/// Chunks: a fixed partition of the runs (independent of the thread count), whole batches each.
struct ChunkPlan {
  std::uint64_t runs = 0, batch = 0;
  std::uint64_t chunk = 0, n_chunks = 0, n_batches = 0;
};

ChunkPlan plan_chunks(const SimulationSettings& settings) {
  ChunkPlan plan;
  plan.runs = settings.runs;
  plan.batch = settings.batch;
  const std::uint64_t batch = plan.batch;
  plan.chunk = batch > 0 ? batch * std::max<std::uint64_t>(1, 4096 / batch) : 4096;
  plan.n_chunks = (plan.runs + plan.chunk - 1) / plan.chunk;
  plan.n_batches = batch > 0 ? plan.runs / batch : 0;
  return plan;
}

/// A thread's counts: occurrences of each state at each iteration, and of each state.
struct ThreadOut {
  std::vector<std::uint64_t> occurrence, pooled;
};

/// What the threads share: each slot of `chunks` and of the batch figures is written by one
/// thread (the one that claimed its chunk), so that the results do not depend on the schedule.
struct SharedRuns {
  SharedRuns(const SimulationSettings& s, const ChunkPlan& p)
      : settings(s),
        plan(p),
        chunks(p.n_chunks),
        batch_mean(p.n_batches),
        batch_pooled(p.n_batches) {}
  const SimulationSettings& settings;
  ChunkPlan plan;
  std::vector<ChunkResult> chunks;
  std::vector<double> batch_mean, batch_pooled;  // per batch: mean entropy, pooled entropy
  std::atomic<std::uint64_t> next_chunk{0};
};

/// A thread's selector, measurer and buffers, reused from run to run.
struct RunScratch {
  Selector selector;
  Measurer measurer;
  std::vector<std::uint8_t> seq;
  std::vector<std::uint64_t> batch_counts;
};

/// The runs of chunk `c`; their states are counted in `out`.
ChunkResult run_chunk(SharedRuns& sh, std::uint64_t c, RunScratch& scratch, ThreadOut& out) {
  const int n = sh.settings.run.iterations;
  const int k = sh.settings.run.states;
  const std::uint64_t runs = sh.plan.runs, batch = sh.plan.batch;
  std::vector<std::uint8_t>& seq = scratch.seq;
  std::vector<std::uint64_t>& batch_counts = scratch.batch_counts;
  ChunkResult res;  // local: neighbouring chunks of other threads share cache lines
  const std::uint64_t first = c * sh.plan.chunk;
  const std::uint64_t last = std::min(runs, first + sh.plan.chunk);
  double batch_sum = 0;
  for (std::uint64_t r = first; r < last; ++r) {
    Rng rng = Rng::stream(sh.settings.seed, r);
    scratch.selector.reset(rng);
    for (int i = 0; i < n; ++i) {
      const int s = scratch.selector.next(rng);
      seq[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(s);
      ++out.occurrence[static_cast<std::size_t>(i * k + s)];
      ++batch_counts[static_cast<std::size_t>(s)];
    }
    const RunMeasures m = scratch.measurer.measure(seq.data(), n, k);
    res.entropy.add(m.entropy);
    res.guess.add(m.guess_accuracy);
    if (n >= 2) {
      res.repetition.add(m.repetition);
      res.conditional.add(m.conditional_entropy);
    }
    if (batch > 0) {
      batch_sum += m.entropy;
      if ((r + 1) % batch == 0) {
        const std::uint64_t b = r / batch;
        sh.batch_mean[b] = batch_sum / static_cast<double>(batch);
        sh.batch_pooled[b] = entropy_bits(batch_counts);
      }
    }
    if (batch == 0 || (r + 1) % batch == 0 || r + 1 == last) {
      for (std::size_t j = 0; j < batch_counts.size(); ++j) {
        out.pooled[j] += batch_counts[j];
        batch_counts[j] = 0;
      }
      batch_sum = 0;
    }
  }
  return res;
}

/// A thread's work: the chunks it claims, one after another, until none is left.
void run_chunks(SharedRuns& sh, ThreadOut& out) {
  const int n = sh.settings.run.iterations;
  const int k = sh.settings.run.states;
  out.occurrence.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(k), 0);
  out.pooled.assign(static_cast<std::size_t>(k), 0);
  RunScratch scratch{Selector(sh.settings.run.algorithm, k, n, sh.settings.run.lambda),
                     Measurer(n), std::vector<std::uint8_t>(static_cast<std::size_t>(n)),
                     std::vector<std::uint64_t>(static_cast<std::size_t>(k), 0)};
  for (;;) {
    const std::uint64_t c = sh.next_chunk.fetch_add(1, std::memory_order_relaxed);
    if (c >= sh.plan.n_chunks) break;
    sh.chunks[c] = run_chunk(sh, c, scratch, out);
  }
}

/// The summary: the chunks' measures merged in chunk order, the threads' counts added up.
SimulationSummary summarise(SharedRuns& sh, const std::vector<ThreadOut>& outs, unsigned threads) {
  const int n = sh.settings.run.iterations;
  const int k = sh.settings.run.states;
  ChunkResult total;
  for (const auto& c : sh.chunks) {
    total.entropy.merge(c.entropy);
    total.repetition.merge(c.repetition);
    total.conditional.merge(c.conditional);
    total.guess.merge(c.guess);
  }
  SimulationSummary out;
  out.settings = sh.settings;
  out.settings.threads = threads;
  out.entropy = total.entropy.spread();
  out.repetition = total.repetition.spread();
  out.conditional_entropy = total.conditional.spread();
  out.guess_accuracy = total.guess.spread();
  out.occurrence.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(k), 0);
  out.pooled.assign(static_cast<std::size_t>(k), 0);
  for (const auto& t : outs) {
    for (std::size_t i = 0; i < out.occurrence.size(); ++i) out.occurrence[i] += t.occurrence[i];
    for (std::size_t i = 0; i < out.pooled.size(); ++i) out.pooled[i] += t.pooled[i];
  }
  out.entropy_pooled = entropy_bits(out.pooled);
  out.batches = sh.plan.n_batches;
  if (sh.plan.n_batches >= 2) {
    out.batch_entropy_mean_q025 = quantile7(sh.batch_mean, 0.025);
    out.batch_entropy_mean_q975 = quantile7(sh.batch_mean, 0.975);
    out.batch_entropy_pooled_q025 = quantile7(sh.batch_pooled, 0.025);
    out.batch_entropy_pooled_q975 = quantile7(sh.batch_pooled, 0.975);
  } else {
    out.batch_entropy_mean_q025 = out.batch_entropy_mean_q975 = kNaN;
    out.batch_entropy_pooled_q025 = out.batch_entropy_pooled_q975 = kNaN;
  }
  return out;
}

}  // namespace

SimulationSummary simulate_selection(const SimulationSettings& settings) {
  validate(settings);
  SharedRuns sh(settings, plan_chunks(settings));

  unsigned threads = settings.threads;
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::uint64_t>(threads, sh.plan.n_chunks));

  std::vector<ThreadOut> outs(threads);
  if (threads <= 1) {
    run_chunks(sh, outs[0]);
  } else {
    std::vector<std::thread> pool;
    pool.reserve(threads);
    for (unsigned t = 0; t < threads; ++t)
      pool.emplace_back([&sh, &outs, t] { run_chunks(sh, outs[t]); });
    for (auto& th : pool) th.join();
  }
  return summarise(sh, outs, threads);
}

void for_each_run(const SimulationSettings& settings,
                  const std::function<void(std::uint64_t, const std::vector<Iteration>&)>& visit) {
  validate(settings);
  for (std::uint64_t r = 0; r < settings.runs; ++r) {
    Rng rng = Rng::stream(settings.seed, r);
    visit(r, generate_run(settings.run, rng));
  }
}

}  // namespace feint::sim

// bench_selection: wall time of `simulate_selection` for 10 million runs of 20 iterations (the
// speed target of Under 10 s on the project machine, all cores). Own main (a driver, not
// a Google Benchmark fixture), because the figure wanted is one end-to-end wall time per algorithm.
//
//   bench_selection [RUNS=10000000] [THREADS=0 (all cores)] [ITERATIONS=20]
//
// Prints one line per algorithm (wall and process CPU time; the machine is shared, so CPU time /
// threads is the figure a quiet machine would show) and exits 1 if any took 10 s or more.
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include <fmt/format.h>

#include "feint/sim/simulation.hpp"

int main(int argc, char** argv) {
  using namespace feint::sim;
  const std::uint64_t runs = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 10'000'000ULL;
  const unsigned threads = argc > 2 ? static_cast<unsigned>(std::strtoul(argv[2], nullptr, 10)) : 0;
  const int iterations = argc > 3 ? std::atoi(argv[3]) : 20;
  fmt::print("bench_selection: {} runs x {} iterations, threads = {} (hardware: {})\n", runs,
             iterations, threads == 0 ? std::string("all") : std::to_string(threads),
             std::thread::hardware_concurrency());
  bool ok = true;
  for (auto a : {Algorithm::random, Algorithm::fixed_block, Algorithm::fixed_balanced,
                 Algorithm::adaptive}) {
    SimulationSettings s;
    s.run.algorithm = a;
    s.run.lambda = 0.5;
    s.run.iterations = iterations;
    s.runs = runs;
    s.seed = 1;
    s.threads = threads;
    const std::clock_t c0 = std::clock();
    const auto t0 = std::chrono::steady_clock::now();
    const SimulationSummary r = simulate_selection(s);
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    ok = ok && sec < 10.0;
    fmt::print("{:<15} {:8.3f} s wall {:8.3f} s CPU  {:6.2f} M runs/s  (entropy mean {:.6f}, {} threads) {}\n",
               to_string(a), sec, cpu, static_cast<double>(runs) / sec / 1e6, r.entropy.mean,
               r.settings.threads, sec < 10.0 ? "ok" : "SLOWER THAN 10 s");
  }
  return ok ? 0 : 1;
}

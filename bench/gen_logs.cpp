// gen_logs - synthetic pad-trace logs in the format of shared/spec/formats.md.
//
// Used for data/example/ (a small, realistic study) and for the scoring benchmark (a log of any
// size). Deterministic for a given seed.
//
//   gen_logs --participants 3 --iterations 20 --out data/example        # one CSV per participant
//   gen_logs --bytes 1100000000 --out /tmp/big.csv                      # one large file
//   gen_logs --bytes 300000000 --out /tmp/big.csv.gz                    # gzip-compressed
//
// Model (a plausible participant, not a fitted one): the robot plays one of four strategies
// (exaggerating, switching, ambiguous, optimal; main or v2). The pad starts at 0.5 and moves at the
// GUI's constant pad speed v = 0.8 pad units/s while a key is held, sampled at ~30 Hz (frame times
// of 33/34 ms, written to the millisecond). After a reaction delay the participant moves toward
// the target they believe in; a deceptive strategy makes them believe the false target first with
// a probability that stays high under the adaptive algorithm and falls with repetition under the
// random one; they switch to the true target late in the trial, and sometimes hesitate (short
// pauses, extra reversals). Positions are multiples of 1e-4 and steps are exactly v * dt, so the
// logged speed never exceeds v (no overspeed segments).
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace {

struct Options {
  int participants = 3;
  int iterations = 20;
  unsigned long long seed = 20261121;
  double min_duration = 3.5, max_duration = 4.5;  // seconds
  unsigned long long bytes = 0;                   // > 0: keep adding participants until reached
  std::string out = "-";
};

const std::array<const char*, 4> kStrategies = {"exaggerating", "switching", "ambiguous", "optimal"};

class Sink {
 public:
  explicit Sink(const std::string& path) {
    if (path == "-") {
      plain_ = stdout;
    } else if (path.size() > 3 && path.ends_with(".gz")) {
      gz_ = gzopen(path.c_str(), "wb6");
    } else {
      plain_ = std::fopen(path.c_str(), "wb");
    }
    if (plain_ == nullptr && gz_ == nullptr) {
      fmt::print(stderr, "gen_logs: cannot write '{}'\n", path);
      std::exit(74);
    }
  }
  ~Sink() {
    flush();
    if (gz_ != nullptr) gzclose(gz_);
    if (plain_ != nullptr && plain_ != stdout) std::fclose(plain_);
  }
  fmt::memory_buffer& buf() { return buf_; }
  void maybe_flush() {
    if (buf_.size() > (1U << 20)) flush();
  }
  void flush() {
    if (buf_.size() == 0) return;
    written_ += buf_.size();
    if (gz_ != nullptr) {
      gzwrite(gz_, buf_.data(), static_cast<unsigned>(buf_.size()));
    } else {
      std::fwrite(buf_.data(), 1, buf_.size(), plain_);
    }
    buf_.clear();
  }
  unsigned long long written() const { return written_ + buf_.size(); }

 private:
  FILE* plain_ = nullptr;
  gzFile gz_ = nullptr;
  fmt::memory_buffer buf_;
  unsigned long long written_ = 0;
};

// Writes one participant's 2 x iterations trials.
void participant(Sink& sink, int p, const Options& o, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const std::string pid = fmt::format("P{:02d}", p);
  constexpr int kStepPerMs = 8;  // v = 0.8 pad/s = 8e-4 pad units per ms = 8 units of 1e-4
  const double v = 0.8;
  for (const char* condition : {"adaptive", "random"}) {
    std::array<int, 4> seen{};
    int last = -1;
    for (int it = 1; it <= o.iterations; ++it) {
      // Strategy choice: adaptive avoids repeats and balances use; random is uniform.
      int s = 0;
      if (std::string_view(condition) == "adaptive") {
        std::vector<int> least;
        const int m = *std::min_element(seen.begin(), seen.end());
        for (int k = 0; k < 4; ++k) {
          if (k != last && seen[k] <= m + 1) least.push_back(k);
        }
        s = least[static_cast<std::size_t>(u(rng) * static_cast<double>(least.size()))];
      } else {
        s = static_cast<int>(u(rng) * 4);
      }
      const bool v2 = s != 3 && u(rng) < 0.5;
      const double p_deceived =
          s == 3 ? 0.1
                 : (std::string_view(condition) == "adaptive" ? 0.7 : 0.7 * std::exp(-0.35 * seen[s]));
      ++seen[s];
      last = s;
      const bool right = u(rng) < 0.5;
      const int truth = right ? 1 : -1;
      const bool deceived = u(rng) < p_deceived;
      const double duration = o.min_duration + (o.max_duration - o.min_duration) * u(rng);
      const int total_ms = static_cast<int>(duration * 1000);
      const int react_ms = 250 + static_cast<int>(u(rng) * 500);
      const int switch_ms = static_cast<int>(total_ms * (0.45 + 0.4 * u(rng)));
      const double hesitancy = deceived ? 0.02 : 0.006;  // chance per frame of a brief change
      int belief = deceived ? -truth : truth;
      int pad = 5000;  // units of 1e-4
      int ms = 0;
      int pause_until = 0;
      int flip_until = 0;
      while (true) {
        auto& b = sink.buf();
        fmt::format_to(std::back_inserter(b), "{},{},{},{},{},{},{}.{:03d},{}.{:04d},{}\n", pid,
                       condition, it, kStrategies[static_cast<std::size_t>(s)], v2 ? "v2" : "main",
                       right ? "right" : "left", ms / 1000, ms % 1000, pad / 10000, pad % 10000, v);
        if (ms >= total_ms) break;
        const int dt = u(rng) < 0.67 ? 33 : 34;
        if (deceived && ms >= switch_ms) belief = truth;
        if (u(rng) < hesitancy) {
          if (u(rng) < 0.5) {
            pause_until = ms + 100 + static_cast<int>(u(rng) * 300);
          } else {
            flip_until = ms + 150 + static_cast<int>(u(rng) * 300);
          }
        }
        int dir = belief;
        if (ms < flip_until) dir = -belief;
        if (ms < react_ms || ms < pause_until) dir = 0;
        pad = std::clamp(pad + dir * kStepPerMs * dt, 0, 10000);
        ms += dt;
      }
      sink.maybe_flush();
    }
  }
}

[[noreturn]] void usage() {
  fmt::print(stderr,
             "usage: gen_logs [--participants N] [--iterations N] [--seed S] [--bytes B] "
             "[--min-duration S] [--max-duration S] --out PATH\n"
             "  PATH: a directory (one pNN.csv per participant), a file (.csv or .csv.gz), or -\n");
  std::exit(64);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage();
      return argv[++i];
    };
    if (a == "--participants") o.participants = std::stoi(value());
    else if (a == "--iterations") o.iterations = std::stoi(value());
    else if (a == "--seed") o.seed = std::stoull(value());
    else if (a == "--bytes") o.bytes = std::stoull(value());
    else if (a == "--min-duration") o.min_duration = std::stod(value());
    else if (a == "--max-duration") o.max_duration = std::stod(value());
    else if (a == "--out") o.out = value();
    else usage();
  }
  if (o.participants < 1 || o.iterations < 1 || !(o.min_duration > 0.2) ||
      o.max_duration < o.min_duration) {
    usage();
  }
  std::mt19937_64 rng(o.seed);
  const std::string header = "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed\n";
  namespace fs = std::filesystem;
  if (o.out != "-" && fs::is_directory(o.out)) {
    for (int p = 1; p <= o.participants; ++p) {
      Sink sink((fs::path(o.out) / fmt::format("p{:02d}.csv", p)).string());
      fmt::format_to(std::back_inserter(sink.buf()), "{}", header);
      participant(sink, p, o, rng);
    }
    return 0;
  }
  Sink sink(o.out);
  fmt::format_to(std::back_inserter(sink.buf()), "{}", header);
  for (int p = 1; p <= o.participants || sink.written() < o.bytes; ++p) participant(sink, p, o, rng);
  sink.flush();
  fmt::print(stderr, "gen_logs: wrote {} bytes (uncompressed) to {}\n", sink.written(), o.out);
  return 0;
}

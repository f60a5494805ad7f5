// bench_questionnaire_long: memory and time of loading a long-layout questionnaire, to show that
// loading is linear in the rows (a 271 KB file used to take 3.66 GB). Own main (a
// driver): for each size it writes a long file of ROWS rows (ROWS / 10 respondents x 10 items),
// loads it, and prints wall time and the growth of the peak resident set size.
//
//   bench_questionnaire_long [MAX_ROWS=2000000]
//
// Linear loading shows as time and memory growing ~10x per 10x rows. Run the sizes in increasing
// order (the peak RSS only grows).
#include <fmt/format.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "feint/io/questionnaire.hpp"

namespace {
long peak_rss_kb() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}
}  // namespace

int main(int argc, char** argv) {
  const long max_rows = argc > 1 ? std::atol(argv[1]) : 2'000'000L;
  const auto path = std::filesystem::temp_directory_path() /
                    ("feint-bench-long-" + std::to_string(::getpid()) + ".csv");
  for (long rows = 20'000; rows <= max_rows; rows *= 10) {
    {
      std::ofstream out(path);
      out << "participant,condition,item,response\n";
      for (long r = 0; r < rows; ++r) {
        const long p = r / 10;
        out << 'P' << p << ',' << (p % 2 ? "a" : "b") << ",item" << r % 10 << ',' << (p + r) % 7 + 1
            << '\n';
      }
    }
    const auto bytes = std::filesystem::file_size(path);
    const long before = peak_rss_kb();
    const auto t0 = std::chrono::steady_clock::now();
    const auto q = feint::io::load_questionnaire(path.string());
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    fmt::print(
        "{:>9} rows ({:>6.1f} MB): {} respondents x {} items, {:.3f} s, peak RSS +{:.1f} MB\n",
        rows, bytes / 1e6, q.respondents(), q.items.size(), secs,
        (peak_rss_kb() - before) / 1024.0);
  }
  std::filesystem::remove(path);
  return 0;
}

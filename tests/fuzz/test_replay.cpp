// Replays every committed fuzz input (tests/fuzz/corpus/<target>/ and regressions/<target>/)
// through the same harness functions libFuzzer runs, compiled with the normal compiler: a crash,
// sanitizer report or broken invariant found once stays fixed.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fuzz/harness.hpp"

namespace fs = std::filesystem;

namespace {

using Entry = int (*)(const std::uint8_t*, std::size_t);

const std::map<std::string, Entry>& targets() {
  static const std::map<std::string, Entry> t = {{"number", feint::fuzz::number},
                                                 {"trace", feint::fuzz::trace},
                                                 {"scores", feint::fuzz::scores},
                                                 {"csv", feint::fuzz::csv},
                                                 {"questionnaire", feint::fuzz::questionnaire}};
  return t;
}

std::size_t replay(const std::string& kind, const std::string& target) {
  const fs::path dir = fs::path(FEINT_SOURCE_DIR) / "tests" / "fuzz" / kind / target;
  if (!fs::is_directory(dir)) return 0;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.is_regular_file()) files.push_back(e.path());
  }
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    SCOPED_TRACE(f.string());
    targets().at(target)(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  return files.size();
}

class FuzzReplay : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(FuzzReplay, EverySeedAndRegressionInputPassesTheHarness) {
  const std::size_t seeds = replay("corpus", GetParam());
  replay("regressions", GetParam());
  EXPECT_GT(seeds, 0u) << "no seed corpus for target " << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzReplay,
                         ::testing::Values("number", "trace", "scores", "csv", "questionnaire"));

TEST(FuzzHarness, NumberTargetAbortsOnADisagreementWithStrtod) {
  // The differential check itself must be able to fail: "+-2" was read as -2 by an older parser.
  const std::string ok = "1e-400";
  feint::fuzz::number(reinterpret_cast<const std::uint8_t*>(ok.data()), ok.size());
  EXPECT_DEATH(feint::fuzz::detail::check(false, "demo"), "fuzz invariant broken: demo");
}

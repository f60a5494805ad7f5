// Helpers of the feint collect tests: temporary study folders and valid pad traces.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "feint/collect/study.hpp"

namespace feint::collect::testing {

inline std::filesystem::path fresh_dir(const std::string& name) {
  static std::atomic<int> n{0};
  auto d = std::filesystem::temp_directory_path() /
           ("feint-collect-" + std::to_string(::getpid()) + "-" + std::to_string(n++) + "-" + name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

/// A trace a person could have made: 60 Hz samples, the pad moved toward `target` at the pad
/// speed from t = 0, the last sample exactly at the end of the round.
inline std::vector<PadSample> valid_trace(const Round& r, double speed, double toward = 1.0) {
  std::vector<PadSample> s;
  const double dur = r.duration();
  const double dir = toward > 0.5 ? 1.0 : -1.0;
  for (int i = 0;; ++i) {
    const double t = i / 60.0;
    if (t >= dur) break;
    s.push_back({t, std::clamp(0.5 + dir * speed * t, 0.0, 1.0)});
  }
  s.push_back({dur, std::clamp(0.5 + dir * speed * dur, 0.0, 1.0)});
  return s;
}

/// Fast settings for tests: a quick robot, few rounds.
inline Settings fast_settings() {
  Settings s;
  s.iterations = 6;
  s.practice = 2;
  s.geometry.speed = 8.0;
  return s;
}

/// Plays every round of `id` through the Study API.
inline void play_all(Study& study, const std::string& id) {
  const auto& s = study.settings();
  for (int i = 0; i < s.practice + s.iterations; ++i) {
    const Round r = study.start_round(id);
    study.submit_round(id, r.kind, r.iteration, valid_trace(r, s.pad_speed, r.iteration % 2));
  }
}

}  // namespace feint::collect::testing

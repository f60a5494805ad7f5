// The worst agreement of each golden family, as measured: the golden tests record every compared
// value here, and the test program prints one line per family when it exits
//   accuracy: <family> worst relative <r> (<where>), worst absolute <a> (<where>)
// (docs/testing.md, "Measured accuracy"). Recording never fails a test; the tolerances do.
#pragma once

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

namespace feint::test {

struct Accuracy {
  double rel = 0, abs = 0;
  std::string rel_at, abs_at;
  std::size_t n = 0;
};

struct AccuracyTable {
  std::map<std::string, Accuracy> families;
  ~AccuracyTable() {
    for (const auto& [f, a] : families)
      std::printf("accuracy: %s n %zu worst relative %.3g (%s), worst absolute %.3g (%s)\n", f.c_str(),
                  a.n, a.rel, a.rel_at.c_str(), a.abs, a.abs_at.c_str());
  }
};

inline AccuracyTable& accuracy_table() {
  static AccuracyTable t;
  return t;
}

/// Records |got - want| and |got - want| / |want| (want != 0) for `family`; infinite or NaN
/// goldens (R's Inf bounds, NA) are skipped, as equal-or-not is all that can be said of them.
inline void record(const std::string& family, double got, double want, const std::string& what = "") {
  if (!std::isfinite(want)) return;
  Accuracy& a = accuracy_table().families[family];
  ++a.n;
  const double d = std::isfinite(got) ? std::fabs(got - want) : INFINITY;
  if (d > a.abs) {
    a.abs = d;
    a.abs_at = what;
  }
  if (want != 0 && d / std::fabs(want) > a.rel) {
    a.rel = d / std::fabs(want);
    a.rel_at = what;
  }
}

}  // namespace feint::test

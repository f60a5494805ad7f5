// ptukey / qtukey against an independent high-precision reference: tests/golden/models/
// ptukey_reference.csv, made by `ptukey_reference > tests/golden/models/ptukey_reference.csv`
// (bench/ptukey_reference.cpp: the studentized range integral by adaptive quadrature in IEEE
// binary128, ~34 digits), on a grid with the extremes: 13 q from 0.01 to 50, 8 k from 2 to 100,
// 17 df from 2 to infinity (2.5, 7.3, 12.5 and 1101.999999999954 not whole, as Satterthwaite and
// Kenward-Roger df). feint's ptukey agrees to 5.5e-16 absolute in P and in 1 - P; the earlier
// quadrature (fixed pieces in s and z) was off by up to 1.8e-2 (q = 50, k = 100, df = 2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "feint/models/studentized_range.hpp"

namespace {

using feint::models::ptukey;
using feint::models::ptukey_upper;
using feint::models::qtukey;

struct Reference {
  double q, k, df;
  long double lower, upper;  // P(Q <= q) and 1 - P(Q <= q), 20 significant digits
};

std::vector<Reference> reference() {
  std::ifstream in(std::string(FEINT_SOURCE_DIR) + "/tests/golden/models/ptukey_reference.csv");
  EXPECT_TRUE(in);
  std::vector<Reference> rows;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    if (cells.size() != 5) continue;
    rows.push_back({std::stod(cells[0]), std::stod(cells[1]),
                    cells[2] == "Inf" ? std::numeric_limits<double>::infinity() : std::stod(cells[2]),
                    std::stold(cells[3]), std::stold(cells[4])});
  }
  return rows;
}

TEST(StudentizedRangeReference, PtukeyAgreesWithThe34DigitQuadratureOnTheWholeGrid) {
  const auto rows = reference();
  ASSERT_EQ(rows.size(), 13u * 8u * 17u);
  double worst = 0;
  for (const auto& r : rows) {
    const double got = ptukey(r.q, r.k, r.df);
    // Absolute: p-values are 1 - ptukey, so this bounds their error too.
    EXPECT_NEAR(got, static_cast<double>(r.lower), 1e-15)
        << "q " << r.q << " k " << r.k << " df " << r.df;
    EXPECT_NEAR(1 - got, static_cast<double>(r.upper), 1e-15)
        << "q " << r.q << " k " << r.k << " df " << r.df;
    worst = std::max(worst, std::abs(static_cast<double>(got - r.lower)));
  }
  RecordProperty("max_abs_error", std::to_string(worst));
}

// P(Q > q) against bench/ptukey_reference.cpp --upper (tests/golden/models/
// ptukey_upper_reference.csv: the upper tail as its own integral in binary128, ~1e-24 relative;
// for two means it equals the closed form 2 P(T > q / sqrt 2) to 2e-24): q 1, 5, 12, 50, 1e4,
// 1e15, k 2, 5, 20, 100, df 2, 7.3, 30, 1160, 1e9 and infinity, P from 0.99 down to far below
// 1e-300. Relative error below 1e-12 where P >= 1e-300 (measured 1.2e-13, at q = 50, k = 20, df
// = infinity, P = 1e-270, where P's condition number in q is ~q^2/2); below that, only that
// feint's P is below 1e-290. 1 - ptukey fails this from P ~ 1e-4 on and is 0 from P ~ 1e-17 on.
TEST(StudentizedRangeReference, PtukeyUpperIsRelativelyAccurateInTheFarTail) {
  std::ifstream in(std::string(FEINT_SOURCE_DIR) +
                   "/tests/golden/models/ptukey_upper_reference.csv");
  ASSERT_TRUE(in);
  std::string line;
  std::getline(in, line);
  int rows = 0, tiny = 0;
  double worst = 0;
  while (std::getline(in, line)) {
    std::vector<std::string> c;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) c.push_back(cell);
    ASSERT_EQ(c.size(), 4u);
    const double q = std::stod(c[0]), k = std::stod(c[1]);
    const double df = c[2] == "Inf" ? std::numeric_limits<double>::infinity() : std::stod(c[2]);
    const long double want = std::stold(c[3]);
    const double got = ptukey_upper(q, k, df);
    ++rows;
    if (want < 1e-300L) {
      EXPECT_LT(got, 1e-290) << "q " << q << " k " << k << " df " << df;
      continue;
    }
    const double rel = static_cast<double>(std::abs((got - want) / want));
    EXPECT_LT(rel, 1e-12) << "q " << q << " k " << k << " df " << df << " P " << c[3];
    worst = std::max(worst, rel);
    if (want < 1e-20L) ++tiny;
  }
  EXPECT_EQ(rows, 6 * 4 * 6);
  EXPECT_GE(tiny, 20);  // the far tail is in the grid
  RecordProperty("max_rel_error", std::to_string(worst));
}

// On the 1,768-point grid: P(Q > q) to 1e-12 relative plus 5e-24 (the reference's 1 - P is
// accurate to ~2e-24 absolute: its z range [-13, 13] leaves that much out at k = 100, q = 50),
// and within 1e-15 of 1 - ptukey (the same probability; measured 7.8e-16). Where P > 1e-10 the
// relative error is 4e-15 (1 - ptukey: 1.3e-6).
TEST(StudentizedRangeReference, PtukeyUpperAgreesWithTheGridAndWithOneMinusPtukey) {
  const auto rows = reference();
  ASSERT_EQ(rows.size(), 13u * 8u * 17u);
  for (const auto& r : rows) {
    const double got = ptukey_upper(r.q, r.k, r.df);
    const double want = static_cast<double>(r.upper);
    EXPECT_NEAR(got, want, 1e-12 * want + 5e-24) << "q " << r.q << " k " << r.k << " df " << r.df;
    EXPECT_NEAR(got, 1 - ptukey(r.q, r.k, r.df), 1e-15)
        << "q " << r.q << " k " << r.k << " df " << r.df;
  }
}

TEST(StudentizedRangeReference, TukeyQuantilesOfTheDemoFamilies) {
  // The 95 % Tukey quantiles for 20 means at the dfs of the demo study's families (feint anova:
  // 58; feint model: 1160, and 1102 with Kenward-Roger). The 34-digit ptukey at these q
  // (bench/ptukey_reference.cpp) is 0.95000000000000017265, 0.95000000000000009571 and
  // 0.94999999999999941520: each q is the quantile to ~1e-14. The earlier ptukey gave
  // 5.249186641047709 (df 58), 5.0234622672850424 (1160) and 5.0240822179273259 (1102).
  EXPECT_NEAR(qtukey(0.95, 20, 58), 5.2491866410073014, 1e-13);
  EXPECT_NEAR(qtukey(0.95, 20, 1160), 5.0234622701576619, 1e-13);
  EXPECT_NEAR(qtukey(0.95, 20, 1101.999999999954), 5.0240822207655036, 1e-13);
}

TEST(StudentizedRangeReference, TukeyPValueOfADemoContrast) {
  // feint model --ddf kenward-roger --contrasts simple on the demo study: iteration15 -
  // iteration16 in the adaptive condition, t = -3.1238429190366332, df = 1101.999999999954; the
  // 34-digit 1 - ptukey(|t| sqrt 2, 20, df) is 0.17281902995024412194 (bench/ptukey_reference.cpp
  // at q = 4.417781022824765; the earlier ptukey gave 0.172819030017473).
  const double q = 3.1238429190366332 * std::sqrt(2.0);
  EXPECT_NEAR(1 - ptukey(q, 20, 1101.999999999954), 0.17281902995024412194, 1e-15);
  EXPECT_NEAR(ptukey_upper(q, 20, 1101.999999999954), 0.17281902995024412194, 1e-15);
}

}  // namespace

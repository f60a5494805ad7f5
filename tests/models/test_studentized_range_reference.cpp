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
}

}  // namespace

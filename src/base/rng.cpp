// Rng::normal - Marsaglia's polar method on Rng::uniform() (see feint/rng.hpp).
#include <cmath>

#include "feint/rng.hpp"

namespace feint {

double Rng::normal() noexcept {
  for (;;) {
    const double u = 2.0 * uniform() - 1.0;
    const double v = 2.0 * uniform() - 1.0;
    const double s = u * u + v * v;
    if (s > 0 && s < 1) return u * std::sqrt(-2.0 * std::log(s) / s);  // the second deviate is dropped
  }
}

}  // namespace feint

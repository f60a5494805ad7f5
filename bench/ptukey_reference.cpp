// ptukey_reference - high-precision values of the studentized range distribution, an independent
// reference for feint::models::ptukey (tests/models/test_studentized_range_reference.cpp reads
// the CSV this writes).
//
//   ptukey_reference [--fine] [DF ...] > tests/golden/models/ptukey_reference.csv
//
// Without DF the whole grid (13 q from 0.01 to 50, 8 k from 2 to 100, 17 df from 2 to infinity,
// non-integer ones among them; ~15 min of CPU); with DF only those df ("Inf" for infinity).
// --fine halves the z pieces and tightens the s tolerance 1000-fold: the check that the default
// rules have converged (253 values at df 2.5, 1160 and Inf moved by at most 8e-21).
//
// The same integral as feint's (Copenhaver & Holland 1988; see studentized_range.hpp),
//   P(q; k, df) = int_0^inf f_df(s) R(q s) ds,  R(w) = k int phi(z) [Phi(z + w) - Phi(z)]^(k-1) dz,
// evaluated independently of feint's code (other variable, other rules, no tables) in IEEE
// binary128 (__float128 through Boost.Multiprecision's float128, 113-bit significand, ~34
// digits): z by 30-point Gauss-Legendre on the pieces of width 2 of [-13, 13] (k phi(13) <
// 1e-36), skipping a node only where a bound of its term is below 1e-32; s by adaptive
// Gauss-Kronrod (31 points) to 1e-26 absolute per piece, on pieces of 2 standard deviations of
// f_df from its mode out to where f_df is below 1e-45 of its peak. Columns: q, nmeans, df,
// ptukey (lower tail), upper (1 - ptukey, from the same 34-digit value), 20 significant digits.
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <boost/multiprecision/float128.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

namespace {

using Real = boost::multiprecision::float128;
using GK = boost::math::quadrature::gauss_kronrod<Real, 31>;
using GL = boost::math::quadrature::gauss<Real, 30>;

Real upper_normal(const Real& x) {
  return boost::math::erfc(x / boost::math::constants::root_two<Real>()) / 2;
}

// Set by --fine: z pieces of width 1 instead of 2, s tolerance 1e-29 instead of 1e-26.
bool fine = false;

// The inner rule: 30-point Gauss-Legendre on pieces of width 2 (--fine: 1) of [-13, 13], the same
// nodes for every w, so phi(z) and the upper tail Q(z) are computed once per node.
struct InnerNodes {
  std::vector<Real> z, weighted_phi, tail, head;  // head = Phi(z)
  InnerNodes() {
    const auto& x = GL::abscissa();
    const auto& wt = GL::weights();
    auto add = [&](const Real& mid, const Real& xi, const Real& wi) {
      const Real zi = mid + xi;
      z.push_back(zi);
      weighted_phi.push_back(wi * exp(-zi * zi / 2) / boost::math::constants::root_two_pi<Real>());
      tail.push_back(upper_normal(zi));
      head.push_back(upper_normal(-zi));
    };
    const Real half = fine ? Real(0.5) : Real(1);
    for (Real a = -13; a < 13; a += 2 * half) {
      const Real mid = a + half;
      for (std::size_t i = 0; i < x.size(); ++i) {
        add(mid, half * x[i], half * wt[i]);
        if (x[i] != 0) add(mid, -half * x[i], half * wt[i]);
      }
    }
  }
};

// An integer power by squaring (pow of a multiprecision number goes through log and exp).
Real power(Real b, int n) {
  Real out = 1;
  for (; n > 0; n >>= 1, b *= b)
    if (n & 1) out *= b;
  return out;
}

// R(w) = k int phi(z) [Phi(z + w) - Phi(z)]^(k-1) dz, the band taken from the tail that does not
// cancel: Q(z) - Q(z + w). A node is skipped when a bound of its term in double precision (the
// band is below Q(z) and below Phi(z + w)) is under 1e-32: a change below 1e-29 in all.
Real range_cdf(const Real& w, int k) {
  static const InnerNodes nodes;
  if (w <= 0) return 0;
  const double wd = static_cast<double>(w);
  Real out = 0;
  for (std::size_t m = 0; m < nodes.z.size(); ++m) {
    const Real& z = nodes.z[m];
    const double zd = static_cast<double>(z);
    const double bound = std::min(static_cast<double>(nodes.tail[m]),
                                  0.5 * std::erfc(-(zd + wd) / std::sqrt(2.0)));
    if (k * static_cast<double>(nodes.weighted_phi[m]) * std::pow(bound, k - 1) < 1e-32) continue;
    const Real b = z > 0 ? nodes.tail[m] - upper_normal(z + w)
                         : upper_normal(-(z + w)) - nodes.head[m];
    if (b > 0) out += nodes.weighted_phi[m] * power(b, k - 1);
  }
  return k * out;
}

// Adaptive Gauss-Kronrod to an absolute error of 1e-26 (--fine: 1e-29) per piece (Boost's adaptive rule measures
// its tolerance relative to the piece's L1 norm, which a negligible piece never meets).
template <class F>
Real adaptive(const F& f, const Real& a, const Real& b, int depth) {
  Real error = 0;
  const Real v = GK::integrate(f, a, b, 0, 0, &error);
  if (error < (fine ? Real("1e-29") : Real("1e-26")) || depth == 0) return v;
  const Real mid = (a + b) / 2;
  return adaptive(f, a, mid, depth - 1) + adaptive(f, mid, b, depth - 1);
}

// log(h^h e^-h / Gamma(h)): Stirling's series from h = 1000 on (its terms below 1e-40 there;
// h log h - lgamma(h) directly would lose ~1e-34 h to cancellation).
Real log_scale_constant(const Real& h) {
  if (h < 1000) return h * log(h) - h - boost::multiprecision::lgamma(h);
  const Real r = 1 / h, r2 = r * r;
  return log(h) / 2 - log(boost::math::constants::two_pi<Real>()) / 2 -
         r * (Real(1) / 12 - r2 * (Real(1) / 360 - r2 * (Real(1) / 1260 - r2 * (Real(1) / 1680 -
                                                                              r2 / 1188))));
}

Real ptukey_reference(const Real& q, int k, double df) {
  if (std::isinf(df)) return range_cdf(q, k);
  const Real h = Real(df) / 2;
  // log f_df(s) = log 2 + h log h - h - lgamma(h) + (h - 1/2) log(1 + t) - h t, t = s^2 - 1:
  // no terms of size df that cancel (the plain (df - 1) log s - h s^2 loses ~1e-34 df, which
  // at df = 1e9 is noise the adaptive rule cannot integrate below 1e-26).
  const Real log_c = log(Real(2)) + log_scale_constant(h);
  auto log_dens = [&](const Real& s) {
    const Real t = (s - 1) * (s + 1);
    return log_c + (h - Real(0.5)) * log1p(t) - h * t;
  };
  auto f = [&](const Real& s) {
    if (s <= 0) return Real(0);
    return exp(log_dens(s)) * range_cdf(q * s, k);
  };
  const Real mode = df > 1 ? sqrt((Real(df) - 1) / Real(df)) : Real("0.1");
  const Real sd = 1 / sqrt(Real(2 * df));
  const Real peak = log_dens(mode), cut = log(Real("1e-45"));
  Real out = 0;
  // Pieces of 2 standard deviations from the mode outwards, each side until the density is
  // negligible (f_df is unimodal) or s reaches 0.
  for (int side : {-1, 1}) {
    for (int j = 0; j < 400; ++j) {
      Real a = mode + side * 2 * j * sd, b = mode + side * 2 * (j + 1) * sd;
      if (side < 0) std::swap(a, b);
      if (a <= 0) a = 0;
      if (b <= a) break;
      out += adaptive(f, a, b, 12);
      const Real edge = side < 0 ? a : b;
      if (edge <= 0 || log_dens(edge) - peak < cut) break;
    }
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<double> qs = {0.01, 0.05, 0.5, 1, 2, 3, 3.6, 4.5, 6, 8, 12, 20, 50};
  const std::vector<int> ks = {2, 3, 5, 10, 20, 40, 60, 100};
  // 2.5, 7.3, 12.5 and 1101.999999999954 (the demo's Kenward-Roger df) are not whole numbers, as
  // Satterthwaite and Kenward-Roger df are; 58 and 1160 are the demo's anova and model df.
  std::vector<double> dfs = {2,    2.5,  3,   5,   7.3, 10,  12.5, 30,  58,
                             100,  1101.999999999954, 1160, 1e4, 1e5, 1e7, 1e9,
                             std::numeric_limits<double>::infinity()};
  int first = 1;
  if (argc > 1 && std::string(argv[1]) == "--fine") {
    fine = true;
    first = 2;
  }
  if (argc > first) {  // only these df (Inf for infinity)
    dfs.clear();
    for (int i = first; i < argc; ++i) dfs.push_back(std::strtod(argv[i], nullptr));
  }
  std::printf("q,nmeans,df,ptukey,upper\n");
  for (const double df : dfs)
    for (const int k : ks)
      for (const double q : qs) {
        const Real p = ptukey_reference(Real(q), k, df);
        char df_text[32] = "Inf";
        if (!std::isinf(df)) std::snprintf(df_text, sizeof df_text, "%.17g", df);
        std::printf("%.17g,%d,%s,%s,%s\n", q, k, df_text, p.str(20, std::ios_base::scientific).c_str(),
                    Real(1 - p).str(20, std::ios_base::scientific).c_str());
        std::fflush(stdout);
      }
}

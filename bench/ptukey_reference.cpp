// ptukey_reference - high-precision values of the studentized range distribution, an independent
// reference for feint::models::ptukey (tests/models/test_studentized_range_reference.cpp reads
// the CSV this writes).
//
//   ptukey_reference [--fine] [DF ...] > tests/golden/models/ptukey_reference.csv
//   ptukey_reference --upper [DF ...] > tests/golden/models/ptukey_upper_reference.csv
// (--upper: P(Q > q) as its own integral, to ~1e-24 relative however small; see range_upper.)
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
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <boost/math/special_functions/gamma.hpp>
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


// ---- The upper tail P(Q > q) to ~1e-24 relative, for p down to 1e-300 and below (--upper).
//   P(range > w) = k int phi(z) [Q(z)^(k-1) - (Q(z) - Q(z + w))^(k-1)] dz
// (the minimum is at z with density k phi(z) Q(z)^(k-1), which integrates to 1; the range is at
// most w when the other k - 1 fall in [z, z + w]). With r = Q(z + w) / Q(z) the bracket is
// Q(z)^(k-1) r sum_{j < k-1} (1 - r)^j: positive terms, no cancellation. Its mass lies within 10
// of z = -w/2 (the bracket is below (k - 1) Q(z)^(k-2) Q(z + w), and phi(z) phi(z + w) falls by
// e^-100 there): 30-point Gauss-Legendre on pieces of width 2 (--fine: 1) of that window.
Real range_upper(const Real& w, int k) {
  if (w <= 0) return 1;
  const Real half = fine ? Real(0.5) : Real(1);
  const auto& x = GL::abscissa();
  const auto& wt = GL::weights();
  Real out = 0;
  auto term = [&](const Real& z) {
    const Real tail = upper_normal(z), r = upper_normal(z + w) / tail, a = 1 - r;
    Real sum = 0, pw = 1;
    for (int j = 0; j < k - 1; ++j, pw *= a) sum += pw;
    return exp(-z * z / 2) / boost::math::constants::root_two_pi<Real>() * power(tail, k - 2) *
           tail * r * sum;
  };
  const Real centre = -w / 2;
  for (Real a = centre - 10; a < centre + 10; a += 2 * half) {
    const Real mid = a + half;
    for (std::size_t i = 0; i < x.size(); ++i) {
      out += half * wt[i] * term(mid + half * x[i]);
      if (x[i] != 0) out += half * wt[i] * term(mid - half * x[i]);
    }
  }
  return k * out;
}

// 30-point Gauss-Legendre on [a, b].
template <class F>
Real legendre(const F& f, const Real& a, const Real& b) {
  const Real half = (b - a) / 2, mid = (a + b) / 2;
  Real out = 0;
  for (std::size_t i = 0; i < GL::abscissa().size(); ++i) {
    out += GL::weights()[i] * f(mid + half * GL::abscissa()[i]);
    if (GL::abscissa()[i] != 0) out += GL::weights()[i] * f(mid - half * GL::abscissa()[i]);
  }
  return half * out;
}

// The rule on [a, b] against the rule on its halves, halving until they agree to 1e-25 relative
// or below `floor` (absolute).
template <class F>
Real adaptive_relative(const F& f, const Real& a, const Real& b, const Real& whole,
                       const Real& floor, int depth) {
  const Real mid = (a + b) / 2, left = legendre(f, a, mid), right = legendre(f, mid, b);
  const Real error = abs(left + right - whole);
  if (error < Real("1e-25") * abs(left + right) || error < floor || depth == 0) return left + right;
  return adaptive_relative(f, a, mid, left, floor / 2, depth - 1) +
         adaptive_relative(f, mid, b, right, floor / 2, depth - 1);
}

// P(|T_df| > t), t_df Student's: the two-sided t tail (df = infinity: the normal's).
Real t_two_sided(const Real& t, double df) {
  if (std::isinf(df)) return 2 * upper_normal(t);
  return boost::math::ibeta(Real(df) / 2, Real(0.5), Real(df) / (Real(df) + t * t));
}

// P(Q > q) = int_0^inf f_df(s) P(range > q s) ds, in s (feint integrates in log s). Below s0,
// where P(range <= q s) <= k (q s phi(0))^(k-1) is under 1e-40, P(range > q s) is 1 and that part
// is P(s < s0) = P(chi2_df < df s0^2), a regularized gamma function. Above s0 the pieces double
// in width up to 2 standard deviations of f_df, which they keep; a piece is skipped (and on the
// right of the mode the loop ends) where its integrand's bound f_df(s) min(1, C(k, 2) P(|Z| >
// q s / sqrt 2)) times its width is below the floor, 1e-30 of the Bonferroni bound C(k, 2)
// P(|T_df| > q / sqrt 2) (which is at most C(k, 2) times P(Q > q)).
Real ptukey_upper_reference(const Real& q, int k, double df) {
  const Real pairs = Real(k) * (k - 1) / 2, root2 = boost::math::constants::root_two<Real>();
  const Real bonferroni = pairs * t_two_sided(q / root2, df);
  if (std::isinf(df)) return range_upper(q, k);
  if (bonferroni == 0) return 0;
  const Real floor = Real("1e-30") * bonferroni;
  const Real h = Real(df) / 2;
  const Real log_c = log(Real(2)) + log_scale_constant(h);
  auto log_dens = [&](const Real& s) {  // log1p(t) = 2 log s: below s = 1/2 that is exact
    const Real t = (s - 1) * (s + 1);
    return log_c + (h - Real(0.5)) * (s < Real(0.5) ? 2 * log(s) : log1p(t)) - h * t;
  };
  auto f = [&](const Real& s) {
    if (s <= 0) return Real(0);
    return exp(log_dens(s)) * range_upper(q * s, k);
  };
  auto bound = [&](const Real& s) {  // of the integrand, for s on the right of the mode
    return exp(log_dens(s)) *
           std::min(Real(1), pairs * 2 * upper_normal(q * s / root2));
  };
  const Real s0 = sqrt(boost::math::constants::two_pi<Real>()) *
                  exp(log(Real("1e-40") / k) / (k - 1)) / q;
  // (For df > 2000 and s0 < 1/2 that is below e^-300 and gamma_p's tgamma would overflow.)
  Real out = h > 1000 && s0 < Real(0.5) ? Real(0) : boost::math::gamma_p(h, h * s0 * s0);
  const Real mode = df > 1 ? sqrt((Real(df) - 1) / Real(df)) : Real("0.1");
  const Real sd = 1 / sqrt(Real(2 * df));
  for (Real a = s0; a < 1e6;) {
    const Real width = std::min(a, 2 * sd), b = a + width;
    const Real near = b < mode ? b : a;  // where f_df is largest on [a, b]
    const Real bd = exp(log_dens(near)) *
                    std::min(Real(1), pairs * 2 * upper_normal(q * a / root2));
    if (bd * width >= floor) out += adaptive_relative(f, a, b, legendre(f, a, b), floor, 14);
    else if (a > mode && bound(a) * 10 * sd < floor) break;
    a = b;
  }
  return out;
}

// The upper-tail grid (--upper, ~15 min of CPU): q from 1 to 1e15 (P down to 2e-30 at df = 2,
// and far below 1e-300 at large df), k 2..100, df 2..infinity; for k = 2 the relative difference
// from the closed form 2 P(T_df > q / sqrt 2) goes to stderr (measured: below 2e-24). Columns: q,
// nmeans, df, upper (P(Q > q), 20 digits).
int upper_grid(int argc, char** argv, int first) {
  const std::vector<double> qs = {1, 5, 12, 50, 1e4, 1e15};
  const std::vector<int> ks = {2, 5, 20, 100};
  std::vector<double> dfs = {2, 7.3, 30, 1160, 1e9, std::numeric_limits<double>::infinity()};
  if (argc > first) {
    dfs.clear();
    for (int i = first; i < argc; ++i) dfs.push_back(std::strtod(argv[i], nullptr));
  }
  std::printf("q,nmeans,df,upper\n");
  for (const double df : dfs)
    for (const int k : ks)
      for (const double q : qs) {
        const Real p = ptukey_upper_reference(Real(q), k, df);
        char df_text[32] = "Inf";
        if (!std::isinf(df)) std::snprintf(df_text, sizeof df_text, "%.17g", df);
        std::printf("%.17g,%d,%s,%s\n", q, k, df_text,
                    p.str(20, std::ios_base::scientific).c_str());
        if (k == 2 && p > 0)  // the check: for two means Q = sqrt(2) |T|
          std::fprintf(stderr, "k 2 q %g df %g: relative difference from 2 P(T > q / sqrt 2) %.3g\n", q,
                       df, static_cast<double>(abs(p / t_two_sided(Real(q) / sqrt(Real(2)), df) - 1)));
        std::fflush(stdout);
      }
  return 0;
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
  bool upper = false;
  for (; argc > first && argv[first][0] == '-' && argv[first][1] == '-'; ++first) {
    if (std::string(argv[first]) == "--fine") fine = true;
    if (std::string(argv[first]) == "--upper") upper = true;
  }
  if (upper) return upper_grid(argc, argv, first);
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

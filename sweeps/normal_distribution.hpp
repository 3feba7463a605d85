// The standard normal distribution on host and device: Phi (normal_cdf), its complement
// (normal_ccdf) and its inverse (normal_quantile).
//
// normal_quantile is Wichura's algorithm AS 241 (PPND16, Applied Statistics 37(3), 1988): three
// rational approximations of degree 7/7 (central region |p - 0.5| <= 0.425, then r = sqrt(-ln
// min(p, 1-p)) <= 5 and r > 5), relative accuracy about 1e-16 over p in [1e-316, 1 - 1e-16]. The
// coefficients are the published ones. It is evaluated from min(p, 1 - p), so the lower tail keeps
// full relative accuracy down to the smallest subnormal; the upper tail is limited by the spacing of
// doubles below 1 (the largest p < 1 is 1 - 2^-53, whose quantile is 8.2095...): callers that need a
// far upper tail pass the complement and negate (normal_quantile(q) = -normal_quantile(1 - q)), as
// the truncated normal in distribution.hpp does.
//
// normal_cdf uses erfc, which keeps relative accuracy in the lower tail (Phi(-37.5) = 4.6e-308);
// the functions come from Kokkos (Kokkos::Experimental in 3.4), so that they compile for every backend.
#pragma once
#include <Kokkos_Core.hpp>

namespace lsi::sweeps {

namespace detail {
#if KOKKOS_VERSION >= 30700
using Kokkos::erfc;
using Kokkos::exp;
using Kokkos::log;
using Kokkos::sqrt;
#else
using Kokkos::Experimental::erfc;
using Kokkos::Experimental::exp;
using Kokkos::Experimental::log;
using Kokkos::Experimental::sqrt;
#endif
KOKKOS_INLINE_FUNCTION constexpr double infinity() { return __builtin_huge_val(); }
KOKKOS_INLINE_FUNCTION constexpr double quiet_nan() { return __builtin_nan(""); }
constexpr double inv_sqrt2 = 0.70710678118654752440;
}  // namespace detail

// Phi(z) = P(Z <= z) = erfc(-z / sqrt(2)) / 2.
KOKKOS_INLINE_FUNCTION double normal_cdf(double z) {
  return 0.5 * detail::erfc(-z * detail::inv_sqrt2);
}

// 1 - Phi(z) = Phi(-z), accurate in the upper tail.
KOKKOS_INLINE_FUNCTION double normal_ccdf(double z) {
  return 0.5 * detail::erfc(z * detail::inv_sqrt2);
}

// The standard normal density.
KOKKOS_INLINE_FUNCTION double normal_pdf(double z) {
  return 0.39894228040143267794 * detail::exp(-0.5 * z * z);
}

// The central region of AS 241: Phi^-1(0.5 + q) for |q| <= 0.425.
KOKKOS_INLINE_FUNCTION double normal_quantile_central(double q) {
  const double r = 0.180625 - q * q;
  const double num = (((((((2.5090809287301226727e+3 * r + 3.3430575583588128105e+4) * r +
                           6.7265770927008700853e+4) *
                              r +
                          4.5921953931549871457e+4) *
                             r +
                         1.3731693765509461125e+4) *
                            r +
                        1.9715909503065514427e+3) *
                           r +
                       1.3314166789178437745e+2) *
                          r +
                      3.3871328727963666080e+0);
  const double den = (((((((5.2264952788528545610e+3 * r + 2.8729085735721942674e+4) * r +
                           3.9307895800092710610e+4) *
                              r +
                          2.1213794301586595867e+4) *
                             r +
                         5.3941960214247511077e+3) *
                            r +
                        6.8718700749205790830e+2) *
                           r +
                       4.2313330701600911252e+1) *
                          r +
                      1.0);
  return q * num / den;
}

// Phi^-1(p) for p in (0,1) (AS 241); -inf at p = 0, +inf at p = 1, NaN outside [0,1] or for NaN.
KOKKOS_INLINE_FUNCTION double normal_quantile(double p) {
  if (!(p >= 0.0 && p <= 1.0)) return detail::quiet_nan();
  if (p == 0.0) return -detail::infinity();
  if (p == 1.0) return detail::infinity();
  const double q = p - 0.5;
  if ((q < 0 ? -q : q) <= 0.425) return normal_quantile_central(q);
  double r = q < 0 ? p : 1.0 - p;
  r = detail::sqrt(-detail::log(r));
  double value;
  if (r <= 5.0) {
    r -= 1.6;
    const double num = (((((((7.74545014278341407640e-4 * r + 2.27238449892691845833e-2) * r +
                             2.41780725177450611770e-1) *
                                r +
                            1.27045825245236838258e+0) *
                               r +
                           3.64784832476320460504e+0) *
                              r +
                          5.76949722146069140550e+0) *
                             r +
                         4.63033784615654529590e+0) *
                            r +
                        1.42343711074968357734e+0);
    const double den = (((((((1.05075007164441684324e-9 * r + 5.47593808499534494600e-4) * r +
                             1.51986665636164571966e-2) *
                                r +
                            1.48103976427480074590e-1) *
                               r +
                           6.89767334985100004550e-1) *
                              r +
                          1.67638483018380384940e+0) *
                             r +
                         2.05319162663775882187e+0) *
                            r +
                        1.0);
    value = num / den;
  } else {
    r -= 5.0;
    const double num = (((((((2.01033439929228813265e-7 * r + 2.71155556874348757815e-5) * r +
                             1.24266094738807843860e-3) *
                                r +
                            2.65321895265761230930e-2) *
                               r +
                           2.96560571828504891230e-1) *
                              r +
                          1.78482653991729133580e+0) *
                             r +
                         5.46378491116411436990e+0) *
                            r +
                        6.65790464350110377720e+0);
    const double den = (((((((2.04426310338993978564e-15 * r + 1.42151175831644588870e-7) * r +
                             1.84631831751005468180e-5) *
                                r +
                            7.86869131145613259100e-4) *
                               r +
                           1.48753612908506148525e-2) *
                              r +
                          1.36929880922735805310e-1) *
                             r +
                         5.99832206555887937690e-1) *
                            r +
                        1.0);
    value = num / den;
  }
  return q < 0 ? -value : value;
}

// Phi^-1 of p[0..n) into out[0..n) (host code), the same bits as normal_quantile of each: the
// central region, where 85 % of uniform probabilities fall, for all n in a loop that GCC
// vectorises, then normal_quantile again for those outside it (the tails, 0, 1, NaN). out may be p.
inline void normal_quantile_each(const double* p, double* out, int n) {
  double central[64];
  for (int begin = 0; begin < n; begin += 64) {
    const int m = n - begin < 64 ? n - begin : 64;
#pragma GCC ivdep
    for (int k = 0; k < m; ++k) central[k] = normal_quantile_central(p[begin + k] - 0.5);
    for (int k = 0; k < m; ++k) {
      const double q = p[begin + k] - 0.5;
      out[begin + k] = (q < 0 ? -q : q) <= 0.425 ? central[k] : normal_quantile(p[begin + k]);
    }
  }
}

}  // namespace lsi::sweeps

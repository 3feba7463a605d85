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

#include "kernels/common/math.hpp"

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
// a b + c as the target computes a written a * b + c: rounded once where it has a fused
// multiply-add (GCC contracts the expression there), twice elsewhere. Written out, so that a
// constant argument folds at compile time to the bits the same call gives at run time.
KOKKOS_FORCEINLINE_FUNCTION double multiply_add(double a, double b, double c) {
#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__) || defined(__FMA__) || \
    defined(__ARM_FEATURE_FMA)
  return math::fused_multiply_add(a, b, c);
#else
  return a * b + c;
#endif
}
// c7 x^7 + ... + c0 in Horner's form, a multiply_add a step.
KOKKOS_FORCEINLINE_FUNCTION double horner7(double x, double c7, double c6, double c5, double c4,
                                           double c3, double c2, double c1, double c0) {
  double s = multiply_add(c7, x, c6);
  s = multiply_add(s, x, c5);
  s = multiply_add(s, x, c4);
  s = multiply_add(s, x, c3);
  s = multiply_add(s, x, c2);
  s = multiply_add(s, x, c1);
  return multiply_add(s, x, c0);
}
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
  const double r = detail::multiply_add(-q, q, 0.180625);
  const double num =
      detail::horner7(r, 2.5090809287301226727e+3, 3.3430575583588128105e+4,
                      6.7265770927008700853e+4, 4.5921953931549871457e+4, 1.3731693765509461125e+4,
                      1.9715909503065514427e+3, 1.3314166789178437745e+2, 3.3871328727963666080e+0);
  const double den =
      detail::horner7(r, 5.2264952788528545610e+3, 2.8729085735721942674e+4,
                      3.9307895800092710610e+4, 2.1213794301586595867e+4, 5.3941960214247511077e+3,
                      6.8718700749205790830e+2, 4.2313330701600911252e+1, 1.0);
  return q * num / den;
}

// The tails of AS 241: |Phi^-1(p)| from r = sqrt(-ln(min(p, 1 - p))) > sqrt(-ln(0.075)), the
// rational approximation for r <= 5 (near) and the one beyond (far).
KOKKOS_INLINE_FUNCTION double normal_quantile_tail_near(double r) {
  r -= 1.6;
  const double num = detail::horner7(r, 7.74545014278341407640e-4, 2.27238449892691845833e-2,
                                     2.41780725177450611770e-1, 1.27045825245236838258e+0,
                                     3.64784832476320460504e+0, 5.76949722146069140550e+0,
                                     4.63033784615654529590e+0, 1.42343711074968357734e+0);
  const double den = detail::horner7(r, 1.05075007164441684324e-9, 5.47593808499534494600e-4,
                                     1.51986665636164571966e-2, 1.48103976427480074590e-1,
                                     6.89767334985100004550e-1, 1.67638483018380384940e+0,
                                     2.05319162663775882187e+0, 1.0);
  return num / den;
}
KOKKOS_INLINE_FUNCTION double normal_quantile_tail_far(double r) {
  r -= 5.0;
  const double num = detail::horner7(r, 2.01033439929228813265e-7, 2.71155556874348757815e-5,
                                     1.24266094738807843860e-3, 2.65321895265761230930e-2,
                                     2.96560571828504891230e-1, 1.78482653991729133580e+0,
                                     5.46378491116411436990e+0, 6.65790464350110377720e+0);
  const double den = detail::horner7(r, 2.04426310338993978564e-15, 1.42151175831644588870e-7,
                                     1.84631831751005468180e-5, 7.86869131145613259100e-4,
                                     1.48753612908506148525e-2, 1.36929880922735805310e-1,
                                     5.99832206555887937690e-1, 1.0);
  return num / den;
}
KOKKOS_INLINE_FUNCTION double normal_quantile_tail(double r) {
  return r <= 5.0 ? normal_quantile_tail_near(r) : normal_quantile_tail_far(r);
}

// Phi^-1(p) for p in (0,1) (AS 241); -inf at p = 0, +inf at p = 1, NaN outside [0,1] or for NaN.
KOKKOS_INLINE_FUNCTION double normal_quantile(double p) {
  if (!(p >= 0.0 && p <= 1.0)) return detail::quiet_nan();
  if (p == 0.0) return -detail::infinity();
  if (p == 1.0) return detail::infinity();
  const double q = p - 0.5;
  if ((q < 0 ? -q : q) <= 0.425) return normal_quantile_central(q);
  const double value = normal_quantile_tail(detail::sqrt(-detail::log(q < 0 ? p : 1.0 - p)));
  return q < 0 ? -value : value;
}

// Phi^-1 of p[0..n) into out[0..n) (host code), the same bits as normal_quantile of each, 64
// values at a time: the central region, where 85 % of uniform probabilities fall, for all of
// them in a loop that GCC vectorises; the others' places listed without a branch; their
// logarithms from the C library, one call each; their square roots and both tails' rational
// approximations in a second vectorised loop, each value taking the one its r asks for. The
// probabilities outside (0, 1) and NaN go through normal_quantile. out may be p.
inline void normal_quantile_each(const double* p, double* out, int n) {
  constexpr int B = 64;
  alignas(64) double central[B], tail_p[B], tail_v[B];
  int tail_at[B];
  for (int begin = 0; begin < n; begin += B) {
    const int m = n - begin < B ? n - begin : B;
    const double* pb = p + begin;
    double* ob = out + begin;
#pragma GCC ivdep
    for (int k = 0; k < m; ++k) central[k] = normal_quantile_central(pb[k] - 0.5);
    int tails = 0;
    for (int k = 0; k < m; ++k) {
      const double q = pb[k] - 0.5;
      tail_at[tails] = k;
      tail_p[tails] = pb[k];
      tails += (q < 0 ? -q : q) <= 0.425 ? 0 : 1;
    }
    for (int k = 0; k < m; ++k) ob[k] = central[k];
    if (tails == 0) continue;
    for (int i = 0; i < tails; ++i) {
      const double pi = tail_p[i];
      const double x = pi - 0.5 < 0 ? pi : 1.0 - pi;
      tail_v[i] = -detail::log(x > 0.0 ? x : 0.5);  // 0.5: a placeholder for 0, 1 and the rest
    }
#pragma GCC ivdep
    for (int i = 0; i < tails; ++i) {
      const double r = detail::sqrt(tail_v[i]);
      const double near_value = normal_quantile_tail_near(r);
      const double far_value = normal_quantile_tail_far(r);
      const double value = r <= 5.0 ? near_value : far_value;
      tail_v[i] = tail_p[i] - 0.5 < 0 ? -value : value;
    }
    for (int i = 0; i < tails; ++i) {
      const double pi = tail_p[i];
      ob[tail_at[i]] = pi > 0.0 && pi < 1.0 ? tail_v[i] : normal_quantile(pi);
    }
  }
}

}  // namespace lsi::sweeps

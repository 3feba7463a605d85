// x^y for x >= 0 without a branch or a library call, so that a loop over samples that needs it
// vectorises (the empirical model's alpha = a1 Fr^a2 in the batched closed forms; libm's pow is
// a scalar call that stops GCC from vectorising the loop).
//
// Method: x^y = exp(y log x), with log x and the product y log x carried in two doubles (hi + lo)
// so that the exponent's rounding error does not grow with |y log x|.
//   log:  x = 2^e m with m in [sqrt(1/2), sqrt(2)) taken from the bits (subnormal x scaled by
//         2^54 first); log m = 2 atanh(s), s = (m - 1) / (m + 1), |s| <= 0.1716, s in two
//         doubles (m - 1 is exact, 2 + (m - 1) carries its error); the series 2 s + 2 s^3 / 3 +
//         ... + 2 s^23 / 23 (the first neglected term is below 2e-20 of the result) with its two
//         leading terms in two doubles; e ln 2 with ln 2 split so that e ln2_hi is exact.
//   exp:  k = round((y log x) / ln 2), r = y log x - k ln 2 (|r| <= 0.35, its error kept),
//         exp(r) = 1 + r + r^2 (1/2! + ... + r^12 / 14!) (the first neglected term is below
//         1e-19), 1 + r summed exactly, times 2^k built from the bits in two factors (so that
//         results near the overflow and underflow thresholds need no special case).
// Accuracy: within 1 ulp of the correctly rounded x^y wherever the result is a normal double
// (the exponent y log x is carried to ~2^-100 relative, so the error does not grow with it);
// tests/kernels/common/test_pow_nonnegative.cpp measures it against long double libm.
// Special values as pow: x^0 = 1 and 1^y = 1 (also for NaN), NaN otherwise for a NaN operand,
// 0^y = +inf (y < 0) or 0 (y > 0), inf^y = 0 (y < 0) or inf (y > 0), overflow to inf and
// underflow to 0. Unlike pow, a negative x gives NaN for every y != 0 (also an integer y).
// Uses fused multiply-adds: fast where the hardware has them (-march=native on x86-64, GPUs).
#pragma once
#include <Kokkos_Macros.hpp>
#include <cstdint>
#include <cstring>

namespace lsi::math {

namespace pow_detail {

KOKKOS_FORCEINLINE_FUNCTION std::uint64_t bits_of(double x) {
  std::uint64_t u;
  memcpy(&u, &x, sizeof u);
  return u;
}
KOKKOS_FORCEINLINE_FUNCTION double double_of(std::uint64_t u) {
  double x;
  memcpy(&x, &u, sizeof x);
  return x;
}
KOKKOS_FORCEINLINE_FUNCTION double fused_multiply_add(double a, double b, double c) {
#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__)
  return ::fma(a, b, c);
#else
  return __builtin_fma(a, b, c);
#endif
}

// ln 2 = ln2_hi + ln2_lo, ln2_hi with 32 significant bits: k ln2_hi is exact for |k| < 2^21.
inline constexpr double ln2_hi = 6.93147180369123816490e-01;
inline constexpr double ln2_lo = 1.90821492927058770002e-10;
// 1.5 * 2^52: v + round_shift - round_shift rounds v to an integer (|v| < 2^51), and the bits of
// v + round_shift hold that integer in their low bits.
inline constexpr double round_shift = 6755399441055744.0;

// log x = hi + lo for a finite x > 0 (subnormals included).
KOKKOS_FORCEINLINE_FUNCTION void log_two_doubles(double x, double& hi, double& lo) {
  const bool tiny = x < 2.2250738585072014e-308;         // subnormal: scale into the normal range
  const double xs = tiny ? x * 18014398509481984.0 : x;  // 2^54
  const std::uint64_t u = bits_of(xs);
  // The biased exponent as a double, without an integer conversion: 2^52 + field - 2^52.
  const double biased = double_of((u >> 52) | 0x4330000000000000ull) - 4503599627370496.0;
  double m = double_of((u & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull);  // [1, 2)
  const bool high = m > 1.4142135623730951;
  m = high ? 0.5 * m : m;  // exact
  const double e = biased - 1023.0 + (high ? 1.0 : 0.0) - (tiny ? 54.0 : 0.0);
  // s = f / (2 + f), f = m - 1 exact (Sterbenz); 2 + f = v + v_lo exactly.
  const double f = m - 1.0;
  const double v = 2.0 + f;
  const double v_lo = f - (v - 2.0);
  // One division: s = f (1/v) is within an ulp or two of f / v, and the remainder
  // f - s v (exact by the fused multiply-add) times 1/v restores what s lacks to ~2^-104.
  const double inv_v = 1.0 / v;
  const double s = f * inv_v;
  const double s_lo = (fused_multiply_add(-s, v, f) - s * v_lo) * inv_v;
  // log m = 2 s + (2/3) s^3 + s^5 (2/5 + 2/7 s^2 + ... + 2/23 s^18): 2 s and (2/3) s^3 in two
  // doubles each (the latter is up to 1 % of log m), the rest (below 2e-4 of it) in one.
  const double z = s * s;
  const double z_lo = fused_multiply_add(s, s, -z);
  const double cube = s * z;
  const double cube_lo = fused_multiply_add(s, z, -cube) + s * z_lo;
  constexpr double two_thirds_hi = 0.66666666666666663;     // nearest double to 2/3
  constexpr double two_thirds_lo = 3.7007434154171883e-17;  // 2/3 - two_thirds_hi
  const double third = cube * two_thirds_hi;
  const double third_lo = fused_multiply_add(cube, two_thirds_hi, -third) +
                          (cube * two_thirds_lo + cube_lo * two_thirds_hi);
  // In Estrin's order (pairs, then powers z^2, z^4, z^8): a shorter chain of dependent
  // multiply-adds than Horner's, so that the vectorised loops calling this overlap more work.
  const double z2 = z * z, z4 = z2 * z2, z8 = z4 * z4;
  const double p01 = fused_multiply_add(2.0 / 7.0, z, 2.0 / 5.0);
  const double p23 = fused_multiply_add(2.0 / 11.0, z, 2.0 / 9.0);
  const double p45 = fused_multiply_add(2.0 / 15.0, z, 2.0 / 13.0);
  const double p67 = fused_multiply_add(2.0 / 19.0, z, 2.0 / 17.0);
  const double p89 = fused_multiply_add(2.0 / 23.0, z, 2.0 / 21.0);
  const double p03 = fused_multiply_add(p23, z2, p01);
  const double p47 = fused_multiply_add(p67, z2, p45);
  const double p = fused_multiply_add(p89, z8, fused_multiply_add(p47, z4, p03));
  const double twice_s = 2.0 * s;
  const double log_m_hi = twice_s + third;  // Fast2Sum: |2 s| > |third|
  const double log_m_lo =
      (third - (log_m_hi - twice_s)) + third_lo + (2.0 * s_lo + 2.0 * z * s_lo) + (cube * z) * p;
  // e ln 2 + log m: the high parts summed with their error kept (TwoSum), then normalised.
  const double a = e * ln2_hi;  // exact
  const double sum = a + log_m_hi;
  const double b_virtual = sum - a;
  const double sum_error = (a - (sum - b_virtual)) + (log_m_hi - b_virtual);
  const double rest = e * ln2_lo + log_m_lo + sum_error;
  hi = sum + rest;
  lo = rest - (hi - sum);
}

// exp(hi + lo) for |lo| at most a few ulp of hi; hi may be +-inf or NaN.
KOKKOS_FORCEINLINE_FUNCTION double exp_two_doubles(double hi, double lo) {
  constexpr double limit = 1100.0;  // exp(1100) overflows, exp(-1100) underflows to 0
  const bool in_range = (hi >= -limit) & (hi <= limit);
  double t = hi > limit ? limit : hi;  // NaN stays NaN
  t = hi < -limit ? -limit : t;
  const double t_lo = in_range ? lo : 0.0;
  const double k = (t * 1.4426950408889634 + round_shift) - round_shift;  // round(t / ln 2)
  // r + r_lo = t + t_lo - k ln 2: t - k ln2_hi is exact (Sterbenz), the rest summed with its
  // error kept (TwoSum), so that r_lo is of the order of an ulp of r.
  const double r_exact = fused_multiply_add(-k, ln2_hi, t);
  const double k_lo = k * ln2_lo;
  const double r = r_exact - k_lo;
  const double r_virtual = r - r_exact;
  const double r_lo = ((r_exact - (r - r_virtual)) + (-k_lo - r_virtual)) + t_lo;
  // exp(r) - 1 - r = r^2 q(r), the Taylor terms up to r^14 / 14!.
  // Estrin's order, as the logarithm's series.
  const double r2 = r * r, r4 = r2 * r2, r8 = r4 * r4;
  const double q01 = fused_multiply_add(1.0 / 6.0, r, 0.5);                         // 1/2!, 1/3!
  const double q23 = fused_multiply_add(1.0 / 120.0, r, 1.0 / 24.0);                // 1/4!, 1/5!
  const double q45 = fused_multiply_add(1.0 / 5040.0, r, 1.0 / 720.0);              // 1/6!, 1/7!
  const double q67 = fused_multiply_add(1.0 / 362880.0, r, 1.0 / 40320.0);          // 1/8!, 1/9!
  const double q89 = fused_multiply_add(1.0 / 39916800.0, r, 1.0 / 3628800.0);      // 1/10!, 1/11!
  const double qab = fused_multiply_add(1.0 / 6227020800.0, r, 1.0 / 479001600.0);  // 1/12!, 1/13!
  const double q03 = fused_multiply_add(q23, r2, q01);
  const double q47 = fused_multiply_add(q67, r2, q45);
  const double q8c = fused_multiply_add(1.0 / 87178291200.0, r4,  // 1/14!
                                        fused_multiply_add(qab, r2, q89));
  const double q = fused_multiply_add(q8c, r8, fused_multiply_add(q47, r4, q03));
  const double expm1_r = r + r2 * q;
  // exp(r + r_lo) = 1 + r + (r^2 q + r_lo (1 + expm1 r)), with 1 + r summed exactly (Fast2Sum).
  const double one_plus_r = 1.0 + r;
  const double one_plus_r_error = r - (one_plus_r - 1.0);
  const double tail = r2 * q + r_lo * (1.0 + expm1_r) + one_plus_r_error;
  const double mantissa = one_plus_r + tail;
  // 2^k as 2^k1 2^k2, k1 = round(k / 2): each within the normal exponents for |k| <= 1587.
  const double k1 = (0.5 * k + round_shift) - round_shift;
  const double k2 = k - k1;
  const std::uint64_t k1_bits = bits_of(k1 + round_shift);  // 0x4338000000000000 + k1
  const std::uint64_t k2_bits = bits_of(k2 + round_shift);
  const double scale1 = double_of((k1_bits + 1023u) << 52);
  const double scale2 = double_of((k2_bits + 1023u) << 52);
  return (mantissa * scale1) * scale2;
}

}  // namespace pow_detail

KOKKOS_FORCEINLINE_FUNCTION double pow_nonnegative(double x, double y) {
  using namespace pow_detail;
  constexpr double inf = __builtin_huge_val();
  const bool regular = (x > 0.0) & (x < inf);  // false for 0, inf, NaN and negative x
  double log_hi = 0.0, log_lo = 0.0;
  log_two_doubles(regular ? x : 1.0, log_hi, log_lo);
  const double t_hi = y * log_hi;
  const double t_lo = fused_multiply_add(y, log_hi, -t_hi) + y * log_lo;
  const double power = exp_two_doubles(t_hi, t_lo);
  // Special operands, in pow's order of precedence; one condition a select, so that GCC
  // if-converts them (it gives up on a select of more than four values).
  double r = power;
  const double of_zero = y > 0.0 ? 0.0 : inf;  // y < 0; y = 0 and y NaN below
  r = x == 0.0 ? of_zero : r;
  const double of_inf = y > 0.0 ? inf : 0.0;
  r = x == inf ? of_inf : r;
  r = (x != x) | (y != y) | (x < 0.0) ? __builtin_nan("") : r;
  r = (y == 0.0) | (x == 1.0) ? 1.0 : r;
  return r;
}

}  // namespace lsi::math

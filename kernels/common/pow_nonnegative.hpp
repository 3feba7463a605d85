// x^y for x >= 0 without a branch or a library call, so that a loop over samples that needs it
// vectorises (the empirical model's alpha = a1 Fr^a2 in the batched closed forms; libm's pow is
// a scalar call that stops GCC from vectorising the loop).
//
// Method: x^y = exp(y log x), with log x and the product y log x carried in two doubles (hi + lo)
// so that the exponent's rounding error does not grow with |y log x|. Two ways to the same
// accuracy: on the host from lookup tables (pow_tables.hpp, written by
// tools/generate_pow_tables.py), fewer operations per value; on a GPU from series alone, no table
// in device memory.
//   log, tables: x = 2^e z, z in [0.703, 1.41) split into 16 sub-intervals by the leading bits of
//         its significand (subnormal x scaled by 2^54 first); with c the centre of z's
//         sub-interval (c = 1 for the one holding 1), log x = e ln 2 + log c + log(1 + r),
//         r = z/c - 1, |r| < 1.01 2^-5: z/c exact in two doubles by a fused multiply-add, the
//         series of log(1 + r) up to r^14 (first neglected term below 2^-78) with r - r^2/2 +
//         r^3/3 in two doubles; 1/c and log c (in two doubles) from the table.
//   log, series: x = 2^e m with m in [sqrt(1/2), sqrt(2)); log m = 2 atanh(s), s = (m - 1) /
//         (m + 1), |s| <= 0.1716, s in two doubles; the series 2 s + 2 s^3 / 3 + ... + 2 s^23 / 23
//         (the first neglected term is below 2e-20 of the result) with its two leading terms in
//         two doubles.
//   Both add e ln 2 with ln 2 split so that e ln2_hi is exact.
//   exp, tables: t = y log x = n ln2/16 + r, |r| <= ln2/32, exp t = 2^k 2^(j/16) exp(r) with
//         n = 16 k + j, 0 <= j < 16: 2^(j/16) in two doubles from the table, exp(r) - 1 by its
//         series up to r^8 (first neglected term below 2^-68).
//   exp, series: t = k ln 2 + r, |r| <= 0.35 (its error kept), exp(r) = 1 + r + r^2 (1/2! + ... +
//         r^12 / 14!) (the first neglected term is below 1e-19), 1 + r summed exactly.
//   Both build 2^k from the bits in two factors, so that results near the overflow and underflow
//   thresholds need no special case.
//   The tables have 16 entries so that eight lanes of an AVX-512 register read them with one
//   permute each (simd_lanes.hpp, pow_nonnegative_each); the tables' way is one template for one
//   lane and for eight, with the same bits.
// Accuracy: within 1 ulp of the correctly rounded x^y wherever the result is a normal double
// (the exponent y log x is carried to ~2^-66 relative, so the error does not grow with it);
// tests/kernels/common/test_pow_nonnegative.cpp measures both ways against long double libm.
// Special values as pow: x^0 = 1 and 1^y = 1 (also for NaN), NaN otherwise for a NaN operand,
// 0^y = +inf (y < 0) or 0 (y > 0), inf^y = 0 (y < 0) or inf (y > 0), overflow to inf and
// underflow to 0. Unlike pow, a negative x gives NaN for every y != 0 (also an integer y).
// Uses fused multiply-adds: fast where the hardware has them (-march=native on x86-64, GPUs).
#pragma once
#include <Kokkos_Macros.hpp>
#include <cstdint>
#include <cstring>

#include "kernels/common/math.hpp"
#include "kernels/common/pow_tables.hpp"
#include "kernels/common/simd_lanes.hpp"

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
using math::fused_multiply_add;

// ln 2 = ln2_hi + ln2_lo, ln2_hi with 32 significant bits: k ln2_hi is exact for |k| < 2^21.
inline constexpr double ln2_hi = 6.93147180369123816490e-01;
inline constexpr double ln2_lo = 1.90821492927058770002e-10;
// 1.5 * 2^52: v + round_shift - round_shift rounds v to an integer (|v| < 2^51), and the bits of
// v + round_shift hold that integer in their low bits.
inline constexpr double round_shift = 6755399441055744.0;

// log x = hi + lo for a finite x > 0 (subnormals included).
KOKKOS_FORCEINLINE_FUNCTION void log_two_doubles_series(double x, double& hi, double& lo) {
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
KOKKOS_FORCEINLINE_FUNCTION double exp_two_doubles_series(double hi, double lo) {
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

// The tables' way, written once over a lane type (simd_lanes.hpp): Real is double, or eight
// doubles (lanes::V8) where the host has AVX-512, with the same bits in every lane. Host
// functions (the tables are host memory), called from pow_nonnegative only where it is compiled
// for the host. The tables have 16 entries, so that eight lanes read one column with one
// two-register permute instead of eight scalar loads; the price is the longer series below.

// log x = hi + lo for a finite x > 0 (subnormals included), from the tables: x = 2^e z with z
// in [0.703, 1.41) in one of 16 sub-intervals with centre c, log x = e ln 2 + log c +
// log(1 + r), r = z/c - 1, |r| < 2^-5 (1.01 2^-5 with 1/c rounded).
template <class Real>
inline void log_two_doubles_table(Real x, Real& hi, Real& lo) {
  const Real one = lanes::splat<Real>(1.0);
  // Subnormal (exponent field 0): scaled by 2^54 into the normal range. Tested on the bits, not
  // as x < DBL_MIN: GCC then does not thread it with the caller's tests of x, which would leave
  // branches the vectoriser cannot if-convert.
  // The product is taken for every x (by 1 for the others): a multiplication only on one branch
  // could trap under -ftrapping-math, which stops GCC from if-converting it.
  const auto tiny = (lanes::bits_of(x) >> 52) == 0;
  const auto u = lanes::bits_of(x * (tiny ? lanes::splat<Real>(18014398509481984.0) : one));
  const auto shifted = u - log_table_offset;
  const auto i = (shifted >> (52 - log_table_bits)) & ((1u << log_table_bits) - 1);
  const auto exponent =
      (lanes::signed_of(shifted) >> 52) - (tiny ? 54ll : 0ll);  // arithmetic shift
  const Real z = lanes::real_of(u - (shifted & 0xFFF0000000000000ull));
  // The exponent as a double from the bits of round_shift + exponent (no conversion
  // instruction, which could raise "inexact" and so is not if-converted either).
  const Real shift = lanes::splat<Real>(round_shift);
  const Real e = lanes::real_of(lanes::bits_of(shift) + lanes::unsigned_of(exponent)) - shift;
  const Real inverse_centre = lanes::lookup16(log_inverse_centre, i);
  // z / c = p + p_lo exactly; r = p - 1 exact (Sterbenz), so z / c - 1 = r + p_lo.
  const Real p = z * inverse_centre;
  const Real p_lo = lanes::fused_multiply_add(z, inverse_centre, -p);
  const Real r = p - one;
  // log(1 + r + p_lo) = r - r^2/2 + r^3/3 + r^4 (-1/4 + r/5 - ... - r^10/14)
  // + p_lo (1 - r + r^2 - r^3): the terms up to r^14 (the first neglected one below 2^-78).
  // -r^2/2 exactly and r^3/3 with its error kept (each two doubles): their roundings would
  // reach 2^-64 of log x; the rest, below 2^-22, is rounded once.
  const Real half_r = 0.5 * r;
  const Real square_hi = -half_r * r;  // -r^2/2 = square_hi + square_lo exactly
  const Real square_lo = lanes::fused_multiply_add(-half_r, r, -square_hi);
  const Real r2 = r * r;
  const Real r2_lo = lanes::fused_multiply_add(r, r, -r2);
  const Real cube = r * r2;
  const Real cube_lo = lanes::fused_multiply_add(r, r2, -cube) + r * r2_lo;
  constexpr double third_hi = 0.33333333333333331;     // nearest double to 1/3
  constexpr double third_lo = 1.8503717077085942e-17;  // 1/3 - third_hi
  const Real third = cube * third_hi;
  const Real third_error = lanes::fused_multiply_add(cube, lanes::splat<Real>(third_hi), -third) +
                           (cube * third_lo + cube_lo * third_hi);
  // In Estrin's order: pairs of terms, then r^2 and r^4.
  const Real r4 = r2 * r2;
  const auto pair = [&r](double odd, double even) {
    return lanes::fused_multiply_add(lanes::splat<Real>(odd), r, lanes::splat<Real>(even));
  };
  const Real c45 = pair(1.0 / 5.0, -1.0 / 4.0);
  const Real c67 = pair(1.0 / 7.0, -1.0 / 6.0);
  const Real c89 = pair(1.0 / 9.0, -1.0 / 8.0);
  const Real c1011 = pair(1.0 / 11.0, -1.0 / 10.0);
  const Real c1214 =
      lanes::fused_multiply_add(lanes::splat<Real>(-1.0 / 14.0), r2, pair(1.0 / 13.0, -1.0 / 12.0));
  const Real q = lanes::fused_multiply_add(
      lanes::fused_multiply_add(c1214, r4, lanes::fused_multiply_add(c1011, r2, c89)), r4,
      lanes::fused_multiply_add(c67, r2, c45));
  const Real series = r4 * q;
  const Real correction =
      p_lo * lanes::fused_multiply_add(r, lanes::fused_multiply_add(r, one - r, -one), one);
  // e ln2_hi + log_c_hi is exact (both multiples of 2^-43); the three sums after it are exact up
  // to an error kept (Fast2Sum: each addend is the smaller, or the running sum is 0).
  const Real s =
      lanes::fused_multiply_add(e, lanes::splat<Real>(ln2_hi), lanes::lookup16(log_centre_hi, i));
  const Real h = s + r;
  const Real h_error = (s - h) + r;
  const Real h2 = h + square_hi;
  const Real h2_error = (h - h2) + square_hi;
  const Real h3 = h2 + third;
  const Real h3_error = (h2 - h3) + third;
  const Real rest =
      h_error + h2_error + h3_error + square_lo + third_error + series + correction +
      lanes::fused_multiply_add(e, lanes::splat<Real>(ln2_lo), lanes::lookup16(log_centre_lo, i));
  hi = h3 + rest;
  lo = rest - (hi - h3);
}

// exp(hi + lo) for |lo| at most a few ulp of hi; hi may be +-inf or NaN. From the table:
// hi + lo = (16 k + j) ln2/16 + r, |r| <= ln2/32, exp = 2^k 2^(j/16) exp(r).
template <class Real>
inline Real exp_two_doubles_table(Real hi, Real lo) {
  constexpr double limit = 1100.0;  // exp(1100) overflows, exp(-1100) underflows to 0
  // Computed for every hi, also outside [-limit, limit] (the table index is masked, so any hi is
  // safe) and replaced at the end: clamping hi first lets GCC fold the clamped path into
  // constants, which leaves the table loads on one branch only and stops the vectoriser.
  constexpr double steps_per_ln2 = 16.0 * 1.4426950408889634;
  // ln2/16 = step_hi + step_lo, step_hi with 32 significant bits: n step_hi is exact.
  constexpr double step_hi = ln2_hi / 16.0;
  constexpr double step_lo = ln2_lo / 16.0;
  const Real shift = lanes::splat<Real>(round_shift);
  const Real n_shifted = hi * steps_per_ln2 + shift;
  const Real n = n_shifted - shift;  // round(hi 16 / ln 2)
  // r = hi - n ln2/16: hi - n step_hi exact (Sterbenz); the rest rounded (each rounding below
  // 2^-58 of the result).
  const Real r =
      (lanes::fused_multiply_add(-n, lanes::splat<Real>(step_hi), hi) - n * step_lo) + lo;
  // exp(r) - 1 = r + r^2 (1/2 + r/6 + ... + r^6/8!): the first neglected term is below 2^-68.
  const Real r2 = r * r, r4 = r2 * r2;
  const auto pair = [&r](double odd, double even) {
    return lanes::fused_multiply_add(lanes::splat<Real>(odd), r, lanes::splat<Real>(even));
  };
  const Real q46 = lanes::fused_multiply_add(lanes::splat<Real>(1.0 / 40320.0), r2,
                                             pair(1.0 / 5040.0, 1.0 / 720.0));
  const Real q = lanes::fused_multiply_add(
      q46, r4, lanes::fused_multiply_add(pair(1.0 / 120.0, 1.0 / 24.0), r2, pair(1.0 / 6.0, 0.5)));
  const Real expm1_r = lanes::fused_multiply_add(r2, q, r);
  const auto n_bits = lanes::bits_of(n_shifted);  // 0x4338000000000000 + n
  const auto j = n_bits & ((1u << exp_table_bits) - 1);
  const Real power_hi = lanes::lookup16(exp_power_hi, j);
  const Real mantissa =
      power_hi + lanes::fused_multiply_add(power_hi, expm1_r, lanes::lookup16(exp_power_lo, j));
  // 2^k as 2^k1 2^k2, k1 = floor(k / 2): each within the normal exponents for |k| <= 1587.
  const auto k = lanes::signed_of(n_bits - lanes::bits_of(shift)) >> exp_table_bits;
  const auto k1 = k >> 1;
  const auto k2 = k - k1;
  const Real scale1 = lanes::real_of(lanes::unsigned_of(k1 + 1023) << 52);
  const Real scale2 = lanes::real_of(lanes::unsigned_of(k2 + 1023) << 52);
  const Real power = (mantissa * scale1) * scale2;
  const Real outside =
      hi > 0.0 ? lanes::splat<Real>(__builtin_huge_val()) : lanes::splat<Real>(0.0);
  return (hi > limit) | (hi < -limit) ? outside : power;  // NaN: power is NaN
}

// x^y from x, y and the power exp(y log x): pow's results for the special operands.
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION Real with_special_operands(Real x, Real y, Real power) {
  constexpr double inf = __builtin_huge_val();
  const Real zero{};
  // In pow's order of precedence; one condition a select, so that GCC if-converts them (it gives
  // up on a select of more than four values).
  Real r = power;
  const Real of_zero = y > 0.0 ? zero : zero + inf;  // y < 0; y = 0 and y NaN below
  r = x == 0.0 ? of_zero : r;
  const Real of_inf = y > 0.0 ? zero + inf : zero;
  r = x == inf ? of_inf : r;
  r = (x != x) | (y != y) | (x < 0.0) ? zero + __builtin_nan("") : r;
  r = (y == 0.0) | (x == 1.0) ? zero + 1.0 : r;
  return r;
}

// Every x goes through the log, also 0, inf, NaN and negative x (finite garbage or NaN, no trap,
// no index outside the tables), and is replaced by with_special_operands: a select of x before
// the log lets GCC thread the log's own tests with it into branches that the vectoriser cannot
// if-convert.
KOKKOS_FORCEINLINE_FUNCTION double pow_by_series(double x, double y) {
  double log_hi = 0.0, log_lo = 0.0;
  log_two_doubles_series(x, log_hi, log_lo);
  const double t_hi = y * log_hi;
  const double t_lo = fused_multiply_add(y, log_hi, -t_hi) + y * log_lo;
  return with_special_operands(x, y, exp_two_doubles_series(t_hi, t_lo));
}

template <class Real>
inline Real pow_by_tables(Real x, Real y) {
  Real log_hi{}, log_lo{};
  log_two_doubles_table(x, log_hi, log_lo);
  const Real t_hi = y * log_hi;
  const Real t_lo = lanes::fused_multiply_add(y, log_hi, -t_hi) + y * log_lo;
  return with_special_operands(x, y, exp_two_doubles_table(t_hi, t_lo));
}

}  // namespace pow_detail

// The tables on the host; the series on a GPU, where the tables would have to live in device
// memory and the arithmetic is cheap next to a lookup.
KOKKOS_FORCEINLINE_FUNCTION double pow_nonnegative(double x, double y) {
#if !defined(__CUDA_ARCH__) && !defined(__HIP_DEVICE_COMPILE__)
  return pow_detail::pow_by_tables<double>(x, y);
#else
  return pow_detail::pow_by_series(x, y);
#endif
}

// out[k] = x[k]^y for k < n (pow_nonnegative's results, bit for bit): on a host with AVX-512
// eight values at a time through the tables' way written for eight lanes (simd_lanes.hpp), the
// rest one at a time. A host function, for the batched models' blocks (closed_form/batch.hpp).
inline void pow_nonnegative_each(const double* x, double y, double* out, int n) {
  int k = 0;
#if LSI_HOST_SIMD_LANES
  const lanes::V8 exponent = lanes::splat<lanes::V8>(y);
  for (; k + 8 <= n; k += 8)
    lanes::store8(out + k, pow_detail::pow_by_tables(lanes::load8(x + k), exponent));
#endif
  for (; k < n; ++k) out[k] = pow_detail::pow_by_tables<double>(x[k], y);
}

}  // namespace lsi::math

// sin and cos of an angle in the first quadrant, [0, pi/2], without a branch or a library call,
// so that a loop over samples that needs them vectorises (the batched closed-form models resolve
// the impact force on the barrier's face angle, which every scene and study keeps in (0, 90 deg]).
// libm's sin/cos are scalar calls that stop GCC from vectorising such a loop.
//
// Method: for x <= pi/4 the Taylor series of sin and cos about 0 are summed directly (r = x); for
// x > pi/4 they are summed at r = pi/2 - x and swapped (sin x = cos r, cos x = sin r), with pi/2
// split into two doubles so that r carries no cancellation error (pi/2 - x is exact for x in
// [pi/4, pi/2], Sterbenz). On |r| <= pi/4 the first neglected terms, r^19/19! and r^20/20!, are
// below 1e-19 of the result, so the error is the Horner sum's round-off: within 2 ulp of the
// correctly rounded value (tests/kernels/common/test_sincos_first_quadrant.cpp measures it against libm).
// Outside [0, pi/2] the result is not sin/cos (the reduction above is all there is).
#pragma once
#include <Kokkos_Macros.hpp>

namespace lsi::math {

struct SinCos {
  double sin = 0.0;
  double cos = 1.0;
};

KOKKOS_INLINE_FUNCTION SinCos sincos_first_quadrant(double x) {
  constexpr double pi_over_2_hi = 1.5707963267948966;     // nearest double to pi/2
  constexpr double pi_over_2_lo = 6.123233995736766e-17;  // pi/2 - pi_over_2_hi
  constexpr double pi_over_4 = 0.7853981633974483;
  const bool low = x <= pi_over_4;
  const double r = low ? x : (pi_over_2_hi - x) + pi_over_2_lo;
  const double z = r * r;
  // sin r = r (1 - z/3! + z^2/5! - ... - z^9/19!): the terms up to z^8/17!.
  double ps = 1.0 / 355687428096000.0;   // 1/17!
  ps = -1.0 / 1307674368000.0 + z * ps;  // 1/15!
  ps = 1.0 / 6227020800.0 + z * ps;      // 1/13!
  ps = -1.0 / 39916800.0 + z * ps;       // 1/11!
  ps = 1.0 / 362880.0 + z * ps;          // 1/9!
  ps = -1.0 / 5040.0 + z * ps;           // 1/7!
  ps = 1.0 / 120.0 + z * ps;             // 1/5!
  ps = -1.0 / 6.0 + z * ps;              // 1/3!
  const double sin_r = r + (r * z) * ps;
  // cos r = 1 - z/2! + z^2/4! - ... : the terms up to z^9/18!.
  double pc = -1.0 / 6402373705728000.0;  // 1/18!
  pc = 1.0 / 20922789888000.0 + z * pc;   // 1/16!
  pc = -1.0 / 87178291200.0 + z * pc;     // 1/14!
  pc = 1.0 / 479001600.0 + z * pc;        // 1/12!
  pc = -1.0 / 3628800.0 + z * pc;         // 1/10!
  pc = 1.0 / 40320.0 + z * pc;            // 1/8!
  pc = -1.0 / 720.0 + z * pc;             // 1/6!
  pc = 1.0 / 24.0 + z * pc;               // 1/4!
  // 1 - z/2 is summed last and in two parts (its rounding error is the largest one).
  const double half_z = 0.5 * z;
  const double one_minus = 1.0 - half_z;
  const double cos_r = one_minus + (((1.0 - one_minus) - half_z) + (z * z) * pc);
  SinCos out;
  out.sin = low ? sin_r : cos_r;
  out.cos = low ? cos_r : sin_r;
  return out;
}

}  // namespace lsi::math

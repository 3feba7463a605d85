// sin and cos of a face angle without a library call (kernels/common/sincos_first_quadrant.hpp),
// against libm over the whole first quadrant, where the batched closed-form models use it.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/common/sincos_first_quadrant.hpp"

namespace {

// Distance from `value` to `exact` in units in the last place of `exact` (long double libm: its
// 64-bit significand makes its own error ~1/2000 of a double ulp, negligible here).
double ulps(double value, long double exact) {
  const double e = static_cast<double>(exact);
  const double ulp = std::nextafter(std::fabs(e), INFINITY) - std::fabs(e);
  return static_cast<double>(std::fabs(static_cast<long double>(value) - exact)) / ulp;
}

TEST(SinCosFirstQuadrant, WithinTwoUlpOfLibmOverTheQuadrant) {
  // 2 ulp: the neglected Taylor terms are below 1e-19 of the result, so the error is the Horner
  // sum's round-off plus the rounding of pi/2 - x; measured 1.06 (sin) and 1.40 (cos) ulp.
  const int n = 1 << 20;
  double worst_sin = 0.0, worst_cos = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double x = 1.5707963267948966 * i / n;
    const lsi::math::SinCos sc = lsi::math::sincos_first_quadrant(x);
    const long double xl = x;
    if (x > 0.0) worst_sin = std::fmax(worst_sin, ulps(sc.sin, std::sin(xl)));
    worst_cos = std::fmax(worst_cos, ulps(sc.cos, std::cos(xl)));
  }
  std::printf("[ sincos_first_quadrant ] worst error: sin %.3f ulp, cos %.3f ulp\n", worst_sin,
              worst_cos);
  EXPECT_LE(worst_sin, 2.0);
  EXPECT_LE(worst_cos, 2.0);
}

TEST(SinCosFirstQuadrant, EndsAndTheSwitchAtAQuarterTurnAreExact) {
  using lsi::math::sincos_first_quadrant;
  EXPECT_EQ(sincos_first_quadrant(0.0).sin, 0.0);
  EXPECT_EQ(sincos_first_quadrant(0.0).cos, 1.0);
  // The double nearest pi/2 is below pi/2 by 6.12e-17: its cosine is that, its sine 1.
  EXPECT_EQ(sincos_first_quadrant(1.5707963267948966).sin, 1.0);
  EXPECT_EQ(sincos_first_quadrant(1.5707963267948966).cos, std::cos(1.5707963267948966));
  // Both sides of pi/4, where the series switch from x to pi/2 - x: continuous to 1 ulp.
  const double q = 0.7853981633974483;
  for (double x : {std::nextafter(q, 0.0), q, std::nextafter(q, 1.0)}) {
    EXPECT_NEAR(sincos_first_quadrant(x).sin, std::sin(x), 2.3e-16) << x;
    EXPECT_NEAR(sincos_first_quadrant(x).cos, std::cos(x), 2.3e-16) << x;
  }
}

}  // namespace

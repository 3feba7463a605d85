// x^y without a library call (kernels/common/pow_nonnegative.hpp), against long double libm over
// the range the empirical model uses it in (alpha = a1 Fr^a2) and over the whole double range,
// and its special values against pow.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "kernels/common/pow_nonnegative.hpp"

namespace {

using lsi::math::pow_nonnegative;

// Distance from `value` to `exact` in units in the last place of `exact` (long double libm: its
// 64-bit significand makes its own error ~1/2000 of a double ulp, negligible here).
double ulps(double value, long double exact) {
  const double e = static_cast<double>(exact);
  const double ulp = std::nextafter(std::fabs(e), INFINITY) - std::fabs(e);
  return static_cast<double>(std::fabs(static_cast<long double>(value) - exact)) / ulp;
}

// The largest error over n draws of x = 10^U(lo, hi), y = U(y_lo, y_hi), keeping the results
// that are normal doubles.
double worst_ulps(double log10_lo, double log10_hi, double y_lo, double y_hi, int n,
                  std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(log10_lo, log10_hi), uy(y_lo, y_hi);
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = std::pow(10.0, ux(rng)), y = uy(rng);
    const long double exact = std::pow(static_cast<long double>(x), static_cast<long double>(y));
    if (!(std::fabs(exact) >= std::numeric_limits<double>::min() &&
          std::fabs(exact) <= std::numeric_limits<double>::max()))
      continue;
    worst = std::fmax(worst, ulps(pow_nonnegative(x, y), exact));
  }
  return worst;
}

TEST(PowNonnegative, WithinOneUlpOverTheEmpiricalModelsRange) {
  // Fr from 1e-3 to 1e3 (a flow 1e6 times faster or slower than its wave speed covers every
  // scene), a2 in [-5, 5] (the range the scene parser allows). 1 ulp: log and exp carry their
  // arguments in two doubles, so only the final rounding (1/2 ulp) and the polynomials' round-off
  // remain.
  const double worst = worst_ulps(-3, 3, -5, 5, 1 << 20, 1);
  std::printf("[ pow_nonnegative ] worst error, Fr in [1e-3, 1e3], a2 in [-5, 5]: %.3f ulp\n",
              worst);
  EXPECT_LE(worst, 1.0);
}

TEST(PowNonnegative, WithinOneUlpOverTheDoubleRange) {
  // x over every normal exponent (and subnormals), y such that x^y stays finite and normal: the
  // exponent y log x reaches 709; carried in two doubles, its error stays far below an ulp of the
  // result, so 1 ulp holds here too.
  double worst = worst_ulps(-307, 308, -2, 2, 1 << 19, 2);
  worst = std::fmax(worst, worst_ulps(-320, -308, -1, 1, 1 << 16, 3));  // subnormal x
  worst = std::fmax(worst, worst_ulps(-1, 1, -300, 300, 1 << 18, 4));   // large |y|
  std::printf("[ pow_nonnegative ] worst error over the double range: %.3f ulp\n", worst);
  EXPECT_LE(worst, 1.0);
}

TEST(PowNonnegative, SpecialValuesAsPow) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double xs[] = {0.0, 1.0, 2.0, 0.5, 1e-310, inf, nan};
  const double ys[] = {0.0, -0.0, 1.0, -1.0, 0.5, -0.515, 1e6, -1e6, inf, -inf, nan};
  for (double x : xs)
    for (double y : ys) {
      const double expected = std::pow(x, y), got = pow_nonnegative(x, y);
      if (std::isnan(expected)) {
        EXPECT_TRUE(std::isnan(got)) << x << "^" << y << " = " << got;
      } else if (std::isinf(expected) || expected == 0.0) {
        EXPECT_EQ(got, expected) << x << "^" << y;
      } else {
        EXPECT_LE(ulps(got, std::pow(static_cast<long double>(x), static_cast<long double>(y))),
                  1.0)
            << x << "^" << y << " = " << got << ", pow: " << expected;
      }
    }
  // Overflow and underflow, and results near them.
  EXPECT_EQ(pow_nonnegative(10.0, 400.0), inf);
  EXPECT_EQ(pow_nonnegative(10.0, -400.0), 0.0);
  EXPECT_LE(ulps(pow_nonnegative(2.0, 1023.5), std::pow(2.0L, 1023.5L)), 1.0);
  EXPECT_LE(ulps(pow_nonnegative(2.0, -1021.5), std::pow(2.0L, -1021.5L)), 1.0);
  // Exact powers of two come out exact.
  EXPECT_EQ(pow_nonnegative(2.0, 10.0), 1024.0);
  EXPECT_EQ(pow_nonnegative(4.0, 0.5), 2.0);
  // A negative base is outside the function's domain: NaN (pow gives (-2)^2 = 4).
  EXPECT_TRUE(std::isnan(pow_nonnegative(-2.0, 2.0)));
  EXPECT_TRUE(std::isnan(pow_nonnegative(-inf, 0.5)));
  EXPECT_EQ(pow_nonnegative(-2.0, 0.0), 1.0);
}

}  // namespace

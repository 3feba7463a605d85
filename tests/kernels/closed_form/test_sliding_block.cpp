// first_stop() (kernels/closed_form/sliding_block.hpp): when a sliding barrier whose velocity
// follows v + a u + s u^2 / 2 comes to rest, in every case of its branch-free form, against roots
// worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/closed_form/sliding_block.hpp"

namespace {
using lsi::first_stop;

// The roots below are exact or given to 1e-15; 1e-14 relative leaves room for the quadratic
// formula's round-off (a few ulp) and nothing more.
constexpr double rel = 1e-14;

TEST(SlidingBlockFirstStop, AtRestStaysAtRestUnlessPushed) {
  EXPECT_EQ(first_stop(0.0, -1.0, 0.0, 10.0), 0.0);  // decelerating: stays
  EXPECT_EQ(first_stop(0.0, 0.0, -1.0, 10.0), 0.0);  // force falling: stays
  EXPECT_EQ(first_stop(0.0, 0.0, 0.0, 10.0), 0.0);   // no net force: stays
  EXPECT_LT(first_stop(0.0, 1.0, -5.0, 10.0), 0.0);  // pushed: moves off
  EXPECT_LT(first_stop(0.0, 0.0, 1.0, 10.0), 0.0);   // force rising: moves off
}

TEST(SlidingBlockFirstStop, ConstantDeceleration) {
  EXPECT_NEAR(first_stop(3.0, -2.0, 0.0, 10.0), 1.5, rel * 1.5);
  EXPECT_LT(first_stop(3.0, -2.0, 0.0, 1.0), 0.0);  // stops after the end of the interval
  EXPECT_LT(first_stop(3.0, 0.0, 0.0, 10.0), 0.0);  // no deceleration: never
  EXPECT_LT(first_stop(3.0, 2.0, 0.0, 10.0), 0.0);
}

TEST(SlidingBlockFirstStop, QuadraticRoots) {
  // 1 - u^2 = 0: u = 1 (the other root, -1, is not a stop).
  EXPECT_NEAR(first_stop(1.0, 0.0, -2.0, 10.0), 1.0, rel);
  EXPECT_LT(first_stop(1.0, 0.0, -2.0, 0.5), 0.0);
  // 2 - u^2/2 = 0 with a = 0 (q from the negative branch): u = 2.
  EXPECT_NEAR(first_stop(2.0, 0.0, -1.0, 10.0), 2.0, 2 * rel);
  // 1 - 3u + u^2 = 0: two positive roots, the first is the stop, (3 - sqrt 5)/2.
  EXPECT_NEAR(first_stop(1.0, -3.0, 2.0, 10.0), (3.0 - std::sqrt(5.0)) / 2.0, rel);
  // 1 + u/2 + u^2/2: no real root (the square root is NaN): never stops.
  EXPECT_LT(first_stop(1.0, 0.5, 1.0, 10.0), 0.0);
  // 1 - 2u + u^2 = (1 - u)^2: a double root at u = 1 (the velocity touches zero; the
  // discriminant is exactly 0).
  EXPECT_NEAR(first_stop(1.0, -2.0, 2.0, 10.0), 1.0, rel);
  // Accelerating, then the force falls: 1e-8 + 1e4 u - u^2/2 = 0 at u = 2e4 + 1e-12; the stable
  // form keeps the small root -1e-12 from cancelling into the large one.
  EXPECT_NEAR(first_stop(1e-8, 1e4, -1.0, 1e5), 2e4, rel * 2e4);
  // The other root is negative: with an interval shorter than 2e4 there is no stop in it.
  EXPECT_LT(first_stop(1e-8, 1e4, -1.0, 1e3), 0.0);
}

}  // namespace

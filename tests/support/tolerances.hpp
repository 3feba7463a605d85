// Named tolerances of the tests: each constant says why two numbers may differ by that much.
// Relative ones (...Rel) multiply the scale of the compared quantity,
//   EXPECT_NEAR(got, want, kTwoRoutesRel * std::fabs(want));
// absolute ones (...Abs) are for values of order one (up to about a hundred for kRoundOffAbs).
// A tolerance with a reason of its own (a discretisation error, a table's digits, a solver's
// stopping rule) stays in its test as a local `constexpr double kName = ...;  // reason`.
#pragma once

namespace lsi::test {

// Relative: the same exact quantity by two routes in double precision (two closed forms, a formula
// and its rearrangement, a closed form and an exact piecewise integrator): tens of operations of a
// few ulp (1.1e-16) each, with ample room.
inline constexpr double kTwoRoutesRel = 1e-12;

// Relative: an ODE integrated to round-off (fixed-step RK4 exact on each smooth piece, or a pair
// held to 1e-12 per step, with the switching instants bisected) against the exact answer or an
// invariant of the motion: the round-off of ~1e4 steps.
inline constexpr double kIntegratedRel = 1e-9;

// Absolute: a handful of operations (a product, a sine, a square root) on unit-scale values: a few
// ulp of 1 (2.2e-16).
inline constexpr double kFewOpsAbs = 1e-15;

// Absolute: double arithmetic on O(1) numbers, tens of operations (sums, quotients, square roots,
// a closed form's terms): round-off with room.
inline constexpr double kUnitArithmeticAbs = 1e-14;

// Absolute: an exact result of order 1 to 100 (a force, a time, an impulse, a velocity) reached by
// many operations (sums over samples, a closed form's phases): the round-off of the largest terms.
inline constexpr double kRoundOffAbs = 1e-12;

}  // namespace lsi::test

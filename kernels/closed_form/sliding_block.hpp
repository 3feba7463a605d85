// A rigid barrier on a rigid base with Coulomb friction tan(delta_b), pushed by a normal force
// N(t) on its inclined face. While it slides (v > 0) its equation of motion is
//   m2 dv/dt = c N(t) - tan(delta_b) m2 g,      c = sin(beta) - tan(delta_b) cos(beta)  (+ shear)
// (horizontal component of N minus the friction of the weight and of N's downward component; see
// face_resolution.hpp). It sticks while c N(t) <= tan(delta_b) m2 g, and never moves upstream.
#pragma once
#include "kernels/common/constants.hpp"
#include "kernels/common/math.hpp"

namespace lsi {

struct SlidingBlock {
  double mass = 0.0;           // m2, kg/m (a fixed barrier is never given to the sliding code)
  double base_friction = 0.0;  // tan(delta_b)
  double drive = 1.0;          // c: net horizontal drive per unit normal force

  // Acceleration while sliding under normal force N (m/s^2).
  KOKKOS_INLINE_FUNCTION double acceleration(double normal_force) const {
    return drive * normal_force / mass - base_friction * gravity;
  }
};

// Smallest root u in (0, u_max] of v + a u + s u^2 / 2 = 0 at which v turns from positive to
// zero, for v >= 0; returns a negative number when there is none. Numerically stable form.
// Written without branches (every case is computed, the answer selected) so that the batched
// models vectorise over samples; a case that does not apply may divide by zero in its own lane,
// harmlessly (IEEE infinities, never selected). `&` and `|` on the comparisons, not `&&` and `||`:
// a short circuit is a branch.
KOKKOS_INLINE_FUNCTION double first_stop(double v, double a, double s, double u_max) {
  // At rest (v <= 0): it stays at rest unless the acceleration is (or turns) positive.
  const double at_rest = ((a < 0.0) | ((a == 0.0) & (s <= 0.0))) ? 0.0 : -1.0;
  // Each candidate root below is +infinity where it does not exist.
  // s = 0: constant acceleration.
  const double linear = a < 0.0 ? -v / a : math::infinity();
  // s != 0: the smaller positive root of the quadratic, q/(s/2) or v/q. With no real root the
  // square root is NaN, and so are q and both roots: every comparison with a NaN is false.
  const double sq = math::sqrt(a * a - 2.0 * s * v);
  const double q = -0.5 * (a + (a >= 0.0 ? sq : -sq));
  const double r1 = q / (0.5 * s), r2 = v / q;  // q = 0: r1 = 0 (no stop) and r2 = infinity
  const double root1 = r1 > 0.0 ? r1 : math::infinity();
  const double root2 = r2 > 0.0 ? r2 : math::infinity();
  const double best = s == 0.0 ? linear : math::min(root1, root2);
  const double sliding = best <= u_max ? best : -1.0;
  return v <= 0.0 ? at_rest : sliding;
}

}  // namespace lsi

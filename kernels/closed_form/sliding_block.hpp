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
  double mass = 0.0;            // m2, kg/m (a fixed barrier is never given to the sliding code)
  double base_friction = 0.0;   // tan(delta_b)
  double drive = 1.0;           // c: net horizontal drive per unit normal force

  // Acceleration while sliding under normal force N (m/s^2).
  KOKKOS_INLINE_FUNCTION double acceleration(double normal_force) const {
    return drive * normal_force / mass - base_friction * gravity;
  }
};

// Smallest root u in (0, u_max] of v + a u + s u^2 / 2 = 0 at which v turns from positive to
// zero, for v >= 0; returns a negative number when there is none. Numerically stable form.
KOKKOS_INLINE_FUNCTION double first_stop(double v, double a, double s, double u_max) {
  if (v <= 0.0) {   // at rest: it stays at rest unless the acceleration is (or turns) positive
    return (a < 0.0 || (a == 0.0 && s <= 0.0)) ? 0.0 : -1.0;
  }
  double best = -1.0;
  if (s == 0.0) {
    if (a < 0.0) best = -v / a;
  } else {
    const double disc = a * a - 2.0 * s * v;
    if (disc >= 0.0) {
      const double sq = math::sqrt(disc);
      const double q = -0.5 * (a + (a >= 0.0 ? sq : -sq));   // roots q/(s/2) and v/q
      const double r1 = (q != 0.0) ? q / (0.5 * s) : -1.0;
      const double r2 = (q != 0.0) ? v / q : -1.0;
      for (double r : {r1, r2}) {
        if (r > 0.0 && (best < 0.0 || r < best)) best = r;
      }
    }
  }
  return (best > 0.0 && best <= u_max) ? best : -1.0;
}

}  // namespace lsi

// The barrier as a rigid body that translates along its horizontal base with Coulomb friction
// tan(delta_b) (Cuomo et al. 2022: the barrier slides, it does not overturn):
//   M dV/dt = F_x - tan(delta_b) N sign(V),   N = max(0, M g - F_y),
// F the force of the flow on the barrier (F_y > 0 upwards, so a flow pressing down on an inclined
// face raises N). At rest (V = 0) the barrier sticks while |F_x| <= tan(delta_b) N; otherwise it
// starts in the direction of F_x. A sliding barrier that would reverse within a step stops at the
// instant its velocity reaches zero (and stays at rest for the rest of the step). The position
// advances with the mean velocity of the step, so a constant force gives the exact motion
// x = x0 + V0 t + a t^2 / 2 (and the exact stopping point). Host code: one scalar update a step.
#pragma once
#include <cmath>

#include "kernels/common/constants.hpp"

namespace lsi::mpm {

struct BarrierMotion {
  double mass = 0.0;              // M, kg/m
  double base_friction = 0.0;     // tan(delta_b)
  double gravity = lsi::gravity;  // g normal to the base, m/s^2
  // State.
  double displacement = 0.0;       // m, downstream positive
  double velocity = 0.0;           // m/s
  double friction_work = 0.0;      // J/m dissipated by the base friction (accumulated)
  double base_normal_force = 0.0;  // N/m, last step
  bool sliding() const { return velocity != 0.0; }

  // Advances by dt under the force (fx, fy) of the flow on the barrier, constant over the step.
  void advance(double fx, double fy, double dt) {
    const double N = std::max(0.0, mass * gravity - fy);
    base_normal_force = N;
    const double limit = base_friction * N;
    const double v0 = velocity;
    if (v0 == 0.0) {
      if (std::fabs(fx) <= limit) return;  // sticks
      const double a = (fx - std::copysign(limit, fx)) / mass;
      velocity = a * dt;
      displacement += 0.5 * a * dt * dt;
      friction_work += limit * std::fabs(0.5 * a * dt * dt);
      return;
    }
    const double a = (fx - std::copysign(limit, v0)) / mass;
    const double v1 = v0 + a * dt;
    if ((v1 > 0.0) == (v0 > 0.0) && v1 != 0.0) {
      const double ds = 0.5 * (v0 + v1) * dt;
      velocity = v1;
      displacement += ds;
      friction_work += limit * std::fabs(ds);
      return;
    }
    const double t_stop = -v0 / a;  // in (0, dt]: the barrier stops within the step
    const double ds = 0.5 * v0 * t_stop;
    velocity = 0.0;
    displacement += ds;
    friction_work += limit * std::fabs(ds);
  }
};

}  // namespace lsi::mpm

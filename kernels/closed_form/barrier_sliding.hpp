// Barrier motion under the triangular force pulse, in closed form: the paper's eqs. 17-20,
// derived again from the sliding block's equation of motion (sliding_block.hpp), with the typos
// of eq. 17 corrected (m2 and tan(delta_b) where m1 and tan(gamma_b) are printed), the sign of the
// vertical load of an inclined face corrected, and the terms eq. 20 drops restored: the velocity
// v2(T1) carried through the decay, the stop of the barrier before T2 when friction wins, and the
// sliding after T2 until the barrier stops. docs/models.md, "Barrier motion", has the derivation.
//
// Phases, with k1 = c F_peak / (m2 T1), g' = g tan(delta_b):
//   stick      0 <= t <= t*,   t* = g' / k1 = m2 g tan(delta_b) T1 / (c F_peak)   (eq. 17, t*)
//   A          t* < t <= T1:  v2 = k1 (t - t*)^2 / 2,   dx = k1 (t - t*)^3 / 6     (eqs. 17, 18)
//   B          T1 < t <= T2:  a = a1 + sB u, u = t - T1, a1 = k1 (T1 - t*),
//                             sB = c (F_res - F_peak) / (m2 (T2 - T1))            (eqs. 17, 18)
//   C          t > T2:        a = c F_res / m2 - g', until v2 = 0                 (eq. 20)
#pragma once
#include "kernels/closed_form/face_resolution.hpp"
#include "kernels/closed_form/force_pulse.hpp"
#include "kernels/closed_form/sliding_block.hpp"

namespace lsi {

struct BarrierMotion {
  bool moves = false;
  double start_time = 0.0;   // t*, s
  double stop_time = 0.0;    // s; +infinity if the barrier never stops
  double final_displacement = 0.0;  // Delta x_f, m; +infinity if it never stops
  // Internal state at the phase boundaries, for evaluation at any t.
  double k1 = 0.0, sB = 0.0, a1 = 0.0, aC = 0.0;
  double v_T1 = 0.0, x_T1 = 0.0, v_T2 = 0.0, x_T2 = 0.0;
  double T1 = 0.0, T2 = 0.0;

  KOKKOS_INLINE_FUNCTION double velocity(double t) const {
    if (!moves || t <= start_time || t >= stop_time) return 0.0;
    if (t <= T1) return 0.5 * k1 * (t - start_time) * (t - start_time);
    if (t <= T2) { const double u = t - T1; return v_T1 + a1 * u + 0.5 * sB * u * u; }
    return v_T2 + aC * (t - T2);
  }
  KOKKOS_INLINE_FUNCTION double displacement(double t) const {
    if (!moves || t <= start_time) return 0.0;
    if (t >= stop_time) return final_displacement;
    if (t <= T1) { const double u = t - start_time; return k1 * u * u * u / 6.0; }
    if (t <= T2) {
      const double u = t - T1;
      return x_T1 + v_T1 * u + 0.5 * a1 * u * u + sB * u * u * u / 6.0;
    }
    const double u = t - T2;
    return x_T2 + v_T2 * u + 0.5 * aC * u * u;
  }
};

KOKKOS_INLINE_FUNCTION BarrierMotion barrier_motion(const ForcePulse& p, const SlidingBlock& b) {
  BarrierMotion m;
  m.T1 = p.rise_time;
  m.T2 = p.duration;
  const double g_friction = b.base_friction * gravity;          // g' = g tan(delta_b)
  // Moves only if the peak drive beats friction.
  if (!(b.drive > 0.0) || !(b.acceleration(p.peak) > 0.0)) return m;
  m.moves = true;
  m.k1 = b.drive * p.peak / (b.mass * p.rise_time);
  m.start_time = g_friction / m.k1;                               // t*
  const double uA = p.rise_time - m.start_time;
  m.v_T1 = 0.5 * m.k1 * uA * uA;
  m.x_T1 = m.k1 * uA * uA * uA / 6.0;
  m.a1 = m.k1 * uA;                                               // = acceleration at T1
  const double dT = p.duration - p.rise_time;
  m.sB = b.drive * (p.residual - p.peak) / (b.mass * dT);
  const double uStop = first_stop(m.v_T1, m.a1, m.sB, dT);
  if (uStop >= 0.0) {                                             // friction stops it before T2
    m.stop_time = p.rise_time + uStop;
    m.final_displacement = m.x_T1 + m.v_T1 * uStop + 0.5 * m.a1 * uStop * uStop +
                           m.sB * uStop * uStop * uStop / 6.0;
    m.v_T2 = 0.0;
    m.x_T2 = m.final_displacement;
    return m;
  }
  m.v_T2 = m.v_T1 + m.a1 * dT + 0.5 * m.sB * dT * dT;
  m.x_T2 = m.x_T1 + m.v_T1 * dT + 0.5 * m.a1 * dT * dT + m.sB * dT * dT * dT / 6.0;
  m.aC = b.acceleration(p.residual);
  if (m.aC < 0.0) {                                               // decelerates to rest
    m.stop_time = p.duration - m.v_T2 / m.aC;
    m.final_displacement = m.x_T2 - 0.5 * m.v_T2 * m.v_T2 / m.aC;
  } else {                                                        // no friction left: never stops
    m.stop_time = math::infinity();
    m.final_displacement = math::infinity();
  }
  return m;
}

// Final displacement of a barrier of the given mass (+infinity: fixed, no motion) under a pulse
// normal to a face at angle face_angle (rad), no face shear: what sweeps and the inverse design
// need, without the time histories.
KOKKOS_INLINE_FUNCTION double final_displacement_under(const ForcePulse& pulse, double barrier_mass,
                                                       double base_friction, double face_angle) {
  if (!math::isfinite(barrier_mass)) return 0.0;
  SlidingBlock block;
  block.mass = barrier_mass;
  block.base_friction = base_friction;
  block.drive = resolve_face_force(face_angle).sliding_drive(base_friction);
  return barrier_motion(pulse, block).final_displacement;
}

}  // namespace lsi

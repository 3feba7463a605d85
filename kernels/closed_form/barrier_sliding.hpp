// Barrier motion under the triangular force pulse, in closed form: the paper's eqs. 17-20,
// derived again from the sliding block's equation of motion (sliding_block.hpp), with the typos
// of eq. 17 corrected (m2 and tan(delta_b) where m1 and tan(gamma_b) are printed), the sign of the
// vertical load of an inclined face corrected, and the terms eq. 20 drops restored: the velocity
// v2(T1) carried through the decay, the stop of the barrier before T2 when friction wins, and the
// sliding after T2 until the barrier stops. docs/theory/models.md, "Barrier motion", has the derivation.
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
  double start_time = 0.0;          // t*, s
  double stop_time = 0.0;           // s; +infinity if the barrier never stops
  double final_displacement = 0.0;  // Delta x_f, m; +infinity if it never stops
  // Internal state at the phase boundaries, for evaluation at any t.
  double k1 = 0.0, sB = 0.0, a1 = 0.0, aC = 0.0;
  double v_T1 = 0.0, x_T1 = 0.0, v_T2 = 0.0, x_T2 = 0.0;
  double T1 = 0.0, T2 = 0.0;

  KOKKOS_INLINE_FUNCTION double velocity(double t) const {
    if (!moves || t <= start_time || t >= stop_time) return 0.0;
    if (t <= T1) return 0.5 * k1 * (t - start_time) * (t - start_time);
    if (t <= T2) {
      const double u = t - T1;
      return v_T1 + a1 * u + 0.5 * sB * u * u;
    }
    return v_T2 + aC * (t - T2);
  }
  KOKKOS_INLINE_FUNCTION double displacement(double t) const {
    if (!moves || t <= start_time) return 0.0;
    if (t >= stop_time) return final_displacement;
    if (t <= T1) {
      const double u = t - start_time;
      return k1 * u * u * u / 6.0;
    }
    if (t <= T2) {
      const double u = t - T1;
      return x_T1 + v_T1 * u + 0.5 * a1 * u * u + sB * u * u * u / 6.0;
    }
    const double u = t - T2;
    return x_T2 + v_T2 * u + 0.5 * aC * u * u;
  }
};

// Written without branches: every phase is computed and the answer selected, so that the batched
// models (batch.hpp) vectorise over samples. Lanes of a phase that does not apply may hold
// infinities (e.g. t* = g'/k1 with k1 = 0); they are never selected.
KOKKOS_INLINE_FUNCTION BarrierMotion barrier_motion(const ForcePulse& p, const SlidingBlock& b) {
  const double g_friction = b.base_friction * gravity;  // g' = g tan(delta_b)
  // One division by the mass for every phase, and one by aC for both the time to rest and the
  // distance of phase C: in a vectorised loop a division costs several multiplications.
  const double drive_per_mass = b.drive / b.mass;
  // Moves only if the peak drive beats friction.
  const bool moves = (b.drive > 0.0) & (drive_per_mass * p.peak - g_friction > 0.0);
  const double k1 = drive_per_mass * p.peak / p.rise_time;
  const double start_time = g_friction / k1;  // t*
  const double uA = p.rise_time - start_time;
  const double v_T1 = 0.5 * k1 * uA * uA;
  const double x_T1 = k1 * uA * uA * uA / 6.0;
  const double a1 = k1 * uA;  // = acceleration at T1
  const double dT = p.duration - p.rise_time;
  const double sB = drive_per_mass * (p.residual - p.peak) / dT;
  const double uStop = first_stop(v_T1, a1, sB, dT);
  const bool stops_before_T2 = uStop >= 0.0;  // friction stops it before T2
  const double x_stop =
      x_T1 + v_T1 * uStop + 0.5 * a1 * uStop * uStop + sB * uStop * uStop * uStop / 6.0;
  const double v_T2 = v_T1 + a1 * dT + 0.5 * sB * dT * dT;
  const double x_T2 = x_T1 + v_T1 * dT + 0.5 * a1 * dT * dT + sB * dT * dT * dT / 6.0;
  const double aC = drive_per_mass * p.residual - g_friction;
  const bool decelerates = aC < 0.0;  // after T2: to rest, or never
  const double time_to_rest = -v_T2 / aC;
  const double stop_C = decelerates ? p.duration + time_to_rest : math::infinity();
  const double x_C = decelerates ? x_T2 + 0.5 * v_T2 * time_to_rest : math::infinity();

  BarrierMotion m;
  m.T1 = p.rise_time;
  m.T2 = p.duration;
  m.moves = moves;
  m.k1 = moves ? k1 : 0.0;
  m.start_time = moves ? start_time : 0.0;
  m.v_T1 = moves ? v_T1 : 0.0;
  m.x_T1 = moves ? x_T1 : 0.0;
  m.a1 = moves ? a1 : 0.0;
  m.sB = moves ? sB : 0.0;
  m.v_T2 = (moves & !stops_before_T2) ? v_T2 : 0.0;
  m.x_T2 = !moves ? 0.0 : stops_before_T2 ? x_stop : x_T2;
  m.aC = (moves & !stops_before_T2) ? aC : 0.0;
  m.stop_time = !moves ? 0.0 : stops_before_T2 ? p.rise_time + uStop : stop_C;
  m.final_displacement = !moves ? 0.0 : stops_before_T2 ? x_stop : x_C;
  return m;
}

// Final displacement of a barrier of the given mass (+infinity: fixed, no motion) under a pulse
// normal to a face at angle face_angle (rad, in [0, pi/2]), no face shear: what sweeps and the
// inverse design need, without the time histories. Branch-free like barrier_motion().
KOKKOS_INLINE_FUNCTION double final_displacement_under(const ForcePulse& pulse, double barrier_mass,
                                                       double base_friction, double face_angle) {
  const bool fixed = !math::isfinite(barrier_mass);
  SlidingBlock block;
  block.mass = fixed ? 1.0 : barrier_mass;
  block.base_friction = base_friction;
  block.drive = resolve_face_force(face_angle).sliding_drive(base_friction);
  const double x = barrier_motion(pulse, block).final_displacement;
  return fixed ? 0.0 : x;
}

}  // namespace lsi

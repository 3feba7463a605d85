// Barrier safety under ANY force history (Newmark-type rigid-block sliding): the exact response
// of the sliding block (sliding_block.hpp) to a normal force that is piecewise linear between
// samples (t_i, N_i) and held at N_{n-1} after the last sample. Within each segment the
// acceleration is linear in t, so velocity and displacement are integrated exactly, with the
// stick -> slip and slip -> stick instants located analytically. Used for the empirical pulse
// and for MPM force histories; for the triangular pulse it reproduces barrier_motion() exactly.
#pragma once
#include "kernels/closed_form/sliding_block.hpp"

namespace lsi {

struct RigidBlockSummary {
  double final_displacement = 0.0;  // m; +infinity if the block never stops
  double stop_time = 0.0;           // s; time it comes to rest for good (+infinity if never)
  double start_time = -1.0;         // s; first instant of sliding (-1: never slides)
};

// time[n] increasing, normal_force[n] (N/m). velocity/displacement (may be null) receive the
// state at each sample time.
KOKKOS_INLINE_FUNCTION RigidBlockSummary rigid_block_response(const double* time,
                                                              const double* normal_force, int n,
                                                              const SlidingBlock& block,
                                                              double* velocity = nullptr,
                                                              double* displacement = nullptr) {
  RigidBlockSummary out;
  double v = 0.0, x = 0.0;
  bool sliding = false;
  auto record = [&](int i) {
    if (velocity) velocity[i] = v;
    if (displacement) displacement[i] = x;
  };
  if (n > 0) record(0);
  for (int i = 0; i + 1 < n; ++i) {
    const double t0 = time[i], t1 = time[i + 1];
    const double a0 = block.acceleration(normal_force[i]);
    const double a1 = block.acceleration(normal_force[i + 1]);
    if (!(t1 > t0)) {
      record(i + 1);
      continue;
    }
    const double s = (a1 - a0) / (t1 - t0);  // da/dt within the segment
    double ta = t0;
    bool onset = false;  // ta is the computed stick -> slip instant: the drive equals friction
    for (int pass = 0; pass < 4 && ta < t1; ++pass) {
      // At the onset the acceleration is zero by construction; rounding (e.g. FMA contraction)
      // may leave -1e-16 there, which would read as "stops at once" and lose the whole slide.
      const double aa = onset ? 0.0 : a0 + s * (ta - t0);
      onset = false;
      if (!sliding) {  // stuck: does the drive beat friction?
        if (aa > 0.0) {
          sliding = true;
        } else if (s > 0.0 && a1 > 0.0) {
          ta = t0 - a0 / s;  // drive = friction here
          sliding = true;
          onset = true;
        } else {
          break;  // stuck to the end of the segment
        }
        if (out.start_time < 0.0) out.start_time = ta;
        continue;
      }
      const double u = first_stop(v, aa, s, t1 - ta);
      if (u < 0.0) {  // slides to the end of the segment
        const double du = t1 - ta;
        x += v * du + 0.5 * aa * du * du + s * du * du * du / 6.0;
        v += aa * du + 0.5 * s * du * du;
        ta = t1;
      } else {  // comes to rest inside the segment
        x += v * u + 0.5 * aa * u * u + s * u * u * u / 6.0;
        v = 0.0;
        sliding = false;
        ta += u;
        out.stop_time = ta;
      }
    }
    if (v < 0.0) v = 0.0;  // round-off guard: never moves upstream
    record(i + 1);
  }
  // After the last sample the force stays constant.
  const double a_end = n > 0 ? block.acceleration(normal_force[n - 1]) : -1.0;
  if ((sliding && v > 0.0) || a_end > 0.0) {
    if (a_end < 0.0) {
      out.stop_time = time[n - 1] - v / a_end;
      out.final_displacement = x - 0.5 * v * v / a_end;
    } else {
      out.stop_time = math::infinity();
      out.final_displacement = math::infinity();
    }
  } else {
    out.final_displacement = x;
  }
  return out;
}

}  // namespace lsi

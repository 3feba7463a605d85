// Static safety of the barrier at every instant of a force history: against sliding on its base
// and against overturning about its downstream toe. The resultant of the normal force N(t) acts on
// the impacted face at height z above the base (default z = h/2: uniform dynamic pressure over the
// flow thickness h, clipped to the barrier height; a triangular, hydrostatic-like distribution
// would give h/3, so h/2 is the conservative choice for overturning).
//   sliding:      FS_s(t)  = tan(delta_b) (W + N v_down) / (N h_x)
//   overturning:  FS_o(t)  = W (B - x_c) / M_o(t),
//                 M_o = N [ h_x z + v_down (z / tan(beta) - B) ]   (= N (z / sin(beta) - B cos(beta))
//                                                                   without face shear)
// W = m2 g, x_c the centroid (barrier_geometry.hpp), h_x and v_down from face_resolution.hpp.
#pragma once
#include "kernels/closed_form/barrier_geometry.hpp"
#include "kernels/closed_form/face_resolution.hpp"
#include "kernels/common/constants.hpp"

namespace lsi {

struct StabilityCheck {
  double min_sliding_safety = math::infinity();      // min over t of FS_s
  double time_min_sliding = 0.0;                     // s
  double min_overturning_safety = math::infinity();  // min over t of FS_o
  double time_min_overturning = 0.0;                 // s
  double resultant_height = 0.0;                     // z, m
};

// Overturning moment about the downstream toe per unit normal force (m).
KOKKOS_INLINE_FUNCTION double overturning_lever(const BarrierGeometry& g, const FaceResolution& r,
                                                double z) {
  const double px = z * math::cos(g.face_angle) / math::sin(g.face_angle);
  return r.horizontal * z + r.vertical_down * (px - g.base_width);
}

KOKKOS_INLINE_FUNCTION StabilityCheck barrier_stability(
    const double* time, const double* normal_force, int n, const BarrierGeometry& g,
    const FaceResolution& r, double barrier_mass, double base_friction, double resultant_height) {
  StabilityCheck out;
  out.resultant_height = math::min(resultant_height, g.height);
  const double W = barrier_mass * gravity;
  const double restoring = W * (g.base_width - g.centroid_x());
  const double lever = overturning_lever(g, r, out.resultant_height);
  for (int i = 0; i < n; ++i) {
    const double N = normal_force[i];
    if (!(N > 0.0)) continue;
    const double push = N * r.horizontal;
    if (push > 0.0) {
      const double fs = base_friction * (W + N * r.vertical_down) / push;
      if (fs < out.min_sliding_safety) {
        out.min_sliding_safety = fs;
        out.time_min_sliding = time[i];
      }
    }
    const double moment = N * lever;
    if (moment > 0.0) {
      const double fs = restoring / moment;
      if (fs < out.min_overturning_safety) {
        out.min_overturning_safety = fs;
        out.time_min_overturning = time[i];
      }
    }
  }
  return out;
}

}  // namespace lsi

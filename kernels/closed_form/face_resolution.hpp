// Resolution of the force that the flow exerts on the impacted (upstream) face of the barrier.
//
// The face rises at angle beta from the horizontal and leans downstream (beta = 90 deg: vertical).
// Its outward normal points upstream and up, n = (-sin beta, cos beta). A normal contact force N
// (per metre, pushing on the barrier) acts along -n: horizontal N sin beta (downstream) and
// vertical N cos beta (DOWNWARDS: the flow presses the leaning face into the ground). Flow sliding
// up the face with a mobilised shear ratio mu_f = S/N adds S along the face, upwards:
// horizontal S cos beta, vertical -S sin beta. See docs/theory/models.md, "Force on an inclined face".
#pragma once
#include "kernels/common/sincos_first_quadrant.hpp"

namespace lsi {

struct FaceResolution {
  double horizontal = 1.0;     // horizontal force on the barrier per unit normal force
  double vertical_down = 0.0;  // downward force on the barrier per unit normal force

  // Net horizontal force that drives sliding, per unit normal force, once the base friction
  // tan(delta_b) of the extra vertical load is subtracted: c = h - tan(delta_b) v.
  KOKKOS_INLINE_FUNCTION double sliding_drive(double base_friction) const {
    return horizontal - base_friction * vertical_down;
  }
};

// beta in radians, in [0, pi/2] (scenes and studies accept (0, 90] deg); face_shear_ratio =
// mobilised tan(delta) on the face (0: shear neglected, as in the paper's analytical model).
// sin and cos without a library call, so that the batched models vectorise (within 2 ulp).
KOKKOS_INLINE_FUNCTION FaceResolution resolve_face_force(double face_angle_rad,
                                                         double face_shear_ratio = 0.0) {
  const math::SinCos sc = math::sincos_first_quadrant(face_angle_rad);
  const double s = sc.sin, c = sc.cos;
  FaceResolution r;
  r.horizontal = s + face_shear_ratio * c;
  r.vertical_down = c - face_shear_ratio * s;
  return r;
}

}  // namespace lsi

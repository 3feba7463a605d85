// Geometry of the trapezoidal barrier (per metre of width): height H, base width B, top width b,
// upstream (impacted) face at angle beta from the horizontal. x is measured downstream from the
// upstream toe. Vertices: upstream toe (0, 0), downstream toe (B, 0), downstream crest
// (B - d, H), upstream crest (r, H), with the face run-out r = H / tan(beta) and the downstream
// run-out d = B - b - r >= 0.
#pragma once
#include "kernels/common/math.hpp"

namespace lsi {

struct BarrierGeometry {
  double height = 0.0;                   // H, m
  double base_width = 0.0;               // B, m
  double top_width = 0.0;                // b, m
  double face_angle = 0.5 * math::pi();  // beta, rad

  KOKKOS_INLINE_FUNCTION double area() const { return 0.5 * (base_width + top_width) * height; }
  KOKKOS_INLINE_FUNCTION double face_run_out() const {
    return height * math::cos(face_angle) / math::sin(face_angle);
  }
  KOKKOS_INLINE_FUNCTION double downstream_run_out() const {
    return base_width - top_width - face_run_out();
  }
  // Horizontal position of the centroid (polygon formula on the four vertices).
  KOKKOS_INLINE_FUNCTION double centroid_x() const {
    const double xs[4] = {0.0, base_width, base_width - downstream_run_out(), face_run_out()};
    const double ys[4] = {0.0, 0.0, height, height};
    double a2 = 0.0, cx = 0.0;
    for (int i = 0; i < 4; ++i) {
      const int j = (i + 1) % 4;
      const double cross = xs[i] * ys[j] - xs[j] * ys[i];
      a2 += cross;
      cx += (xs[i] + xs[j]) * cross;
    }
    return cx / (3.0 * a2);
  }
};

}  // namespace lsi

// The rigid barrier's shape: a trapezoid standing on the base, impacted on its upstream (left)
// face. Geometry of the paper's Fig. 1: height H, base width B, crest width b, upstream face
// inclined at beta from the horizontal (90 deg: vertical). Corners, counter-clockwise from the
// upstream toe (x0, y0):
//   (x0, y0) -> (x0 + B, y0) -> (x0 + H / tan(beta) + b, y0 + H) -> (x0 + H / tan(beta), y0 + H)
// The three faces the flow can touch (upstream face, crest, downstream face) carry outward unit
// normals; the bottom edge rests on the base and is never a contact face.
#pragma once
#include <Kokkos_Core.hpp>
#include <cmath>

#include "kernels/common/math.hpp"

namespace lsi::mpm {

struct BarrierFace {
  double point[2] = {0.0, 0.0};   // a point of the face (its lower or upstream end), m
  double normal[2] = {0.0, 0.0};  // outward unit normal
};

struct BarrierShape {
  enum Face : int { Upstream = 0, Crest = 1, Downstream = 2 };
  BarrierFace face[3];
  double toe[2] = {0.0, 0.0};  // upstream toe (x0, y0), m, at zero displacement
  double height = 0.0, base_width = 0.0, top_width = 0.0, face_angle = 0.5 * math::pi();

  BarrierShape() = default;
  BarrierShape(double x0, double y0, double H, double B, double b, double beta)
      : height(H), base_width(B), top_width(b), face_angle(beta) {
    toe[0] = x0;
    toe[1] = y0;
    const double run = std::fabs(beta - 0.5 * math::pi()) < 1e-12 ? 0.0 : H / std::tan(beta);
    const double crest_up[2] = {x0 + run, y0 + H}, crest_down[2] = {x0 + run + b, y0 + H};
    const double heel[2] = {x0 + B, y0};
    set(Upstream, toe, crest_up);
    set(Crest, crest_up, crest_down);
    set(Downstream, crest_down, heel);
  }
  // x of the upstream crest corner: material beyond it (downstream) has overtopped the face.
  double crest_upstream_x() const { return face[Crest].point[0]; }

  // Signed distance-like value of the point (x, y) (barrier frame) to the barrier: the largest of
  // the face values (x - p).n. <= 0 inside or on the barrier (for points above its base); the face
  // that attains it is the nearest one for a point inside this convex shape.
  KOKKOS_INLINE_FUNCTION double outside_distance(double x, double y, int& nearest) const {
    double best = -1e300;
    nearest = Upstream;
    for (int k = 0; k < 3; ++k) {
      const double d =
          (x - face[k].point[0]) * face[k].normal[0] + (y - face[k].point[1]) * face[k].normal[1];
      if (d > best) {
        best = d;
        nearest = k;
      }
    }
    return best;
  }

 private:
  // The face from corner a to corner b, walking toe -> crest -> heel (clockwise): the outward
  // normal is the left-hand normal (-t_y, t_x) of the direction t = b - a. A crest of zero width
  // (a triangular barrier) gets the upward normal.
  void set(int k, const double a[2], const double b[2]) {
    const double tx = b[0] - a[0], ty = b[1] - a[1], len = std::sqrt(tx * tx + ty * ty);
    face[k].point[0] = a[0];
    face[k].point[1] = a[1];
    face[k].normal[0] = len > 0.0 ? -ty / len : 0.0;
    face[k].normal[1] = len > 0.0 ? tx / len : 1.0;
  }
};

}  // namespace lsi::mpm

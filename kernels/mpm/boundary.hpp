// Rigid, grid-aligned walls with Coulomb friction, applied to grid-node velocities: a node on or
// beyond a wall loses the velocity component into the wall; its tangential velocity is reduced by
// mu times the normal velocity removed (Coulomb), never reversed; it may leave the wall freely.
// A bilateral wall (a fixed support, e.g. the clamped end of a bar) also holds nodes that would
// leave it. An inclined base is a horizontal base with gravity rotated by the slope angle.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/math.hpp"

namespace lsi::mpm {

struct Wall {
  bool active = false;
  double position = 0.0;   // coordinate of the wall (x for left/right, y for bottom/top), m
  double friction = 0.0;   // Coulomb coefficient mu (0: smooth)
  bool bilateral = false;  // true: the normal velocity is zero whatever its sign (fixed support)
  bool no_slip = false;  // true: a node on the wall keeps no tangential velocity (friction unused)
};

struct Boundaries {
  Wall left, right, bottom, top;
};

// Applies the walls to the velocity v of a node at (x, y). Returns true if a wall acted.
KOKKOS_INLINE_FUNCTION bool apply_walls(const Boundaries& b, double x, double y, double v[2],
                                        double tol) {
  bool acted = false;
  auto contact = [&](const Wall& w, int normal_axis, double inward) {
    const double vn = v[normal_axis] * inward;  // > 0: leaving the wall
    if (vn >= 0.0 && !w.bilateral) return;
    acted = true;
    const int t = 1 - normal_axis;
    v[normal_axis] = 0.0;
    if (w.no_slip) {
      v[t] = 0.0;
      return;
    }
    const double vt = v[t], reduce = w.friction * math::fabs(vn);  // mu |v_n|
    v[t] = math::fabs(vt) <= reduce ? 0.0 : vt - (vt > 0.0 ? reduce : -reduce);
  };
  if (b.left.active && x <= b.left.position + tol) contact(b.left, 0, 1.0);
  if (b.right.active && x >= b.right.position - tol) contact(b.right, 0, -1.0);
  if (b.bottom.active && y <= b.bottom.position + tol) contact(b.bottom, 1, 1.0);
  if (b.top.active && y >= b.top.position - tol) contact(b.top, 1, -1.0);
  return acted;
}

}  // namespace lsi::mpm

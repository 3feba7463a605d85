// Quadratic B-spline shape functions on a uniform grid (3 x 3 nodes per particle in 2D).
// Chosen over linear hat functions because their gradients are continuous: a particle crossing a
// cell face does not see a jump in its internal force ("cell-crossing noise"), and the APIC
// inertia tensor is the constant D = dx^2 / 4 I (Jiang et al. 2015).
#pragma once
#include <Kokkos_Core.hpp>

namespace lsi::mpm {

struct Stencil1D {
  int base;      // index of the first of the 3 nodes
  double w[3];   // weights
  double dw[3];  // d(weight)/dx
};

// x: particle coordinate relative to the grid origin; dx: cell size.
KOKKOS_FORCEINLINE_FUNCTION Stencil1D quadratic_bspline(double x, double inv_dx) {
  Stencil1D s;
  const double xi = x * inv_dx;
  s.base = static_cast<int>(xi - 0.5);  // floor, xi > 0.5 inside the padded grid
  const double f = xi - s.base;         // in [0.5, 1.5)
  const double a = 1.5 - f, b = f - 1.0, c = f - 0.5;
  s.w[0] = 0.5 * a * a;
  s.w[1] = 0.75 - b * b;
  s.w[2] = 0.5 * c * c;
  s.dw[0] = -a * inv_dx;
  s.dw[1] = -2.0 * b * inv_dx;
  s.dw[2] = c * inv_dx;
  return s;
}

// The weights times the nodes' offsets from the particle, w_a (x_a - x) for the 3 nodes of s
// (x relative to the grid origin): the APIC moments of the separable P2G and G2P sums.
KOKKOS_FORCEINLINE_FUNCTION void offset_weights(const Stencil1D& s, double x, double dx,
                                                double out[3]) {
  for (int a = 0; a < 3; ++a) out[a] = s.w[a] * ((s.base + a) * dx - x);
}

}  // namespace lsi::mpm

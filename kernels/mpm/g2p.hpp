// Grid to particle: velocity (APIC: the grid velocity interpolated, with the affine matrix
// C = 4/dx^2 sum w v_i (x_i - x_p)^T; or a FLIP/PIC blend), velocity gradient L = sum v_i grad(w)^T,
// and position x += dt sum w (v_i_old + v_i) / 2 (trapezoidal: exact for constant acceleration). In the same pass it reduces the largest particle speed (for the
// next time step) and flags non-finite values or particles leaving the grid (health check).
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/math.hpp"
#include "kernels/mpm/grid.hpp"
#include "kernels/mpm/particles.hpp"
#include "kernels/mpm/shape_function.hpp"

namespace lsi::mpm {

struct G2PReport {
  double max_speed = 0.0;   // m/s
  int non_finite = 0;       // number of particles with a non-finite velocity or position
  int outside = 0;          // number of particles too close to the grid edge (or beyond)
};

template <class ExecSpace, class MemorySpace>
G2PReport g2p(const Particles<MemorySpace>& p, const Grid<MemorySpace>& g, double dt,
              double flip_ratio) {
  const double ox = g.origin[0], oy = g.origin[1], dx = g.dx, inv_dx = 1.0 / g.dx;
  const double apic = flip_ratio > 0.0 ? 0.0 : 4.0 * inv_dx * inv_dx;
  const double xmax = (g.nx - 2) * dx, ymax = (g.ny - 2) * dx;   // keep 1 cell of padding
  const int nx = g.nx;
  double vmax = 0.0;
  int bad = 0, out = 0;
  Kokkos::parallel_reduce(
      "lsi::mpm::g2p", Kokkos::RangePolicy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& vm, int& nonfinite, int& outside) {
        const double xp = p.position(q, 0) - ox, yp = p.position(q, 1) - oy;
        const Stencil1D sx = quadratic_bspline(xp, inv_dx), sy = quadratic_bspline(yp, inv_dx);
        double v[2] = {0, 0}, dv[2] = {0, 0}, vmid[2] = {0, 0}, C[2][2] = {{0, 0}, {0, 0}}, L[2][2] = {{0, 0}, {0, 0}};
        for (int a = 0; a < 3; ++a) {
          const double dxa = (sx.base + a) * dx - xp;
          for (int b = 0; b < 3; ++b) {
            const double dyb = (sy.base + b) * dx - yp;
            const int node = (sx.base + a) + nx * (sy.base + b);
            const double w = sx.w[a] * sy.w[b];
            const double gw[2] = {sx.dw[a] * sy.w[b], sx.w[a] * sy.dw[b]};
            const double vi[2] = {g.velocity(node, 0), g.velocity(node, 1)};
            const double d[2] = {dxa, dyb};
            for (int r = 0; r < 2; ++r) {
              v[r] += w * vi[r];
              const double vo = g.velocity_old(node, r);
              dv[r] += w * (vi[r] - vo);
              vmid[r] += 0.5 * w * (vi[r] + vo);
              for (int c = 0; c < 2; ++c) {
                C[r][c] += w * vi[r] * d[c];
                L[r][c] += vi[r] * gw[c];
              }
            }
          }
        }
        for (int r = 0; r < 2; ++r) {
          const double vnew = flip_ratio > 0.0
                                  ? flip_ratio * (p.velocity(q, r) + dv[r]) + (1.0 - flip_ratio) * v[r]
                                  : v[r];
          p.velocity(q, r) = vnew;
          p.position(q, r) += dt * vmid[r];
          for (int c = 0; c < 2; ++c) {
            p.affine(q, r, c) = apic * C[r][c];
            p.velocity_gradient(q, r, c) = L[r][c];
          }
        }
        const double s2 = p.velocity(q, 0) * p.velocity(q, 0) + p.velocity(q, 1) * p.velocity(q, 1);
        if (!(s2 < 1e300) || !(p.position(q, 0) == p.position(q, 0)) ||
            !(p.position(q, 1) == p.position(q, 1))) {
          ++nonfinite;
        } else {
          const double s = math::sqrt(s2);
          if (s > vm) vm = s;
        }
        const double px = p.position(q, 0) - ox, py = p.position(q, 1) - oy;
        if (!(px > dx && px < xmax && py > dx && py < ymax)) ++outside;
      },
      Kokkos::Max<double>(vmax), bad, out);
  return {vmax, bad, out};
}

}  // namespace lsi::mpm

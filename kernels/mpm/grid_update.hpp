// Grid update: v_old = p / m, v = v_old + dt f / m, then the walls (boundary.hpp). Returns the
// work the walls' reactions R = m (v - v_before) / dt dissipated this step, measured with the
// mid-step velocity (v_old + v) / 2 that moves the particles (g2p.hpp), so that the node's kinetic
// energy change is exactly dt (f + R) . v_mid: a head-on stop from V dissipates m V^2 / 2, a node
// held at rest by the wall dissipates nothing, Coulomb sliding dissipates mu |R_n| |v_t| dt.
// Adds the walls' reaction force (N/m, force on the walls) to `wall_force`, and with wall bands
// (wall_bands.hpp) books each wall node's normal impulse to its wall's bands.
// Optional (small_mass > 0): nodes with less mass than `small_mass` get gravity but no internal
// force: at the edge of a
// point's support the quadratic B-spline's weight falls as (1.5 - r)^2 but its gradient only as
// (1.5 - r), so the acceleration f / m of a node that only such points reach grows without bound
// as r -> 1.5, and through the velocity gradient and the APIC matrix it feeds back into the
// stress (measured: a fast overtopping flow in scenes/reference/L3-B3 at 16 cells per thickness
// ejected a point out of the grid with APIC; with the threshold at 1e-3 of a point's mass it
// runs to rest). The price: the internal forces no longer sum to zero, so momentum is conserved
// only approximately (a block hitting a free barrier: 0.08 % of the momentum exchanged), hence
// off by default.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/boundary.hpp"
#include "kernels/mpm/grid.hpp"
#include "kernels/mpm/wall_bands.hpp"

namespace lsi::mpm {

template <class ExecSpace, class MemorySpace>
double grid_update(const Grid<MemorySpace>& g, const Boundaries& walls, double dt,
                   double wall_force[2], double small_mass = 0.0, const double* gravity = nullptr,
                   const WallBands<MemorySpace>& bands = {}) {
  const double ox = g.origin[0], oy = g.origin[1], dx = g.dx, tol = 1e-9 * g.dx;
  const int nx = g.nx;
  // Only the nodes whose fields may be nonzero (Grid::active, Grid::row_spans): outside them
  // nothing moves.
  const NodeBox region = g.dirty_box();
  double dissipated = 0.0, fx = 0.0, fy = 0.0;
  if (region.empty()) return 0.0;
  const NodeItems<ExecSpace> items(region, g.dirty_rows());
  const auto mass = g.mass;
  const auto momentum = g.momentum;
  const auto force = g.force;
  const auto velocity = g.velocity;
  const auto velocity_old = g.velocity_old;
  const double gx = gravity ? gravity[0] : 0.0, gy = gravity ? gravity[1] : 0.0;
  const bool banded = bands.active();
  Kokkos::parallel_reduce(
      "lsi::mpm::grid_update", range_policy<ExecSpace>(0, items.count()),
      KOKKOS_LAMBDA(const int t, double& lost, double& rx, double& ry) {
        items.visit(t, [&](const int j, const int i_begin, const int i_end) {
          for (int i = i_begin; i <= i_end; ++i) {  // a row of the region, or one node
            const int n = i + nx * j;
            const double m = mass(n);
            if (!(m > 0.0)) {
              velocity(n, 0) = velocity(n, 1) = 0.0;
              velocity_old(n, 0) = velocity_old(n, 1) = 0.0;
              continue;
            }
            double v[2], vo[2];
            for (int d = 0; d < 2; ++d) {
              vo[d] = momentum(n, d) / m;
              v[d] = vo[d] + dt * (m < small_mass ? (d == 0 ? gx : gy) : force(n, d) / m);
            }
            const double before[2] = {v[0], v[1]};
            const double x = ox + i * dx, y = oy + j * dx;
            if (apply_walls(walls, x, y, v, tol)) {
              for (int d = 0; d < 2; ++d) lost -= m * (v[d] - before[d]) * 0.5 * (vo[d] + v[d]);
              const double Ix = -m * (v[0] - before[0]), Iy = -m * (v[1] - before[1]);  // on walls
              rx += Ix / dt;
              ry += Iy / dt;
              if (banded) bands.add(walls, i, j, x, y, tol, Ix, Iy);
            }
            velocity_old(n, 0) = vo[0];
            velocity_old(n, 1) = vo[1];
            velocity(n, 0) = v[0];
            velocity(n, 1) = v[1];
          }
        });
      },
      dissipated, fx, fy);
  // Every node outside the mass rectangle (and its row spans) is now zero.
  g.set_dirty_to_mass();
  wall_force[0] += fx;
  wall_force[1] += fy;
  return dissipated;
}

}  // namespace lsi::mpm

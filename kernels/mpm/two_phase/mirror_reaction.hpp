// The walls' reaction that the wall correction (TwoPhaseSettings::wall_correction,
// two_phase_p2g.hpp) applies through the mirror images of the points near a wall. The grid update
// sums the paper's eq. 26 over the nodes a wall constrains; with the correction part of the
// reaction acts instead on the free nodes next to the wall (the share N_j(wall) sigma_nn that
// the first free node's B-spline still has on the wall), and eq. 26 misses it: 12.5 % of the
// weight of the hydrostatic column in test_mpm_two_phase.cpp (WallForceCarriesTheWeight).
//
// That share follows from the partition of unity: without the correction the internal forces of
// the P2G, -V (sigma' - p I) grad(w_i), sum to zero over the nodes (the gradients of the weights
// of a point sum to zero), so the mixture forces of the nodes sum to the external forces,
// sum_p (m_S + m_L) g + t_p. The mirror images add forces normal to the walls on the free nodes
// only, so the force of the walls on the material through the mirrors is
//   sum_i f_mix,i - sum_p ((m_S + m_L) g + t_p)
// and its opposite is the force ON the walls, added to eq. 26's. Exact to round-off while every
// point's 3 x 3 stencil lies inside the grid (the walls stand two cells inside it). Two
// reductions (nodes of the P2G's rectangle, points), run only when the correction is on.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/grid.hpp"
#include "kernels/mpm/two_phase/two_phase_grid.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"

namespace lsi::mpm::two_phase {

// After the P2G: the mirror images' share of the force on the walls, N/m (x, y).
template <class ExecSpace, class MemorySpace>
void mirror_wall_reaction(const TwoPhaseGrid<MemorySpace>& g,
                          const TwoPhaseParticles<MemorySpace>& p, const double gravity[2],
                          double on_walls[2]) {
  on_walls[0] = on_walls[1] = 0.0;
  const auto S = g.solid;
  const NodeBox region = S.dirty_box();
  if (region.empty() || p.count == 0) return;
  const NodeItems<ExecSpace> items(region);
  const int nx = S.nx;
  double fx = 0.0, fy = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::two_phase::mirror_reaction_nodes", range_policy<ExecSpace>(0, items.count()),
      KOKKOS_LAMBDA(const int t, double& sx, double& sy) {
        items.visit(t, [&](const int j, const int i_begin, const int i_end) {
          for (int ii = i_begin; ii <= i_end; ++ii) {
            sx += S.force(ii + nx * j, 0);
            sy += S.force(ii + nx * j, 1);
          }
        });
      },
      fx, fy);
  const auto ms = p.solid.mass;
  const auto ml = p.liquid_mass;
  const auto tr = p.traction;
  const double gx = gravity[0], gy = gravity[1];
  double ex = 0.0, ey = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::two_phase::mirror_reaction_points", range_policy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& sx, double& sy) {
        const double m = ms(q) + ml(q);
        sx += m * gx + tr(q, 0);
        sy += m * gy + tr(q, 1);
      },
      ex, ey);
  on_walls[0] = -(fx - ex);
  on_walls[1] = -(fy - ey);
}

}  // namespace lsi::mpm::two_phase

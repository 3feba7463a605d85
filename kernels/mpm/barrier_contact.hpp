// Frictional contact between the material and the rigid barrier, on the grid (after the grid
// update and the walls, before G2P). The barrier is a rigid body with a known velocity field
// (a horizontal translation V), so the multi-velocity contact of Bardenhagen et al. (2000)
// reduces to a projection at the nodes the barrier covers: a node with mass on or inside the
// barrier (barrier_shape.hpp, within 1e-9 dx) whose velocity relative to the barrier points into
// the nearest face (v_rel . n < 0) loses that normal component; its tangential relative velocity
// is reduced by tan(delta) times the normal velocity removed (Coulomb), never reversed. A node
// moving away from the face is left free: the flow may separate from the barrier.
// The impulse the nodes receive, summed, is minus the impulse on the barrier (paper eq. 26: the
// force on the barrier is the sum of the contact forces): returned per face as a force (N/m),
// with the work the contact took from the material, measured with the mid-step node velocity as
// for the walls (grid_update.hpp), and the moment of the upstream face's forces about the
// barrier's downstream toe (the overturning moment of the face load, from where along the face
// each node pushes). Given row_impulse (one entry per node row of the grid), each upstream face
// node's normal impulse on the barrier this step is also added into its row's entry: the face
// load's distribution with height, which the caller shares among height bands
// (barrier_coupling.hpp). On the host a row is one thread's (NodeItems), so its entry is summed
// in the same order whatever the threads.
#pragma once
#include <Kokkos_Core.hpp>
#include <cmath>

#include "kernels/common/execution_instance.hpp"
#include "kernels/common/math.hpp"
#include "kernels/mpm/barrier_shape.hpp"
#include "kernels/mpm/grid.hpp"

namespace lsi::mpm {

struct BarrierContactReport {
  double force[3][2] = {{0, 0}, {0, 0}, {0, 0}};  // N/m on the barrier, per face, (x, y)
  double work =
      0.0;        // J/m taken from the material this step (> 0: dissipated or given to the barrier)
  int nodes = 0;  // nodes in contact this step
  // N m/m: sum over the upstream face's nodes of (y - y_toe) f_x - (x - x_downstream_toe) f_y,
  // positive where it tips the barrier downstream about its downstream toe.
  double upstream_moment = 0.0;
  double total(int d) const { return force[0][d] + force[1][d] + force[2][d]; }
};

template <class ExecSpace, class MemorySpace>
BarrierContactReport barrier_contact(const Grid<MemorySpace>& g, const BarrierShape& shape,
                                     double displacement, double velocity, double friction,
                                     double dt,
                                     const Kokkos::View<double*, MemorySpace>& row_impulse = {}) {
  const double ox = g.origin[0], oy = g.origin[1], dx = g.dx, tol = 1e-9 * g.dx;
  const int nx = g.nx;
  const BarrierShape b = shape;
  BarrierContactReport r;
  double f[6] = {0, 0, 0, 0, 0, 0}, work = 0.0, moment = 0.0;
  int nodes = 0;
  const double x_downstream_toe = b.toe[0] + b.base_width;
  // Only the nodes that may hold mass (Grid::mass_box and its row spans, set by P2G), and of
  // those the columns the barrier covers, one cell wider on each side (a node beyond them is
  // outside the barrier by more than the tolerance). The rows stay those of the mass rectangle:
  // on one host thread (a work item per row) the same sums as over the whole rectangle.
  NodeBox region = g.mass_box();
  if (region.empty()) return r;
  double x_lo = b.toe[0], x_hi = b.toe[0];
  for (const auto& face : b.face) {
    x_lo = face.point[0] < x_lo ? face.point[0] : x_lo;
    x_hi = face.point[0] > x_hi ? face.point[0] : x_hi;
  }
  x_hi = x_hi > b.toe[0] + b.base_width ? x_hi : b.toe[0] + b.base_width;
  const double first = std::floor((x_lo + displacement - ox) / dx) - 1.0;
  const double last = std::ceil((x_hi + displacement - ox) / dx) + 1.0;
  if (first > region.i1 || last < region.i0) return r;  // no node in contact
  if (first > region.i0) region.i0 = static_cast<int>(first);
  if (last < region.i1) region.i1 = static_cast<int>(last);
  const NodeItems<ExecSpace> items(region, g.mass_rows());
  const bool rows = row_impulse.extent(0) > 0;
  Kokkos::parallel_reduce(
      "lsi::mpm::barrier_contact", range_policy<ExecSpace>(0, items.count()),
      KOKKOS_LAMBDA(const int item, double& f0, double& f1, double& f2, double& f3, double& f4,
                    double& f5, double& w, double& mo, int& count) {
        items.visit(item, [&](const int j, const int i_begin, const int i_end) {
          for (int i = i_begin; i <= i_end; ++i) {  // a row of the region, or one node
            const int n = i + nx * j;
            const double m = g.mass(n);
            if (!(m > 0.0)) continue;
            const double x = ox + i * dx - displacement, y = oy + j * dx;
            if (y < b.toe[1] - tol) continue;  // below the base: the base wall's business
            int k = 0;
            if (b.outside_distance(x, y, k) > tol) continue;
            const double nxk = b.face[k].normal[0], nyk = b.face[k].normal[1];
            const double v[2] = {g.velocity(n, 0), g.velocity(n, 1)};
            const double rel[2] = {v[0] - velocity, v[1]};
            const double vn = rel[0] * nxk + rel[1] * nyk;
            if (vn >= 0.0) continue;
            // Tangential relative velocity after removing the normal part, then Coulomb.
            double t[2] = {rel[0] - vn * nxk, rel[1] - vn * nyk};
            const double vt = math::sqrt(t[0] * t[0] + t[1] * t[1]);
            const double reduce = friction * (-vn);
            const double keep = vt <= reduce ? 0.0 : (vt - reduce) / vt;
            t[0] *= keep;
            t[1] *= keep;
            const double vnew[2] = {velocity + t[0], t[1]};
            double imp[2];
            for (int d = 0; d < 2; ++d) {
              imp[d] = m * (vnew[d] - v[d]);  // impulse on the node
              w -= imp[d] * 0.5 * (g.velocity_old(n, d) + vnew[d]);
              g.velocity(n, d) = vnew[d];
            }
            const double fx = -imp[0] / dt, fy = -imp[1] / dt;  // on the barrier
            if (k == 0) {
              f0 += fx;
              f1 += fy;
              mo += (y - b.toe[1]) * fx - (x - x_downstream_toe) * fy;
              // The face's normal impulse per row (on a device several work items share a row).
              if (rows) Kokkos::atomic_add(&row_impulse(j), imp[0] * nxk + imp[1] * nyk);
            } else if (k == 1) {
              f2 += fx;
              f3 += fy;
            } else {
              f4 += fx;
              f5 += fy;
            }
            ++count;
          }
        });
      },
      f[0], f[1], f[2], f[3], f[4], f[5], work, moment, nodes);
  for (int k = 0; k < 3; ++k) {
    r.force[k][0] = f[2 * k];
    r.force[k][1] = f[2 * k + 1];
  }
  r.work = work;
  r.nodes = nodes;
  r.upstream_moment = moment;
  return r;
}

}  // namespace lsi::mpm

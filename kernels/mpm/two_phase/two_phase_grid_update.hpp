// Two-phase grid update, per node (the order of Anura3D-type codes): the liquid acceleration
// first, from the liquid momentum equation with the Darcy drag, then the solid from the MIXTURE
// equation minus the liquid inertia,
//   m_L a_L = f_L - Q (v_L - v_S)                       (liquid, f_L = V n p grad w + m_L g)
//   m_S a_S = f_mix - m_L a_L                           (mixture, f_mix with the total stress)
// so that m_S a_S + m_L a_L = f_mix exactly whatever the drag treatment.
//   Drag::Explicit      the drag uses the relative velocity at the start of the step,
//                       w0 = v_L0 - v_S0. Stable for dt < 2 / (Q (1/m_L + 1/m_S)) (the
//                       permeability limit of the time step, two_phase_time_step.hpp).
//   Drag::SemiImplicit  the drag uses the relative velocity at the END of the step, solved per
//                       node in closed form (no system: Q couples only the two phases of one
//                       node): with the drag-free trial velocities
//                         v_L* = v_L0 + dt f_L / m_L,   v_S* = v_S0 + dt (f_mix - f_L) / m_S,
//                         w1 = (v_L* - v_S*) / (1 + dt Q (1/m_L + 1/m_S)),
//                         v_L = v_L* - dt Q w1 / m_L,  then a_L = (v_L - v_L0)/dt and a_S as above.
//                       The relative velocity decays monotonically for any dt: no permeability
//                       limit.
// Then the walls (boundary.hpp, apply_walls) act on both phases: the solid with `walls`, the
// liquid with `liquid_walls` (normally the same walls: no penetration of the liquid = an
// impermeable boundary; leave a wall out of liquid_walls to let the liquid through).
// Reductions (J/m this step, measured with the mid-step velocities that move the points):
// wall dissipation, drag dissipation dt Q w_drag . w_mid, and the work of gravity on the
// relative (seepage) flow dt m_L g . w_mid, which the points' potential energy does not see
// (points move with the solid). The force on the walls follows the paper's eq. 26:
// F = -(m_S dv_S + m_L dv_L) / dt summed over the nodes a wall acted on.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/boundary.hpp"
#include "kernels/mpm/two_phase/two_phase_grid.hpp"

namespace lsi::mpm::two_phase {

enum class Drag { Explicit, SemiImplicit };

struct GridUpdateReport {
  double wall_dissipation = 0.0;      // J/m
  double drag_dissipation = 0.0;      // J/m
  double seepage_gravity_work = 0.0;  // J/m
  double wall_force[2] = {0.0, 0.0};  // N/m, on the walls
};

// A node's sums from P2G (two_phase_p2g.hpp): both masses, momenta and forces (the solid's force
// is the mixture's), and the drag coefficient.
struct TwoPhaseNodeSums {
  double mS, mL, pS[2], pL[2], fS[2], fL[2], Q;
};

// The sums reduced over the nodes of a grid update (GridUpdateReport before it is filled in).
struct TwoPhaseUpdateSums {
  double wall_lost, drag_lost, seep, rx, ry;
};

// A node's velocities before the walls act, from its sums (see the file comment): at the start
// of the step (vS0, vL0) and after it (vS, vL), and the relative velocity the drag acts on (wd).
// A node without solid mass gets zeros; a node without liquid moves the liquid with the solid.
// Branch-free (every lane computes the wet and the dry update, with the masses of an empty
// node replaced by 1 so that no division is by zero, and keeps the one its node takes), so that
// a loop over nodes vectorises: each operation is the same, and exact, in a vector lane.
template <bool SemiImplicit>
KOKKOS_FORCEINLINE_FUNCTION void two_phase_node_velocities(
    const double mS, const double mL, const double Qn, const double pS[2], const double pL[2],
    const double fS[2], const double fL[2], const double dt, double vS0[2], double vL0[2],
    double vS[2], double vL[2], double wd[2]) {
  const bool has = mS > 0.0, wet = has && mL > 0.0;
  const double ms = has ? mS : 1.0, ml = wet ? mL : 1.0, Q = wet ? Qn : 0.0;
  const double relax = SemiImplicit ? 1.0 / (1.0 + dt * Q * (1.0 / ml + 1.0 / ms)) : 0.0;
  for (int d = 0; d < 2; ++d) {
    const double s0 = pS[d] / ms, l0 = wet ? pL[d] / ml : s0;
    const double dry = s0 + dt * fS[d] / ms;
    double w, l, s;
    if constexpr (SemiImplicit) {
      const double fLd = fL[d], fmix = fS[d];
      const double vLs = l0 + dt * fLd / ml, vSs = s0 + dt * (fmix - fLd) / ms;
      w = (vLs - vSs) * relax;
      l = vLs - dt * Q * w / ml;
      const double aL = (l - l0) / dt;
      s = s0 + dt * (fmix - mL * aL) / ms;
    } else {
      w = l0 - s0;
      const double aL = (fL[d] - Q * w) / ml;
      l = l0 + dt * aL;
      s = s0 + dt * (fS[d] - mL * aL) / ms;
    }
    vS0[d] = has ? s0 : 0.0;
    vL0[d] = has ? l0 : 0.0;
    vS[d] = !has ? 0.0 : wet ? s : dry;
    vL[d] = !has ? 0.0 : wet ? l : dry;
    wd[d] = wet ? w : 0.0;
  }
}

// The rest of node i = ii + nx j's update from its masses, drag coefficient and velocities
// (two_phase_node_velocities): the walls, the node's share of the reductions into r, its
// velocities after and before the update into both grids.
template <class GridT>
KOKKOS_FORCEINLINE_FUNCTION void finish_two_phase_node(
    const GridT& S, const GridT& L, const int i, const int ii, const int j, const double mS,
    const double mL, const double Q, const double vS0[2], const double vL0[2], double vS[2],
    double vL[2], const double wd[2], const Boundaries& walls, const Boundaries& liquid_walls,
    const double ox, const double oy, const double dx, const double tol, const double dt,
    const double gx, const double gy, TwoPhaseUpdateSums& r) {
  if (mS > 0.0) {
    const bool wet = mL > 0.0;
    const double bS[2] = {vS[0], vS[1]}, bL[2] = {vL[0], vL[1]};
    const double x = ox + ii * dx, y = oy + j * dx;
    const bool hitS = apply_walls(walls, x, y, vS, tol);
    const bool hitL = wet && apply_walls(liquid_walls, x, y, vL, tol);
    double vSm[2], vLm[2];
    for (int d = 0; d < 2; ++d) {
      vSm[d] = 0.5 * (vS0[d] + vS[d]);
      vLm[d] = 0.5 * (vL0[d] + vL[d]);
    }
    if (hitS || hitL) {
      for (int d = 0; d < 2; ++d)
        r.wall_lost -= mS * (vS[d] - bS[d]) * vSm[d] + (wet ? mL * (vL[d] - bL[d]) * vLm[d] : 0.0);
      r.rx += -(mS * (vS[0] - bS[0]) + (wet ? mL * (vL[0] - bL[0]) : 0.0)) / dt;
      r.ry += -(mS * (vS[1] - bS[1]) + (wet ? mL * (vL[1] - bL[1]) : 0.0)) / dt;
    }
    if (wet) {
      const double wm[2] = {vLm[0] - vSm[0], vLm[1] - vSm[1]};
      r.drag_lost += dt * Q * (wd[0] * wm[0] + wd[1] * wm[1]);
      r.seep += dt * mL * (gx * wm[0] + gy * wm[1]);
    }
  }
  for (int d = 0; d < 2; ++d) {
    S.velocity_old(i, d) = vS0[d];
    S.velocity(i, d) = vS[d];
    L.velocity_old(i, d) = vL0[d];
    L.velocity(i, d) = vL[d];
  }
}

// The update of node i = ii + nx j from its sums n (see the file comment): its velocities
// after and before the update into both grids, its share of the reductions into r.
template <bool SemiImplicit, class GridT>
KOKKOS_FORCEINLINE_FUNCTION void update_two_phase_node(
    const GridT& S, const GridT& L, const int i, const int ii, const int j,
    const TwoPhaseNodeSums& n, const Boundaries& walls, const Boundaries& liquid_walls,
    const double ox, const double oy, const double dx, const double tol, const double dt,
    const double gx, const double gy, TwoPhaseUpdateSums& r) {
  double vS0[2], vL0[2], vS[2], vL[2], wd[2];
  two_phase_node_velocities<SemiImplicit>(n.mS, n.mL, n.Q, n.pS, n.pL, n.fS, n.fL, dt, vS0, vL0, vS,
                                          vL, wd);
  finish_two_phase_node(S, L, i, ii, j, n.mS, n.mL, n.Q, vS0, vL0, vS, vL, wd, walls, liquid_walls,
                        ox, oy, dx, tol, dt, gx, gy, r);
}

// update_two_phase_node for nodes ii0..ii1 (at most kNodeRun of them) of row j, from their sums
// node_sums(ii, j, i), in three loops: the sums, the velocities (two_phase_node_velocities: the
// divisions, most of a node's time, a vector of nodes at a time where the compiler vectorises
// the loop), and the rest node by node in the nodes' order (the same bits as one node at a time).
constexpr int kNodeRun = 16;
template <bool SemiImplicit, class GridT, class NodeSums>
KOKKOS_INLINE_FUNCTION void update_two_phase_node_run(
    const GridT& S, const GridT& L, const int nx, const int j, const int ii0, const int ii1,
    const NodeSums& node_sums, const Boundaries& walls, const Boundaries& liquid_walls,
    const double ox, const double oy, const double dx, const double tol, const double dt,
    const double gx, const double gy, TwoPhaseUpdateSums& r) {
  constexpr int K = kNodeRun;
  const int n = ii1 - ii0 + 1;
  double mS[K], mL[K], Q[K], pS[2][K], pL[2][K], fS[2][K], fL[2][K];
  for (int k = 0; k < n; ++k) {
    const TwoPhaseNodeSums s = node_sums(ii0 + k, j, ii0 + k + nx * j);
    mS[k] = s.mS;
    mL[k] = s.mL;
    Q[k] = s.Q;
    for (int d = 0; d < 2; ++d) {
      pS[d][k] = s.pS[d];
      pL[d][k] = s.pL[d];
      fS[d][k] = s.fS[d];
      fL[d][k] = s.fL[d];
    }
  }
  double vS0[2][K], vL0[2][K], vS[2][K], vL[2][K], wd[2][K];
#pragma GCC ivdep
  for (int k = 0; k < n; ++k) {
    const double ps[2] = {pS[0][k], pS[1][k]}, pl[2] = {pL[0][k], pL[1][k]};
    const double fs[2] = {fS[0][k], fS[1][k]}, fl[2] = {fL[0][k], fL[1][k]};
    double s0[2], l0[2], s[2], l[2], w[2];
    two_phase_node_velocities<SemiImplicit>(mS[k], mL[k], Q[k], ps, pl, fs, fl, dt, s0, l0, s, l,
                                            w);
    for (int d = 0; d < 2; ++d) {
      vS0[d][k] = s0[d];
      vL0[d][k] = l0[d];
      vS[d][k] = s[d];
      vL[d][k] = l[d];
      wd[d][k] = w[d];
    }
  }
  for (int k = 0; k < n; ++k) {
    const double s0[2] = {vS0[0][k], vS0[1][k]}, l0[2] = {vL0[0][k], vL0[1][k]};
    const double w[2] = {wd[0][k], wd[1][k]};
    double s[2] = {vS[0][k], vS[1][k]}, l[2] = {vL[0][k], vL[1][k]};
    finish_two_phase_node(S, L, ii0 + k + nx * j, ii0 + k, j, mS[k], mL[k], Q[k], s0, l0, s, l, w,
                          walls, liquid_walls, ox, oy, dx, tol, dt, gx, gy, r);
  }
}

// The update of every node of `region` (a reduction of the report's sums over the nodes in
// rows, NodeItems, narrowed by the row spans `spans` where given): node_sums(ii, j, i) gives the
// sums of node (ii, j), index i (read from the grids here; taken from P2G's buffers, and
// stored, by two_phase_p2g_grid_update.hpp), then update_two_phase_node. Afterwards every node
// outside the mass rectangle (and its row spans) is zero.
template <class ExecSpace, bool SemiImplicit, class MemorySpace, class NodeSums>
GridUpdateReport update_two_phase_nodes(const char* name, const TwoPhaseGrid<MemorySpace>& g,
                                        const NodeBox& region, const int* spans,
                                        const Boundaries& walls, const Boundaries& liquid_walls,
                                        double dt, const double gravity[2],
                                        const NodeSums& node_sums) {
  const auto S = g.solid;
  const auto L = g.liquid;
  const double ox = S.origin[0], oy = S.origin[1], dx = S.dx, tol = 1e-9 * S.dx;
  const double gx = gravity[0], gy = gravity[1];
  const int nx = S.nx;
  GridUpdateReport rep;
  if (region.empty()) return rep;
  double fx = 0.0, fy = 0.0;
  const NodeItems<ExecSpace> items(region, spans);
  constexpr bool runs_of_nodes = NodeItems<ExecSpace>::whole_rows && SemiImplicit;  // host
  Kokkos::parallel_reduce(
      name, range_policy<ExecSpace>(0, items.count()),
      KOKKOS_LAMBDA(const int t, double& wall_lost, double& drag_lost, double& seep, double& rx,
                    double& ry) {
        TwoPhaseUpdateSums r{wall_lost, drag_lost, seep, rx, ry};
        items.visit(t, [&](const int j, const int i_begin, const int i_end) {
          // (A plain `if` on a constant: nvcc refuses a device lambda's first capture of a
          // variable inside `if constexpr`.)
          if (runs_of_nodes) {
            // A row, a run of nodes at a time (the explicit drag's fewer divisions do not pay
            // for the run's passes over its arrays: one node at a time).
            for (int ii = i_begin; ii <= i_end; ii += kNodeRun)
              update_two_phase_node_run<SemiImplicit>(
                  S, L, nx, j, ii, i_end - ii < kNodeRun ? i_end : ii + kNodeRun - 1, node_sums,
                  walls, liquid_walls, ox, oy, dx, tol, dt, gx, gy, r);
          } else {  // a row of the region, or one node
            for (int ii = i_begin; ii <= i_end; ++ii) {
              const int i = ii + nx * j;
              update_two_phase_node<SemiImplicit>(S, L, i, ii, j, node_sums(ii, j, i), walls,
                                                  liquid_walls, ox, oy, dx, tol, dt, gx, gy, r);
            }
          }
        });
        wall_lost = r.wall_lost;
        drag_lost = r.drag_lost;
        seep = r.seep;
        rx = r.rx;
        ry = r.ry;
      },
      rep.wall_dissipation, rep.drag_dissipation, rep.seepage_gravity_work, fx, fy);
  S.set_dirty_to_mass();
  L.set_dirty_to_mass();
  rep.wall_force[0] = fx;
  rep.wall_force[1] = fy;
  return rep;
}

template <class ExecSpace, bool SemiImplicit, class MemorySpace>
GridUpdateReport two_phase_grid_update_impl(const TwoPhaseGrid<MemorySpace>& g,
                                            const Boundaries& walls, const Boundaries& liquid_walls,
                                            double dt, const double gravity[2]) {
  const auto S = g.solid;
  const auto L = g.liquid;
  const auto drag = g.drag;
  // Only the nodes whose fields may be nonzero (Grid::active, set by two_phase_p2g for both
  // grids): outside them nothing moves.
  return update_two_phase_nodes<ExecSpace, SemiImplicit>(
      SemiImplicit ? "lsi::mpm::two_phase::grid_update_semi_implicit"
                   : "lsi::mpm::two_phase::grid_update_explicit",
      g, S.dirty_box(), S.dirty_rows(), walls, liquid_walls, dt, gravity,
      KOKKOS_LAMBDA(const int, const int, const int i) {
        return TwoPhaseNodeSums{S.mass(i),
                                L.mass(i),
                                {S.momentum(i, 0), S.momentum(i, 1)},
                                {L.momentum(i, 0), L.momentum(i, 1)},
                                {S.force(i, 0), S.force(i, 1)},
                                {L.force(i, 0), L.force(i, 1)},
                                drag(i)};
      });
}

template <class ExecSpace, class MemorySpace>
GridUpdateReport two_phase_grid_update(const TwoPhaseGrid<MemorySpace>& g, const Boundaries& walls,
                                       const Boundaries& liquid_walls, double dt,
                                       const double gravity[2], Drag drag) {
  return drag == Drag::SemiImplicit
             ? two_phase_grid_update_impl<ExecSpace, true>(g, walls, liquid_walls, dt, gravity)
             : two_phase_grid_update_impl<ExecSpace, false>(g, walls, liquid_walls, dt, gravity);
}

}  // namespace lsi::mpm::two_phase

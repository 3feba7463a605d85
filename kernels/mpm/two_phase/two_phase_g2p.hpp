// Two-phase grid to particle (APIC for both phases): solid and liquid velocities interpolated,
// their affine matrices C = 4/dx^2 sum w v_i (x_i - x_p)^T, the solid velocity gradient
// L_S = sum v_S,i grad(w)^T (for the effective stress, the volume and the porosity), the liquid
// divergence div v_L = sum v_L,i . grad(w) (for the pore pressure), and the position, which moves
// with the SOLID: x += dt sum w (v_S,i_old + v_S,i) / 2 (trapezoidal, as the single-phase g2p).
// In the same pass: the largest speed of either phase (time step), the work of the points'
// surface loads dt t_p . v_S,mid, and the health check (non-finite velocities, positions or
// pore pressures; points within one cell of the grid edge).
// With the wall correction (two_phase_p2g.hpp), the nodes strictly beyond a corrected wall are
// read as ghosts: their velocity component normal to the wall is minus that of their mirror node
// (the odd extension of the normal velocity about a symmetry plane), so that the divergence and
// velocity gradient seen by the points is the transpose of the mirror forces of P2G (a consistent
// pair: without it the correction drives a growing checkerboard of the pore pressure in the
// lowest cells). Corrected walls must lie on grid lines.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/math.hpp"
#include "kernels/mpm/boundary.hpp"
#include "kernels/mpm/g2p.hpp"
#include "kernels/mpm/shape_function.hpp"
#include "kernels/mpm/two_phase/two_phase_grid.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"

namespace lsi::mpm::two_phase {

struct TwoPhaseG2PReport {
  G2PReport health;            // max_speed over both phases, non_finite, outside
  double load_work = 0.0;      // J/m, work of the surface loads this step
};

template <class ExecSpace, class MemorySpace>
TwoPhaseG2PReport two_phase_g2p(const TwoPhaseParticles<MemorySpace>& p,
                                const TwoPhaseGrid<MemorySpace>& g, double dt,
                                const Boundaries* walls = nullptr,
                                const Boundaries* liquid_walls = nullptr) {
  const auto s = p.solid;
  const auto S = g.solid;
  const auto L = g.liquid;
  const double ox = S.origin[0], oy = S.origin[1], dx = S.dx, inv_dx = 1.0 / S.dx;
  const double apic = 4.0 * inv_dx * inv_dx;
  const double xmax = (S.nx - 2) * dx, ymax = (S.ny - 2) * dx;
  const int nx = S.nx;
  // Corrected walls: left, right, bottom, top; node index of the wall line, inward sign.
  const Boundaries none;
  const Boundaries& sw = walls ? *walls : none;
  const Boundaries& lw = liquid_walls ? *liquid_walls : none;
  const bool ghost_s[4] = {sw.left.active, sw.right.active, sw.bottom.active, sw.top.active};
  const bool ghost_l[4] = {lw.left.active, lw.right.active, lw.bottom.active, lw.top.active};
  const bool any_ghost = walls != nullptr || liquid_walls != nullptr;
  auto index_of = [&](const Wall& a, const Wall& b, double o) {
    const Wall& w = a.active ? a : b;
    return static_cast<int>((w.position - o) * inv_dx + 0.5);
  };
  const int wall_index[4] = {index_of(sw.left, lw.left, ox), index_of(sw.right, lw.right, ox),
                             index_of(sw.bottom, lw.bottom, oy), index_of(sw.top, lw.top, oy)};
  double vmax = 0.0, work = 0.0;
  int bad = 0, out = 0;
  Kokkos::parallel_reduce(
      "lsi::mpm::two_phase::g2p", Kokkos::RangePolicy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& vm, double& wk, int& nonfinite, int& outside) {
        const double xp = s.position(q, 0) - ox, yp = s.position(q, 1) - oy;
        const Stencil1D sx = quadratic_bspline(xp, inv_dx), sy = quadratic_bspline(yp, inv_dx);
        double vS[2] = {0, 0}, vSm[2] = {0, 0}, CS[2][2] = {{0, 0}, {0, 0}},
               LS[2][2] = {{0, 0}, {0, 0}};
        double vL[2] = {0, 0}, CL[2][2] = {{0, 0}, {0, 0}}, divL = 0.0;
        for (int b = 0; b < 3; ++b) {
          const double wy = sy.w[b], dwy = sy.dw[b], dyb = (sy.base + b) * dx - yp;
          const int row = sx.base + nx * (sy.base + b);
          for (int a = 0; a < 3; ++a) {
            const int node = row + a;
            const double w = sx.w[a] * wy, dxa = (sx.base + a) * dx - xp;
            const double gw[2] = {sx.dw[a] * wy, sx.w[a] * dwy};
            // Ghost nodes: for each phase, the mirror node across every corrected wall the node
            // lies beyond, and which components are reflected.
            int ms_node = node, ml_node = node;
            bool flip_s[2] = {false, false}, flip_l[2] = {false, false};
            if (any_ghost) {
              int is[2] = {sx.base + a, sy.base + b}, il[2] = {sx.base + a, sy.base + b};
              for (int k = 0; k < 4; ++k) {
                const int ax = k < 2 ? 0 : 1;
                const int sg = (k == 0 || k == 2) ? 1 : -1;
                const int own = ax == 0 ? sx.base + a : sy.base + b;
                if (sg * (own - wall_index[k]) >= 0) continue;   // not beyond this wall
                if (ghost_s[k]) { is[ax] = 2 * wall_index[k] - own; flip_s[ax] = true; }
                if (ghost_l[k]) { il[ax] = 2 * wall_index[k] - own; flip_l[ax] = true; }
              }
              ms_node = is[0] + nx * is[1];
              ml_node = il[0] + nx * il[1];
            }
            for (int r = 0; r < 2; ++r) {
              const double vs = flip_s[r] ? -S.velocity(ms_node, r) : S.velocity(node, r);
              const double vso = flip_s[r] ? -S.velocity_old(ms_node, r) : S.velocity_old(node, r);
              const double vl = flip_l[r] ? -L.velocity(ml_node, r) : L.velocity(node, r);
              vS[r] += w * vs;
              vSm[r] += 0.5 * w * (vs + vso);
              CS[r][0] += w * vs * dxa;
              CS[r][1] += w * vs * dyb;
              LS[r][0] += vs * gw[0];
              LS[r][1] += vs * gw[1];
              vL[r] += w * vl;
              CL[r][0] += w * vl * dxa;
              CL[r][1] += w * vl * dyb;
              divL += vl * gw[r];
            }
          }
        }
        for (int r = 0; r < 2; ++r) {
          s.velocity(q, r) = vS[r];
          p.liquid_velocity(q, r) = vL[r];
          s.position(q, r) += dt * vSm[r];
          for (int c = 0; c < 2; ++c) {
            s.affine(q, r, c) = apic * CS[r][c];
            p.liquid_affine(q, r, c) = apic * CL[r][c];
            s.velocity_gradient(q, r, c) = LS[r][c];
          }
        }
        p.liquid_divergence(q) = divL;
        wk += dt * (p.traction(q, 0) * vSm[0] + p.traction(q, 1) * vSm[1]);
        const double s2 = vS[0] * vS[0] + vS[1] * vS[1], l2 = vL[0] * vL[0] + vL[1] * vL[1];
        if (!(s2 < 1e300) || !(l2 < 1e300) || !(s.position(q, 0) == s.position(q, 0)) ||
            !(s.position(q, 1) == s.position(q, 1)) ||
            !(math::fabs(p.pore_pressure(q)) < 1e300)) {
          ++nonfinite;
        } else {
          const double v = math::sqrt(math::max(s2, l2));
          if (v > vm) vm = v;
        }
        const double px = s.position(q, 0) - ox, py = s.position(q, 1) - oy;
        if (!(px > dx && px < xmax && py > dx && py < ymax)) ++outside;
      },
      Kokkos::Max<double>(vmax), work, bad, out);
  TwoPhaseG2PReport r;
  r.health.max_speed = vmax;
  r.health.non_finite = bad;
  r.health.outside = out;
  r.load_work = work;
  return r;
}

}  // namespace lsi::mpm::two_phase

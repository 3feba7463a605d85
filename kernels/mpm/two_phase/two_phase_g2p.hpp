// Two-phase grid to particle, APIC or a FLIP/PIC blend for both phases (the single-phase
// Transfer and flip ratio of g2p.hpp): with
// APIC the solid and liquid velocities are interpolated and so are their affine matrices
// C = 4/dx^2 sum w v_i (x_i - x_p)^T; with FLIP/PIC each velocity is
// r (v_p + sum w (v_i - v_i,old)) + (1 - r) sum w v_i and the affine matrices stay zero (the
// single-phase g2p.hpp's blend, per phase). Then the solid velocity gradient
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
// Separable sums (as the single-phase g2p.hpp): each row of 3 nodes is summed first, then the
// row factors.
// two_phase_g2p_update() runs, in the same pass over the points, the rest of the step's point
// work with L_S and div v_L still in registers: the effective-stress update (stress_update.hpp),
// the pore pressure and porosity (pore_pressure_update.hpp, when the free-surface drainage is
// off: it needs every point's new volume first) and the time-step limits of the next step
// (two_phase_time_step.hpp). One pass over the points instead of five.
#pragma once
#include <Kokkos_Core.hpp>
#include <cmath>

#include "kernels/common/math.hpp"
#include "kernels/mpm/boundary.hpp"
#include "kernels/mpm/g2p.hpp"
#include "kernels/mpm/shape_function.hpp"
#include "kernels/mpm/stress_update.hpp"
#include "kernels/mpm/two_phase/pore_pressure_update.hpp"
#include "kernels/mpm/two_phase/two_phase_grid.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"
#include "kernels/mpm/two_phase/two_phase_time_step.hpp"

namespace lsi::mpm::two_phase {

struct TwoPhaseG2PReport {
  G2PReport health;        // max_speed over both phases, non_finite, outside
  double load_work = 0.0;  // J/m, work of the surface loads this step
  // two_phase_g2p_update() only:
  double viscous_work = 0.0;  // J/m, the bulk viscosity's work (pore pressure fused)
  TimeStepLimits limits;      // of the points at the end of the step (pore pressure fused)
};

// What two_phase_g2p_impl does after the transfer of a point.
struct TwoPhasePointWork {
  bool plastic = false;         // the stress update with Mohr-Coulomb (a kernel of its own)
  bool pore_pressure = false;   // pore pressure, porosity and the next step's limits
  TwoPhaseConstants constants;  // of the pore pressure and the limits
};

// The corrected walls of the ghost reads (see the file comment).
struct GhostWalls {
  bool solid[4] = {false, false, false, false};  // left, right, bottom, top
  bool liquid[4] = {false, false, false, false};
  int index[4] = {0, 0, 0, 0};  // node index of the wall line
};

template <class ExecSpace, bool Ghosts, G2PStress Stress, bool Apic, class MemorySpace>
TwoPhaseG2PReport two_phase_g2p_impl(
    const TwoPhaseParticles<MemorySpace>& p, const TwoPhaseGrid<MemorySpace>& g, double dt,
    const GhostWalls& gw, const TwoPhasePointWork& work, double flip_ratio,
    const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials = {}) {
  const auto s = p.solid;
  const auto S = g.solid;
  const auto L = g.liquid;
  const double ox = S.origin[0], oy = S.origin[1], dx = S.dx, inv_dx = 1.0 / S.dx;
  const double apic = 4.0 * inv_dx * inv_dx;
  const double xmax = (S.nx - 2) * dx, ymax = (S.ny - 2) * dx;
  const int nx = S.nx;
  const bool pore = work.pore_pressure;
  const TwoPhaseConstants kc = work.constants;
  const double flip = flip_ratio, pic = 1.0 - flip_ratio;
  double vmax = 0.0, load = 0.0, viscous = 0.0, cmax = 0.0, dtk = 1e300;
  int bad = 0, out = 0;
  Kokkos::parallel_reduce(
      Stress == G2PStress::None ? "lsi::mpm::two_phase::g2p" : "lsi::mpm::two_phase::g2p_update",
      Kokkos::RangePolicy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& vm, double& wk, double& visc, double& cm, double& tk,
                    int& nonfinite, int& outside) {
        // Named here, outside the `if constexpr`s: nvcc rejects a lambda whose first use (and
        // so capture) of a variable is inside one (`points` and `apic_scale` are first used in
        // the Apic branches below).
        [[maybe_unused]] const auto& mats = materials;
        [[maybe_unused]] const GhostWalls& ghost = gw;
        [[maybe_unused]] const bool fuse_pore = pore;
        [[maybe_unused]] const TwoPhaseConstants& constants = kc;
        [[maybe_unused]] const double r_flip = flip, r_pic = pic;
        [[maybe_unused]] const double apic_scale = apic;  // 4 / dx^2, APIC only
        const auto& points = p;
        const auto& grid_s = S;
        const auto& grid_l = L;
        const double xp = s.position(q, 0) - ox, yp = s.position(q, 1) - oy;
        const Stencil1D sx = quadratic_bspline(xp, inv_dx), sy = quadratic_bspline(yp, inv_dx);
        const double* wx = sx.w;
        const double* dwx = sx.dw;
        double wxd[3];
        offset_weights(sx, xp, dx, wxd);
        double vS[2] = {0, 0}, vSm[2] = {0, 0}, CS[2][2] = {{0, 0}, {0, 0}},
               LS[2][2] = {{0, 0}, {0, 0}};
        double vL[2] = {0, 0}, CL[2][2] = {{0, 0}, {0, 0}}, divL = 0.0;
        [[maybe_unused]] double vSo[2] = {0, 0}, vLo[2] = {0, 0};  // FLIP: old grid velocities
        for (int b = 0; b < 3; ++b) {  // rows outside: the inner loop walks contiguous nodes
          const double wy = sy.w[b], dwy = sy.dw[b], dyb = (sy.base + b) * dx - yp;
          const int row = sx.base + nx * (sy.base + b);
          double A0s[2] = {0, 0}, A1s[2] = {0, 0}, A2s[2] = {0, 0}, O0s[2] = {0, 0};
          double A0l[2] = {0, 0}, A1l[2] = {0, 0}, A2l = 0.0, O0l[2] = {0, 0};
          for (int a = 0; a < 3; ++a) {
            const int node = row + a;
            double vs[2], vso[2], vl[2], vlo[2] = {0, 0};
            if constexpr (Ghosts) {
              // Ghost nodes: for each phase, the mirror node across every corrected wall the
              // node lies beyond, and which components are reflected.
              int is[2] = {sx.base + a, sy.base + b}, il[2] = {sx.base + a, sy.base + b};
              bool flip_s[2] = {false, false}, flip_l[2] = {false, false};
              for (int k = 0; k < 4; ++k) {
                const int ax = k < 2 ? 0 : 1;
                const int sg = (k == 0 || k == 2) ? 1 : -1;
                const int own = ax == 0 ? sx.base + a : sy.base + b;
                if (sg * (own - ghost.index[k]) >= 0) continue;  // not beyond this wall
                if (ghost.solid[k]) {
                  is[ax] = 2 * ghost.index[k] - own;
                  flip_s[ax] = true;
                }
                if (ghost.liquid[k]) {
                  il[ax] = 2 * ghost.index[k] - own;
                  flip_l[ax] = true;
                }
              }
              const int ms_node = is[0] + nx * is[1], ml_node = il[0] + nx * il[1];
              for (int r = 0; r < 2; ++r) {
                vs[r] = flip_s[r] ? -grid_s.velocity(ms_node, r) : grid_s.velocity(node, r);
                vso[r] =
                    flip_s[r] ? -grid_s.velocity_old(ms_node, r) : grid_s.velocity_old(node, r);
                vl[r] = flip_l[r] ? -grid_l.velocity(ml_node, r) : grid_l.velocity(node, r);
                if constexpr (!Apic)
                  vlo[r] =
                      flip_l[r] ? -grid_l.velocity_old(ml_node, r) : grid_l.velocity_old(node, r);
              }
            } else {
              for (int r = 0; r < 2; ++r) {
                vs[r] = grid_s.velocity(node, r);
                vso[r] = grid_s.velocity_old(node, r);
                vl[r] = grid_l.velocity(node, r);
                if constexpr (!Apic) vlo[r] = grid_l.velocity_old(node, r);
              }
            }
            for (int r = 0; r < 2; ++r) {
              A0s[r] += wx[a] * vs[r];
              A1s[r] += wxd[a] * vs[r];
              A2s[r] += dwx[a] * vs[r];
              O0s[r] += wx[a] * vso[r];
              A0l[r] += wx[a] * vl[r];
              A1l[r] += wxd[a] * vl[r];
              if constexpr (!Apic) O0l[r] += wx[a] * vlo[r];
            }
            A2l += dwx[a] * vl[0];
          }
          for (int r = 0; r < 2; ++r) {
            vS[r] += wy * A0s[r];
            vSm[r] += 0.5 * wy * (A0s[r] + O0s[r]);
            CS[r][0] += wy * A1s[r];
            CS[r][1] += wy * dyb * A0s[r];
            LS[r][0] += wy * A2s[r];
            LS[r][1] += dwy * A0s[r];
            vL[r] += wy * A0l[r];
            if constexpr (!Apic) {
              vSo[r] += wy * O0s[r];
              vLo[r] += wy * O0l[r];
            }
            CL[r][0] += wy * A1l[r];
            CL[r][1] += wy * dyb * A0l[r];
          }
          divL += wy * A2l + dwy * A0l[1];
        }
        for (int r = 0; r < 2; ++r) {
          if constexpr (Apic) {
            s.velocity(q, r) = vS[r];
            points.liquid_velocity(q, r) = vL[r];
          } else {
            s.velocity(q, r) = r_flip * (s.velocity(q, r) + vS[r] - vSo[r]) + r_pic * vS[r];
            points.liquid_velocity(q, r) =
                r_flip * (points.liquid_velocity(q, r) + vL[r] - vLo[r]) + r_pic * vL[r];
          }
          s.position(q, r) += dt * vSm[r];
          for (int c = 0; c < 2; ++c) {
            if constexpr (Apic) {  // FLIP/PIC: the affine matrices stay zero (as built)
              s.affine(q, r, c) = apic_scale * CS[r][c];
              points.liquid_affine(q, r, c) = apic_scale * CL[r][c];
            }
            s.velocity_gradient(q, r, c) = LS[r][c];
          }
        }
        points.liquid_divergence(q) = divL;
        wk += dt * (points.traction(q, 0) * vSm[0] + points.traction(q, 1) * vSm[1]);
        if constexpr (Stress != G2PStress::None) {
          const PreparedMaterial& m = mats(s.material(q));
          // The pore pressure update needs the porosity of the start of the step (n in D) and
          // the volume of the end (stress update first, as in the unfused sequence).
          if (fuse_pore)
            points.volumetric_rate(q) =
                mixture_volumetric_rate(points.porosity(q), LS[0][0] + LS[1][1], divL);
          update_point_stress<Stress == G2PStress::Plastic>(s, q, m, LS[0][0], LS[0][1], LS[1][0],
                                                            LS[1][1], dt);
          if (fuse_pore) {
            visc += update_point_pore_pressure(points, q, m, constants, LS[0][0], LS[0][1],
                                               LS[1][0], LS[1][1], dt);
            point_time_step_limits(points, q, m, constants, cm, tk);
          }
        }
        const double s2 = vS[0] * vS[0] + vS[1] * vS[1], l2 = vL[0] * vL[0] + vL[1] * vL[1];
        if (!(s2 < 1e300) || !(l2 < 1e300) || !(s.position(q, 0) == s.position(q, 0)) ||
            !(s.position(q, 1) == s.position(q, 1)) ||
            !(math::fabs(points.pore_pressure(q)) < 1e300)) {
          ++nonfinite;
        } else {
          const double v = math::sqrt(math::max(s2, l2));
          if (v > vm) vm = v;
        }
        const double px = s.position(q, 0) - ox, py = s.position(q, 1) - oy;
        if (!(px > dx && px < xmax && py > dx && py < ymax)) ++outside;
      },
      Kokkos::Max<double>(vmax), load, viscous, Kokkos::Max<double>(cmax), Kokkos::Min<double>(dtk),
      bad, out);
  TwoPhaseG2PReport r;
  r.health.max_speed = vmax;
  r.health.non_finite = bad;
  r.health.outside = out;
  r.load_work = load;
  r.viscous_work = viscous;
  r.limits.wave_speed = cmax > 0.0 ? std::sqrt(cmax) : 0.0;  // the reduction took c^2
  r.limits.permeability_dt = dtk;
  return r;
}

// The ghost walls from the corrected walls (nullptr: none).
inline GhostWalls ghost_walls(const Boundaries* walls, const Boundaries* liquid_walls,
                              const double origin[2], double inv_dx) {
  const Boundaries none;
  const Boundaries& sw = walls ? *walls : none;
  const Boundaries& lw = liquid_walls ? *liquid_walls : none;
  const Wall* ws[4] = {&sw.left, &sw.right, &sw.bottom, &sw.top};
  const Wall* wl[4] = {&lw.left, &lw.right, &lw.bottom, &lw.top};
  GhostWalls gw;
  for (int k = 0; k < 4; ++k) {
    gw.solid[k] = ws[k]->active;
    gw.liquid[k] = wl[k]->active;
    const Wall& w = ws[k]->active ? *ws[k] : *wl[k];
    gw.index[k] = static_cast<int>((w.position - origin[k < 2 ? 0 : 1]) * inv_dx + 0.5);
  }
  return gw;
}

// The instantiation for the transfer: APIC, or the FLIP/PIC blend with flip_ratio r in [0, 1]
// (1: FLIP, 0: PIC; unused with APIC).
template <class ExecSpace, bool Ghosts, G2PStress Stress, class MemorySpace>
TwoPhaseG2PReport two_phase_g2p_transfer(
    const TwoPhaseParticles<MemorySpace>& p, const TwoPhaseGrid<MemorySpace>& g, double dt,
    const GhostWalls& gw, const TwoPhasePointWork& work, Transfer transfer, double flip_ratio,
    const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials = {}) {
  if (transfer == Transfer::Apic)
    return two_phase_g2p_impl<ExecSpace, Ghosts, Stress, true>(p, g, dt, gw, work, 0.0, materials);
  return two_phase_g2p_impl<ExecSpace, Ghosts, Stress, false>(p, g, dt, gw, work, flip_ratio,
                                                              materials);
}

// G2P of both phases alone (the points' stress, pore pressure and porosity untouched).
template <class ExecSpace, class MemorySpace>
TwoPhaseG2PReport two_phase_g2p(const TwoPhaseParticles<MemorySpace>& p,
                                const TwoPhaseGrid<MemorySpace>& g, double dt,
                                const Boundaries* walls = nullptr,
                                const Boundaries* liquid_walls = nullptr,
                                Transfer transfer = Transfer::Apic, double flip_ratio = 0.0) {
  const GhostWalls gw = ghost_walls(walls, liquid_walls, g.solid.origin, 1.0 / g.dx());
  const TwoPhasePointWork none;
  constexpr G2PStress N = G2PStress::None;
  if (walls != nullptr || liquid_walls != nullptr)
    return two_phase_g2p_transfer<ExecSpace, true, N>(p, g, dt, gw, none, transfer, flip_ratio);
  return two_phase_g2p_transfer<ExecSpace, false, N>(p, g, dt, gw, none, transfer, flip_ratio);
}

// G2P of both phases and the point updates that follow it (see the file comment): the effective
// stress always, the pore pressure, porosity and next step's limits when work.pore_pressure
// (then r.viscous_work and r.limits are set).
template <class ExecSpace, class MemorySpace>
TwoPhaseG2PReport two_phase_g2p_update(
    const TwoPhaseParticles<MemorySpace>& p, const TwoPhaseGrid<MemorySpace>& g, double dt,
    const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials,
    const TwoPhasePointWork& work, const Boundaries* walls = nullptr,
    const Boundaries* liquid_walls = nullptr, Transfer transfer = Transfer::Apic,
    double flip_ratio = 0.0) {
  const GhostWalls gw = ghost_walls(walls, liquid_walls, g.solid.origin, 1.0 / g.dx());
  const bool ghosts = walls != nullptr || liquid_walls != nullptr;
  constexpr G2PStress E = G2PStress::Elastic, P = G2PStress::Plastic;
  const Transfer t = transfer;
  const double r = flip_ratio;
  if (ghosts)
    return work.plastic
               ? two_phase_g2p_transfer<ExecSpace, true, P>(p, g, dt, gw, work, t, r, materials)
               : two_phase_g2p_transfer<ExecSpace, true, E>(p, g, dt, gw, work, t, r, materials);
  return work.plastic
             ? two_phase_g2p_transfer<ExecSpace, false, P>(p, g, dt, gw, work, t, r, materials)
             : two_phase_g2p_transfer<ExecSpace, false, E>(p, g, dt, gw, work, t, r, materials);
}

}  // namespace lsi::mpm::two_phase

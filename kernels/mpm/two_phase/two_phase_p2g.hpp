// Two-phase particle to grid, one pass over the points (ScatterViews as the single-phase P2G,
// duplicated per thread or atomic). Per node i and point p, w = w_ip, with APIC momenta:
//   solid   mass     w m_S                 momentum w m_S (v_S + C_S (x_i - x_p))
//   liquid  mass     w m_L                 momentum w m_L (v_L + C_L (x_i - x_p))
//   mixture force   -V (sigma' - p I) grad(w) + w (m_S + m_L) g + w t_p      (t_p: surface load)
//   liquid  force   +V n p grad(w) + w m_L g     (weak form of -n grad p; the free surface
//                                                 term drops out: natural drained p = 0)
//   drag    Q       w V n^2 rho_L g_D / k        (g_D: the g in the definition of k)
// where p stands for p + q, q >= 0 the artificial bulk viscosity of the point
// (pore_pressure_update.hpp; zero when it is off).
//
// Optional wall correction (TwoPhaseSettings::wall_correction). A wall acts on the nodes on or
// beyond it, but the quadratic B-spline of the first free node above a wall is still 1/8 on the
// wall, so that free node takes 1/8 of the wall's reaction in the weak form and misses it: the
// points of the lowest cell layers carry a decaying +15 %, -5 %, +2 % pattern of the stress and
// pore pressure (the boundary layer of docs/mpm.md, test_mpm_geostatic.cpp). With the correction,
// each point within 1.5 cells of an active wall adds, to the free nodes only (those more than
// 1e-9 dx inside the wall) and to the force component NORMAL to the wall only, the force of its
// mirror image across the wall (a symmetry plane: same normal stresses and pore pressure, shear
// stress and normal gravity reversed). For a field symmetric about the wall this completes the
// partition of unity, i.e. it is the missing share N_j(wall) sigma_nn of the wall reaction. The
// mixture force is corrected for `walls`, the liquid force for `liquid_walls` (impermeable
// walls). Valid while the material rests against the wall (a column, a deposit, a flow on its
// base); a body approaching a wall through the air would feel its mirror within 1.5 cells.
#pragma once
#include <Kokkos_Core.hpp>
#include <Kokkos_ScatterView.hpp>

#include "kernels/mpm/boundary.hpp"
#include "kernels/mpm/p2g.hpp"
#include "kernels/mpm/shape_function.hpp"
#include "kernels/mpm/two_phase/two_phase_grid.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"

namespace lsi::mpm::two_phase {

template <class ExecSpace, bool Atomic>
struct TwoPhaseScatter {
  using Single = GridScatter<ExecSpace, Atomic>;
  Single solid, liquid;
  typename Single::template SV<double*> drag;

  TwoPhaseScatter() = default;
  template <class MemorySpace>
  explicit TwoPhaseScatter(const TwoPhaseGrid<MemorySpace>& g)
      : solid(g.solid), liquid(g.liquid), drag(g.drag) {}
};

template <class ExecSpace, bool Atomic, class MemorySpace>
void two_phase_p2g(const TwoPhaseParticles<MemorySpace>& p, const TwoPhaseGrid<MemorySpace>& g,
                   TwoPhaseScatter<ExecSpace, Atomic>& scatter, const double gravity[2],
                   double liquid_density, double darcy_gravity, const Boundaries* walls = nullptr,
                   const Boundaries* liquid_walls = nullptr) {
  namespace KE = Kokkos::Experimental;
  if constexpr (GridScatter<ExecSpace, Atomic>::duplicated) {
    for (auto* grid : {&g.solid, &g.liquid}) {
      Kokkos::deep_copy(grid->mass, 0.0);
      Kokkos::deep_copy(grid->momentum, 0.0);
      Kokkos::deep_copy(grid->force, 0.0);
    }
    Kokkos::deep_copy(g.drag, 0.0);
  }
  for (auto* s : {&scatter.solid, &scatter.liquid}) {
    s->mass.reset();
    s->momentum.reset();
    s->force.reset();
  }
  scatter.drag.reset();
  auto& ms = scatter.solid.mass;
  auto& ps = scatter.solid.momentum;
  auto& fs = scatter.solid.force;
  auto& ml = scatter.liquid.mass;
  auto& pl = scatter.liquid.momentum;
  auto& fl = scatter.liquid.force;
  auto& dq = scatter.drag;
  const auto s = p.solid;
  const double ox = g.solid.origin[0], oy = g.solid.origin[1], dx = g.solid.dx;
  const double inv_dx = 1.0 / dx;
  const int nx = g.solid.nx;
  const double gx = gravity[0], gy = gravity[1], rhoLg = liquid_density * darcy_gravity;
  // Walls for the correction, relative to the grid origin: left, right, bottom, top.
  const bool correct = walls != nullptr || liquid_walls != nullptr;
  const Boundaries none;
  const Boundaries& sw = walls ? *walls : none;
  const Boundaries& lw = liquid_walls ? *liquid_walls : none;
  const bool wall_on[4] = {sw.left.active, sw.right.active, sw.bottom.active, sw.top.active};
  const bool liquid_on[4] = {lw.left.active, lw.right.active, lw.bottom.active, lw.top.active};
  const double wall_at[4] = {(sw.left.active ? sw.left.position : lw.left.position) - ox,
                              (sw.right.active ? sw.right.position : lw.right.position) - ox,
                              (sw.bottom.active ? sw.bottom.position : lw.bottom.position) - oy,
                              (sw.top.active ? sw.top.position : lw.top.position) - oy};
  const double tol = 1e-9 * dx;
  Kokkos::parallel_for(
      "lsi::mpm::two_phase::p2g", Kokkos::RangePolicy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q) {
        auto ms_a = ms.access();
        auto ps_a = ps.access();
        auto fs_a = fs.access();
        auto ml_a = ml.access();
        auto pl_a = pl.access();
        auto fl_a = fl.access();
        auto dq_a = dq.access();
        const double xp = s.position(q, 0) - ox, yp = s.position(q, 1) - oy;
        const Stencil1D sx = quadratic_bspline(xp, inv_dx), sy = quadratic_bspline(yp, inv_dx);
        const double mS = s.mass(q), mL = p.liquid_mass(q), V = s.volume(q);
        // p + q: the artificial bulk viscosity acts like a pore pressure (pore_pressure_update.hpp)
        const double n = p.porosity(q), pw = p.pore_pressure(q) + p.viscous_pressure(q);
        const double vS[2] = {s.velocity(q, 0), s.velocity(q, 1)};
        const double vL[2] = {p.liquid_velocity(q, 0), p.liquid_velocity(q, 1)};
        // total stress times volume (tension positive)
        const double Vs[3] = {V * (s.stress(q, 0) - pw), V * (s.stress(q, 1) - pw), V * s.stress(q, 2)};
        const double Vnp = V * n * pw;
        const double Q = V * n * n * rhoLg / p.conductivity(q);
        const double fext[2] = {(mS + mL) * gx + p.traction(q, 0), (mS + mL) * gy + p.traction(q, 1)};
        const double fLext[2] = {mL * gx, mL * gy};
        for (int b = 0; b < 3; ++b) {
          const double wy = sy.w[b], dwy = sy.dw[b], dyb = (sy.base + b) * dx - yp;
          const int row = sx.base + nx * (sy.base + b);
          for (int a = 0; a < 3; ++a) {
            const int node = row + a;
            const double w = sx.w[a] * wy, dxa = (sx.base + a) * dx - xp;
            const double gw[2] = {sx.dw[a] * wy, sx.w[a] * dwy};
            ms_a(node) += w * mS;
            ml_a(node) += w * mL;
            dq_a(node) += w * Q;
            for (int r = 0; r < 2; ++r) {
              ps_a(node, r) += w * mS * (vS[r] + s.affine(q, r, 0) * dxa + s.affine(q, r, 1) * dyb);
              pl_a(node, r) += w * mL * (vL[r] + p.liquid_affine(q, r, 0) * dxa +
                                         p.liquid_affine(q, r, 1) * dyb);
              fl_a(node, r) += Vnp * gw[r] + w * fLext[r];
            }
            fs_a(node, 0) += -(Vs[0] * gw[0] + Vs[2] * gw[1]) + w * fext[0];
            fs_a(node, 1) += -(Vs[2] * gw[0] + Vs[1] * gw[1]) + w * fext[1];
          }
        }
        if (!correct) return;
        // Mirror images across the walls (see the file comment). Wall k: axis a (0: x, 1: y),
        // position c, inward sign s (+1: the material is on the side of larger coordinates).
        for (int k = 0; k < 4; ++k) {
          const bool solid_wall = wall_on[k], liquid_wall = liquid_on[k];
          if (!solid_wall && !liquid_wall) continue;
          const int ax = k < 2 ? 0 : 1;
          const double c = wall_at[k], sgn = (k == 0 || k == 2) ? 1.0 : -1.0;
          const double pos[2] = {xp, yp};
          const double dist = sgn * (pos[ax] - c);   // > 0 inside
          if (!(dist > 0.0 && dist < 1.5 * dx)) continue;
          double mpos[2] = {xp, yp};
          mpos[ax] = 2.0 * c - pos[ax];
          const Stencil1D mx = quadratic_bspline(mpos[0], inv_dx), my = quadratic_bspline(mpos[1], inv_dx);
          // Normal force of the image: -V (sigma_nn d_n w - sigma_nt d_t w) - w m g_n (mixture),
          // V n p d_n w - w m_L g_n (liquid).
          const double snn = Vs[ax == 0 ? 0 : 1], snt = Vs[2];
          const double gn = ax == 0 ? gx : gy;
          for (int b = 0; b < 3; ++b)
            for (int a = 0; a < 3; ++a) {
              const int ni[2] = {mx.base + a, my.base + b};
              if (!(sgn * (ni[ax] * dx - c) > tol)) continue;   // free nodes only
              const int node = ni[0] + nx * ni[1];
              const double w = mx.w[a] * my.w[b];
              const double gw[2] = {mx.dw[a] * my.w[b], mx.w[a] * my.dw[b]};
              if (solid_wall)
                fs_a(node, ax) += -(snn * gw[ax] - snt * gw[1 - ax]) - w * (mS + mL) * gn;
              if (liquid_wall) fl_a(node, ax) += Vnp * gw[ax] - w * mL * gn;
            }
        }
      });
  auto gms = g.solid.mass;
  auto gps = g.solid.momentum;
  auto gfs = g.solid.force;
  auto gml = g.liquid.mass;
  auto gpl = g.liquid.momentum;
  auto gfl = g.liquid.force;
  auto gdq = g.drag;
  KE::contribute(gms, ms);
  KE::contribute(gps, ps);
  KE::contribute(gfs, fs);
  KE::contribute(gml, ml);
  KE::contribute(gpl, pl);
  KE::contribute(gfl, fl);
  KE::contribute(gdq, dq);
}

}  // namespace lsi::mpm::two_phase

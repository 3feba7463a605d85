// Pore pressure and porosity update (after G2P and the effective-stress update), per point:
//   D  = (1 - n) tr(eps_dot_S) + n div(v_L)        the mixture's volumetric strain rate
//   dp = -(K_L / n) D dt                            (p compression positive)
// the storage equation of a linearly compressible liquid in a skeleton of incompressible grains
// (liquid mass balance with the solid mass balance substituted), with tr(eps_dot_S) = L_xx + L_yy
// of the solid and div(v_L) of the liquid from the grid velocities of the step (USL).
// Porosity from the solid volumetric strain, the grains being incompressible: the solid volume
// (1 - n) V is constant, so with J = det(I + L_S dt) (the same J that scales V in
// stress_update.hpp)
//   n_new = 1 - (1 - n) / J.
// n of the START of the step is used in dp. Solid and liquid masses of the point are constant.
//
// Optional stabilisations of saturated impacts (docs/notes/two_phase.md, "Impacts"; all off by default):
// * Artificial bulk viscosity (von Neumann-Richtmyer linear + quadratic, Landshoff form, as in
//   explicit impact codes), active in compression only:
//     q = rho_m l (-D) (c1 c + c2 l (-D))   for D < 0,   q = 0 otherwise,
//   rho_m = (m_S + m_L) / V, c the saturated wave speed of the point (two_phase_time_step.hpp),
//   l the cell size. q is a pressure of the point used in P2G with p (p + q in the mixture and
//   in the liquid force) and is NOT accumulated into p. Its work, -q D V dt >= 0 (the q of the
//   start of the step against the D of the step), is returned as dissipation. The time step
//   accounts for it (two_phase_time_step.hpp).
// * Free-surface drainage (free_surface_fill > 0): points whose neighbourhood is not full get
//   p = q = 0 (below).
// * Cell projection of p (project_pore_pressure, called by the solver after this update), and
//   the cell means reported as the smooth pore pressure (cell_mean_pore_pressure).
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/execution_instance.hpp"
#include "kernels/common/math.hpp"
#include "kernels/mpm/constitutive/material.hpp"
#include "kernels/mpm/shape_function.hpp"
#include "kernels/mpm/two_phase/two_phase_grid.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"
#include "kernels/mpm/two_phase/two_phase_time_step.hpp"

namespace lsi::mpm::two_phase {

// Coefficients of the artificial bulk viscosity (dimensionless; 0, 0: off).
struct BulkViscosity {
  double linear = 0.0;     // c1
  double quadratic = 0.0;  // c2
  bool on() const { return linear > 0.0 || quadratic > 0.0; }
};

KOKKOS_INLINE_FUNCTION double bulk_viscous_pressure(double rho_m, double c, double l, double D,
                                                    double c1, double c2) {
  if (!(D < 0.0)) return 0.0;
  return rho_m * l * (-D) * (c1 * c + c2 * l * (-D));
}

// Nodal volume sum_q w_iq V_q into grid.smooth_weight.
template <class ExecSpace, class MemorySpace>
void nodal_volume(const TwoPhaseParticles<MemorySpace>& p, const TwoPhaseGrid<MemorySpace>& g) {
  const auto s = p.solid;
  const auto vol = g.smooth_weight;
  fill<ExecSpace>(vol, 0.0);
  const double ox = g.solid.origin[0], oy = g.solid.origin[1], inv_dx = 1.0 / g.solid.dx;
  const int nx = g.solid.nx;
  Kokkos::parallel_for(
      "lsi::mpm::two_phase::nodal_volume", range_policy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q) {
        const Stencil1D sx = quadratic_bspline(s.position(q, 0) - ox, inv_dx),
                        sy = quadratic_bspline(s.position(q, 1) - oy, inv_dx);
        const double V = s.volume(q);
        for (int b = 0; b < 3; ++b)
          for (int a = 0; a < 3; ++a)
            Kokkos::atomic_add(&vol(sx.base + a + nx * (sy.base + b)), sx.w[a] * sy.w[b] * V);
      });
}

// The cell of a point at (x, y) (index of its lower-left node), or -1 outside the grid (a point
// that left it: the step that moved it there reports it, but the cell kernels may still run).
KOKKOS_INLINE_FUNCTION int cell_of_point(double x, double y, double ox, double oy, double inv_dx,
                                         int nx, int ny) {
  const double fx = (x - ox) * inv_dx, fy = (y - oy) * inv_dx;
  if (!(fx >= 0.0 && fy >= 0.0 && fx < nx - 1 && fy < ny - 1)) return -1;  // NaN: outside
  return static_cast<int>(fx) + nx * static_cast<int>(fy);
}

// The n V weighted sums of the pore pressure per cell (cell index = index of its lower-left node)
// into grid.smooth_value (sum n V p) and grid.smooth_weight (sum n V), over the points of each cell
// (the cell of a point's position).
template <class ExecSpace, class MemorySpace>
void sum_cell_pore_pressure(const TwoPhaseParticles<MemorySpace>& p,
                            const TwoPhaseGrid<MemorySpace>& g) {
  const auto s = p.solid;
  const auto num = g.smooth_value, den = g.smooth_weight;
  fill<ExecSpace>(num, 0.0);
  fill<ExecSpace>(den, 0.0);
  const double ox = g.solid.origin[0], oy = g.solid.origin[1], inv_dx = 1.0 / g.solid.dx;
  const int nx = g.solid.nx, ny = g.solid.ny;
  Kokkos::parallel_for(
      "lsi::mpm::two_phase::cell_pressure_sum", range_policy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q) {
        const int c = cell_of_point(s.position(q, 0), s.position(q, 1), ox, oy, inv_dx, nx, ny);
        if (c < 0) return;
        const double w = p.porosity(q) * s.volume(q);
        Kokkos::atomic_add(&num(c), w * p.pore_pressure(q));
        Kokkos::atomic_add(&den(c), w);
      });
}

// The cell-averaged pore pressure of every point, out(q) = sum_{r in c} n_r V_r p_r /
// sum_{r in c} n_r V_r over the points r of q's cell c: the smooth field that is reported
// (snapshots, the pressure on the barrier's face), whatever the solver keeps per point. Uses the
// grid's smooth_value / smooth_weight as scratch; p is not changed.
template <class ExecSpace, class MemorySpace>
void cell_mean_pore_pressure(const TwoPhaseParticles<MemorySpace>& p,
                             const TwoPhaseGrid<MemorySpace>& g,
                             const Kokkos::View<double*, MemorySpace>& out) {
  sum_cell_pore_pressure<ExecSpace>(p, g);
  const auto s = p.solid;
  const auto num = g.smooth_value, den = g.smooth_weight;
  const double ox = g.solid.origin[0], oy = g.solid.origin[1], inv_dx = 1.0 / g.solid.dx;
  const int nx = g.solid.nx, ny = g.solid.ny;
  Kokkos::parallel_for(
      "lsi::mpm::two_phase::cell_pressure_mean", range_policy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q) {
        const int c = cell_of_point(s.position(q, 0), s.position(q, 1), ox, oy, inv_dx, nx, ny);
        out(q) = c >= 0 && den(c) > 0.0 ? num(c) / den(c) : p.pore_pressure(q);
      });
}

// Cell projection of the pore pressure (`cell_pressure`): p_p <- the cell mean above, in place. A
// projection (P^2 = P) that is symmetric in the n V weighted product, so with p already uniform in
// the cell it changes nothing and the forces of P2G stay the transpose of the storage equation
// (energy consistent); points crossing cells are mixed, which can only lower the stored liquid
// energy sum n V p^2 / (2 K_L) (Jensen): the drop is returned (J/m). Removes the checkerboard
// (Q1P0-like pressure per cell).
template <class ExecSpace, class MemorySpace>
double project_pore_pressure(const TwoPhaseParticles<MemorySpace>& p,
                             const TwoPhaseGrid<MemorySpace>& g, double liquid_bulk_modulus) {
  sum_cell_pore_pressure<ExecSpace>(p, g);
  const auto s = p.solid;
  const auto num = g.smooth_value, den = g.smooth_weight;
  const double ox = g.solid.origin[0], oy = g.solid.origin[1], inv_dx = 1.0 / g.solid.dx;
  const int nx = g.solid.nx, ny = g.solid.ny;
  const double K_L = liquid_bulk_modulus;
  double drop = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::two_phase::cell_pressure_set", range_policy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& d) {
        const int c = cell_of_point(s.position(q, 0), s.position(q, 1), ox, oy, inv_dx, nx, ny);
        if (c < 0) return;
        const double w = p.porosity(q) * s.volume(q);
        const double p0 = p.pore_pressure(q), p1 = num(c) / den(c);
        d += w * (p0 * p0 - p1 * p1) / (2.0 * K_L);
        p.pore_pressure(q) = p1;
      },
      drop);
  return drop;
}

// D = (1 - n) tr(L_S) + n div(v_L) (see the file comment).
KOKKOS_FORCEINLINE_FUNCTION double mixture_volumetric_rate(double n, double trace_L_solid,
                                                           double liquid_divergence) {
  return (1.0 - n) * trace_L_solid + n * liquid_divergence;
}

// The pore pressure and porosity of point q from D = volumetric_rate(q) (set by the caller) and
// the solid velocity gradient L of the step (the first part of update_point_pore_pressure).
// Without branches, so that the host's loop over a block of points vectorises (two_phase_g2p.hpp).
template <class Points>
KOKKOS_FORCEINLINE_FUNCTION void update_point_pore_pressure_porosity(
    const Points& p, const int q, const TwoPhaseConstants& k, const double Lxx, const double Lxy,
    const double Lyx, const double Lyy, const double dt) {
  const double n = p.porosity(q), d = p.volumetric_rate(q);
  p.pore_pressure(q) -= k.liquid_bulk_modulus / n * d * dt;
  const double J = (1.0 + Lxx * dt) * (1.0 + Lyy * dt) - Lxy * Lyx * dt * dt;
  p.porosity(q) = 1.0 - (1.0 - n) / J;
}

// The viscous pressure of point q from D = volumetric_rate(q), its porosity and volume of the end
// of the step (the second part of update_point_pore_pressure, with the bulk viscosity on).
// Returns the work of the bulk viscosity, J/m.
template <class Points>
KOKKOS_FORCEINLINE_FUNCTION double update_point_viscous_pressure(const Points& p, const int q,
                                                                 const PreparedMaterial& m,
                                                                 const TwoPhaseConstants& k,
                                                                 const double dt) {
  const auto& s = p.solid;
  const double d = p.volumetric_rate(q), n1 = p.porosity(q);
  const double V = s.volume(q);
  const double dissipated = -p.viscous_pressure(q) * d * V * dt;
  const double M = m.lame_lambda + 2.0 * m.shear_modulus;
  const double c =
      saturated_wave_speed(M, m.material.density, n1, k.liquid_density, k.liquid_bulk_modulus);
  const double rho_m = (s.mass(q) + p.liquid_mass(q)) / V;
  p.viscous_pressure(q) = bulk_viscous_pressure(rho_m, c, k.cell_size, d, k.c1, k.c2);
  return dissipated;
}

// The pore pressure, porosity and viscous pressure of point q from D = volumetric_rate(q) (set by
// the caller) and the solid velocity gradient L of the step; V = volume(q) must already be the
// end-of-step volume (stress_update.hpp). Returns the work of the bulk viscosity, J/m (0 when it
// is off). Shared by pore_pressure_update() and the fused two-phase G2P (two_phase_g2p.hpp).
// `Points`: TwoPhaseParticles, or TwoPhasePointArrays on the host.
template <class Points>
KOKKOS_FORCEINLINE_FUNCTION double update_point_pore_pressure(
    const Points& p, const int q, const PreparedMaterial& m, const TwoPhaseConstants& k,
    const double Lxx, const double Lxy, const double Lyx, const double Lyy, const double dt) {
  update_point_pore_pressure_porosity(p, q, k, Lxx, Lxy, Lyx, Lyy, dt);
  if (!k.viscous()) return 0.0;
  return update_point_viscous_pressure(p, q, m, k, dt);
}

// Returns the dissipation of the step, J/m: the work of the bulk viscosity and the liquid energy
// released at free-surface points (0 with both off). g.dx() is the length l of the viscosity.
template <class ExecSpace, class MemorySpace>
double pore_pressure_update(const TwoPhaseParticles<MemorySpace>& p,
                            const TwoPhaseGrid<MemorySpace>& g, const Liquid& liquid, double dt,
                            const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials,
                            BulkViscosity viscosity = {}, double free_surface_fill = 0.0) {
  const auto s = p.solid;
  const double K_L = liquid.bulk_modulus, rho_L = liquid.density;
  const auto D = p.volumetric_rate;
  Kokkos::parallel_for(
      "lsi::mpm::two_phase::volumetric_rate", range_policy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q) {
        D(q) = mixture_volumetric_rate(p.porosity(q),
                                       s.velocity_gradient(q, 0, 0) + s.velocity_gradient(q, 1, 1),
                                       p.liquid_divergence(q));
      });
  const bool surface = free_surface_fill > 0.0;
  if (surface) nodal_volume<ExecSpace>(p, g);
  const auto vol = g.smooth_weight;
  const double ox = g.solid.origin[0], oy = g.solid.origin[1], inv_dx = 1.0 / g.solid.dx;
  const double inv_cell = inv_dx * inv_dx, fill_min = free_surface_fill;
  const int nx = g.solid.nx;
  TwoPhaseConstants k;
  k.liquid_density = rho_L;
  k.liquid_bulk_modulus = K_L;
  k.c1 = viscosity.linear;
  k.c2 = viscosity.quadratic;
  k.cell_size = g.dx();
  double dissipated = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::two_phase::pore_pressure_update", range_policy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& diss) {
        diss += update_point_pore_pressure(
            p, q, materials(s.material(q)), k, s.velocity_gradient(q, 0, 0),
            s.velocity_gradient(q, 0, 1), s.velocity_gradient(q, 1, 0),
            s.velocity_gradient(q, 1, 1), dt);
        const double n1 = p.porosity(q);
        if (surface) {
          // Fill of the point's neighbourhood: sum_i w_ip (sum_q w_iq V_q) / dx^2 (1 inside the
          // material; 0.62 for the top row of 2 x 2 points per cell under a flat surface, 0.85
          // for the second row). Below free_surface_fill the point is on the free surface:
          // drained, p = q = 0; the liquid energy it held is counted with the viscous work.
          const Stencil1D sx = quadratic_bspline(s.position(q, 0) - ox, inv_dx),
                          sy = quadratic_bspline(s.position(q, 1) - oy, inv_dx);
          double fill = 0.0;
          for (int b = 0; b < 3; ++b)
            for (int a = 0; a < 3; ++a)
              fill += sx.w[a] * sy.w[b] * vol(sx.base + a + nx * (sy.base + b));
          if (fill * inv_cell < fill_min) {
            const double pw = p.pore_pressure(q);
            diss += n1 * pw * pw * s.volume(q) / (2.0 * K_L);
            p.pore_pressure(q) = 0.0;
            p.viscous_pressure(q) = 0.0;
          }
        }
      },
      dissipated);
  return dissipated;
}

}  // namespace lsi::mpm::two_phase

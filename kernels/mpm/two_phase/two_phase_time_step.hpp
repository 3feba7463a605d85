// Two-phase time step (the paper's eq. 25 times the Courant number, recomputed every step from
// the points' current porosity):
//   dt = C min( dx / (c + |v|max),  dt_k )        (dt_k only with the explicit drag)
// Wave speed c (per point, the largest over the points). Eq. 25 prints the undrained mixture
// speed sqrt((E + K_L/n) / rho_m); we use the constrained modulus M = K + 4G/3 instead of E
// (plane strain, as the single-phase time step) and take the larger of
//   c_u  = sqrt((M + K_L/n) / rho_m)       undrained: both phases move together (low k)
//   c_f  = fastest wave of the uncoupled phases (k -> infinity, no drag): the largest root of
//          det(K - c^2 diag(m_S, m_L)) = 0 with, per unit volume, m_S = (1-n) rho_S,
//          m_L = n rho_L and the wave stiffness matrix (from sigma' = M eps_S and
//          p = -(K_L/n) ((1-n) eps_S + n eps_L))
//            K = [[M + (1-n)^2 K_L / n, (1-n) K_L], [(1-n) K_L, n K_L]].
// c_u is the Rayleigh quotient of K for the mode u_S = u_L, so c_f >= c_u always; c_f is the
// true CFL limit when the drag is weak (e.g. M = 1e7 Pa, K_L = 2.2e9 Pa, n = 0.4: c_u = 1664 m/s,
// c_f = 1857 m/s), c_u when it is strong. Taking c_f is safe in both.
// Permeability limit of the explicit drag (derived for the grid update of this code, see
// docs/theory/two_phase.md): the relative velocity w of a node obeys w' = -Q (1/m_L + 1/m_S) w, so
// forward Euler is stable for dt < 2 / (Q (1/m_L + 1/m_S)); per unit volume
// Q = n^2 rho_L g / k, hence
//   dt_k = 2 k (1 - n) rho_S / (n g rho_m),     rho_m = (1-n) rho_S + n rho_L.
// (The paper prints 2 (rho_m + (1/n - 2) rho_L) k / (rho_L g), after Mieremet et al. 2016, for
// another discretisation; for n = 0.4, rho_S = 2650 it is 25 % larger than the bound of ours.)
#pragma once
#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>

#include "kernels/common/execution_instance.hpp"
#include "kernels/common/math.hpp"
#include "kernels/mpm/constitutive/material.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"
#include "kernels/common/constants.hpp"

namespace lsi::mpm::two_phase {

// Squared wave speed of a saturated point (see above), m^2/s^2. M: constrained modulus of the
// skeleton. With the wave matrix per unit mass, A = diag(m_S, m_L)^-1 K,
//   a = A_SS = (M + (1-n)^2 K_L / n) / m_S,   d = A_LL = K_L / rho_L,
//   det A = det K / (m_S m_L) = M K_L / (m_S rho_L)     (the (1-n)^2 K_L^2 / n terms cancel)
// and c_f^2 = a/2 + d/2 + sqrt((a/2 + d/2)^2 - det A); three divisions (the time-step limits
// evaluate it for every point every step).
KOKKOS_FORCEINLINE_FUNCTION double saturated_wave_speed_squared(double M, double rho_S, double n,
                                                                double rho_L, double K_L) {
  const double inv_n = 1.0 / n, mS = (1.0 - n) * rho_S, inv_mS = 1.0 / mS;
  const double rho_m = mS + n * rho_L;
  const double cu2 = (M + K_L * inv_n) / rho_m;
  const double d = K_L / rho_L;
  const double a = (M + (1.0 - n) * (1.0 - n) * K_L * inv_n) * inv_mS;
  const double half_tr = 0.5 * (a + d), det = d * M * inv_mS;
  const double cf2 = half_tr + math::sqrt(math::max(half_tr * half_tr - det, 0.0));
  return math::max(cu2, cf2);
}

// Wave speed of a saturated point (see above), m/s.
KOKKOS_FORCEINLINE_FUNCTION double saturated_wave_speed(double M, double rho_S, double n,
                                                        double rho_L, double K_L) {
  return math::sqrt(saturated_wave_speed_squared(M, rho_S, n, rho_L, K_L));
}

// Permeability limit of the explicit drag (see above), s.
KOKKOS_INLINE_FUNCTION double permeability_time_step(double k, double rho_S, double n, double rho_L,
                                                     double g) {
  const double rho_m = (1.0 - n) * rho_S + n * rho_L;
  return 2.0 * k * (1.0 - n) * rho_S / (n * g * rho_m);
}

struct TimeStepLimits {
  double wave_speed = 0.0;         // m/s, largest over the points (0: none; with the bulk
                                   // viscosity's share, see below)
  double permeability_dt = 1e300;  // s, smallest over the points (explicit drag only)
};

// The constants of the per-point updates of a two-phase step (the time-step limits here, the pore
// pressure in pore_pressure_update.hpp): the liquid, the g of the conductivity, the bulk
// viscosity and its length l (the cell size).
struct TwoPhaseConstants {
  double liquid_density = 1000.0;       // rho_L, kg/m^3
  double liquid_bulk_modulus = 2.2e9;   // K_L, Pa
  double darcy_gravity = lsi::gravity;  // m/s^2
  double c1 = 0.0, c2 = 0.0;            // bulk viscosity (BulkViscosity), 0, 0: off
  double cell_size = 0.0;               // m
  KOKKOS_INLINE_FUNCTION bool viscous() const { return c1 > 0.0 || c2 > 0.0; }
};

// Point q's squared wave speed without the bulk viscosity's share, m^2/s^2, and its permeability
// step, s. Without branches, so that the host's loop over a block of points vectorises
// (two_phase_g2p.hpp).
template <class Points>
KOKKOS_FORCEINLINE_FUNCTION void point_wave_speed_and_permeability_step(const Points& p,
                                                                        const int q,
                                                                        const PreparedMaterial& m,
                                                                        const TwoPhaseConstants& k,
                                                                        double& cq2, double& tq) {
  const double M = m.lame_lambda + 2.0 * m.shear_modulus, rho_S = m.material.density;
  const double n = p.porosity(q);
  cq2 = saturated_wave_speed_squared(M, rho_S, n, k.liquid_density, k.liquid_bulk_modulus);
  tq = permeability_time_step(p.conductivity(q), rho_S, n, k.liquid_density, k.darcy_gravity);
}

// The squared wave speed cq2 of a point with the share of the artificial bulk viscosity
// (pore_pressure_update.hpp) at the volumetric rate D: as explicit impact codes, for a
// compressing point the speed c becomes sqrt(c^2 + Qv^2) + Qv with the viscous speed
// Qv = c1 c + c2 l |D| (von Neumann-Richtmyer / Landshoff).
KOKKOS_FORCEINLINE_FUNCTION double with_viscous_speed(const double cq2, const double D,
                                                      const TwoPhaseConstants& k) {
  if (!(D < 0.0 && k.viscous())) return cq2;
  const double cq = math::sqrt(cq2);
  const double Qv = k.c1 * cq - k.c2 * k.cell_size * D;
  const double cv = math::sqrt(cq2 + Qv * Qv) + Qv;
  return cv * cv;
}

// Point q's squared wave speed and permeability step, folded into the running max c2 (m^2/s^2:
// one square root for all the points, after the reduction) and min dtk.
template <class Points>
KOKKOS_FORCEINLINE_FUNCTION void point_time_step_limits(const Points& p, const int q,
                                                        const PreparedMaterial& m,
                                                        const TwoPhaseConstants& k, double& c2,
                                                        double& dtk) {
  double cq2, tq;
  point_wave_speed_and_permeability_step(p, q, m, k, cq2, tq);
  cq2 = with_viscous_speed(cq2, p.volumetric_rate(q), k);
  if (cq2 > c2) c2 = cq2;
  if (tq < dtk) dtk = tq;
}

template <class ExecSpace, class MemorySpace>
TimeStepLimits two_phase_time_step_limits(
    const TwoPhaseParticles<MemorySpace>& p,
    const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials, const Liquid& liquid,
    double darcy_gravity, double viscosity_linear = 0.0, double viscosity_quadratic = 0.0,
    double cell_size = 0.0) {
  const auto s = p.solid;
  const TwoPhaseConstants k{liquid.density,   liquid.bulk_modulus, darcy_gravity,
                            viscosity_linear, viscosity_quadratic, cell_size};
  TimeStepLimits lim;
  Kokkos::parallel_reduce(
      "lsi::mpm::two_phase::time_step_limits", range_policy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& c2, double& dtk) {
        point_time_step_limits(p, q, materials(s.material(q)), k, c2, dtk);
      },
      Kokkos::Max<double>(lim.wave_speed), Kokkos::Min<double>(lim.permeability_dt));
  lim.wave_speed = lim.wave_speed > 0.0 ? std::sqrt(lim.wave_speed) : 0.0;  // from c^2
  return lim;
}

inline double two_phase_time_step(double cell_size, const TimeStepLimits& lim, double max_speed,
                                  bool explicit_drag, double courant, double max_time_step) {
  double dt = cell_size / (lim.wave_speed + max_speed);
  if (explicit_drag) dt = std::min(dt, lim.permeability_dt);
  return std::min(courant * dt, max_time_step);
}

}  // namespace lsi::mpm::two_phase

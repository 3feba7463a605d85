// Pore pressure and porosity update (after G2P and the effective-stress update), per point:
//   dp = -(K_L / n) [ (1 - n) tr(eps_dot_S) + n div(v_L) ] dt     (p compression positive)
// the storage equation of a linearly compressible liquid in a skeleton of incompressible grains
// (liquid mass balance with the solid mass balance substituted), with tr(eps_dot_S) = L_xx + L_yy
// of the solid and div(v_L) of the liquid from the grid velocities of the step (USL).
// Porosity from the solid volumetric strain, the grains being incompressible: the solid volume
// (1 - n) V is constant, so with J = det(I + L_S dt) (the same J that scales V in
// stress_update.hpp)
//   n_new = 1 - (1 - n) / J.
// n of the START of the step is used in dp. Solid and liquid masses of the point are constant.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/mpm/two_phase/two_phase_particles.hpp"

namespace lsi::mpm::two_phase {

template <class ExecSpace, class MemorySpace>
void pore_pressure_update(const TwoPhaseParticles<MemorySpace>& p, double liquid_bulk_modulus,
                          double dt) {
  const auto s = p.solid;
  const double K_L = liquid_bulk_modulus;
  Kokkos::parallel_for(
      "lsi::mpm::two_phase::pore_pressure_update", Kokkos::RangePolicy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q) {
        const double Lxx = s.velocity_gradient(q, 0, 0), Lxy = s.velocity_gradient(q, 0, 1),
                     Lyx = s.velocity_gradient(q, 1, 0), Lyy = s.velocity_gradient(q, 1, 1);
        const double n = p.porosity(q);
        p.pore_pressure(q) -= K_L / n * ((1.0 - n) * (Lxx + Lyy) + n * p.liquid_divergence(q)) * dt;
        const double J = (1.0 + Lxx * dt) * (1.0 + Lyy * dt) - Lxy * Lyx * dt * dt;
        p.porosity(q) = 1.0 - (1.0 - n) / J;
      });
}

}  // namespace lsi::mpm::two_phase

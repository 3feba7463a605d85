// Two-phase energy accounting (J/m), point part: kinetic energy of each phase, elastic energy of
// the skeleton (effective stress), stored energy of the compressed pore liquid n p^2 V / (2 K_L)
// (p changes by -(K_L/n) d(eps) so the liquid stores p^2 / (2 K_L / n) per unit volume),
// gravitational potential -(m_S + m_L) g . x (points move with the solid), plastic work.
// The solver adds the accumulated wall and drag dissipation, the work of gravity on the seepage
// flow and the work of the surface loads (two_phase_grid_update.hpp, two_phase_g2p.hpp).
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/constitutive/linear_elastic.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"

namespace lsi::mpm::two_phase {

struct TwoPhaseEnergyReport {
  double time = 0.0;
  double kinetic_solid = 0.0, kinetic_liquid = 0.0, elastic = 0.0, liquid = 0.0, potential = 0.0;
  double plastic = 0.0, boundary = 0.0, drag = 0.0;
  double viscous = 0.0;  // accumulated work of the artificial bulk viscosity (>= 0)
  // minus the accumulated work of gravity on the relative flow and of the surface loads: they
  // enter the total like potential energies.
  double seepage_potential = 0.0, load_potential = 0.0;
  double kinetic() const { return kinetic_solid + kinetic_liquid; }
  double total() const {
    return kinetic() + elastic + liquid + potential + plastic + boundary + drag + viscous +
           seepage_potential + load_potential;
  }
};

template <class ExecSpace, class MemorySpace>
TwoPhaseEnergyReport two_phase_particle_energies(
    const TwoPhaseParticles<MemorySpace>& p,
    const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials, double liquid_bulk_modulus,
    const double gravity[2]) {
  TwoPhaseEnergyReport e;
  const auto s = p.solid;
  const double gx = gravity[0], gy = gravity[1], K_L = liquid_bulk_modulus;
  Kokkos::parallel_reduce(
      "lsi::mpm::two_phase::energy", range_policy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& ks, double& kl, double& el, double& li, double& pot,
                    double& pl) {
        const double mS = s.mass(q), mL = p.liquid_mass(q);
        ks +=
            0.5 * mS * (s.velocity(q, 0) * s.velocity(q, 0) + s.velocity(q, 1) * s.velocity(q, 1));
        kl += 0.5 * mL *
              (p.liquid_velocity(q, 0) * p.liquid_velocity(q, 0) +
               p.liquid_velocity(q, 1) * p.liquid_velocity(q, 1));
        const double st[4] = {s.stress(q, 0), s.stress(q, 1), s.stress(q, 2), s.stress(q, 3)};
        el += s.volume(q) * elastic_energy_density(materials(s.material(q)).material, st);
        const double pw = p.pore_pressure(q);
        li += p.porosity(q) * pw * pw * s.volume(q) / (2.0 * K_L);
        pot -= (mS + mL) * (gx * s.position(q, 0) + gy * s.position(q, 1));
        pl += s.plastic_work(q);
      },
      e.kinetic_solid, e.kinetic_liquid, e.elastic, e.liquid, e.potential, e.plastic);
  return e;
}

}  // namespace lsi::mpm::two_phase

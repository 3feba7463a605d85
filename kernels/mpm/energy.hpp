// Energy accounting (J/m): kinetic, elastic strain, gravitational potential (-m g.x), plastic
// dissipation (accumulated by the stress update); the boundary dissipation is accumulated by the
// grid update. Evaluated at output steps only.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/constitutive/linear_elastic.hpp"
#include "kernels/mpm/particles.hpp"

namespace lsi::mpm {

struct EnergyReport {
  double time = 0.0;
  double kinetic = 0.0, elastic = 0.0, potential = 0.0, plastic = 0.0, boundary = 0.0;
  // total = kinetic + elastic + potential + plastic + boundary: constant for an exact solver;
  // its change is the numerical dissipation (negative) or spurious energy (positive).
  double total() const { return kinetic + elastic + potential + plastic + boundary; }
};

template <class ExecSpace, class MemorySpace>
EnergyReport particle_energies(const Particles<MemorySpace>& p,
                               const Kokkos::View<const PreparedMaterial*, MemorySpace>& materials,
                               const double gravity[2]) {
  EnergyReport e;
  const double gx = gravity[0], gy = gravity[1];
  Kokkos::parallel_reduce(
      "lsi::mpm::energy", range_policy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& k, double& el, double& pot, double& pl) {
        const double m = p.mass(q);
        k += 0.5 * m * (p.velocity(q, 0) * p.velocity(q, 0) + p.velocity(q, 1) * p.velocity(q, 1));
        const double s[4] = {p.stress(q, 0), p.stress(q, 1), p.stress(q, 2), p.stress(q, 3)};
        el += p.volume(q) * elastic_energy_density(materials(p.material(q)).material, s);
        pot -= m * (gx * p.position(q, 0) + gy * p.position(q, 1));
        pl += p.plastic_work(q);
      },
      e.kinetic, e.elastic, e.potential, e.plastic);
  return e;
}

}  // namespace lsi::mpm

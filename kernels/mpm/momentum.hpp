// Total momentum of the material points (kg m/s per m): sum of m v over the points; a
// saturated run adds the pore liquid's m_L v_L with add_momentum.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/particles.hpp"

namespace lsi::mpm {

// sum m v of one phase: its masses and velocities (kg/m, m/s), added to out (kg m/s per m).
template <class ExecSpace, class Masses, class Velocities>
void add_momentum(const Masses& mass, const Velocities& velocity, double out[2]) {
  double px = 0.0, py = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::momentum", range_policy<ExecSpace>(0, mass.extent(0)),
      KOKKOS_LAMBDA(const int q, double& x, double& y) {
        x += mass(q) * velocity(q, 0);
        y += mass(q) * velocity(q, 1);
      },
      px, py);
  out[0] += px;
  out[1] += py;
}

template <class ExecSpace, class MemorySpace>
void momentum(const Particles<MemorySpace>& p, double out[2]) {
  out[0] = out[1] = 0.0;
  add_momentum<ExecSpace>(p.mass, p.velocity, out);
}

}  // namespace lsi::mpm

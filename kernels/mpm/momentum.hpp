// Total momentum of the material points (kg m/s per m): sum of m v over the points, and for the
// saturated points the pore liquid's m_L v_L as well (two_phase::momentum).
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/mpm/particles.hpp"

namespace lsi::mpm {

template <class ExecSpace, class MemorySpace>
void momentum(const Particles<MemorySpace>& p, double out[2]) {
  double px = 0.0, py = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::momentum", Kokkos::RangePolicy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& x, double& y) {
        x += p.mass(q) * p.velocity(q, 0);
        y += p.mass(q) * p.velocity(q, 1);
      },
      px, py);
  out[0] = px;
  out[1] = py;
}

}  // namespace lsi::mpm

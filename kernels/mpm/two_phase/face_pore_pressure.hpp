// The largest pore pressure on the barrier's upstream face: over the material points in front of
// the face within `band` (m) of it, between the base and the crest. Pa, compression positive;
// 0 when no point is there.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/mpm/barrier_shape.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"

namespace lsi::mpm::two_phase {

template <class ExecSpace, class MemorySpace>
double face_pore_pressure(const TwoPhaseParticles<MemorySpace>& p, const BarrierShape& shape,
                          double displacement, double band) {
  const BarrierFace f = shape.face[BarrierShape::Upstream];
  const double y0 = shape.toe[1], y1 = shape.toe[1] + shape.height;
  const auto x = p.solid.position;
  const auto pp = p.pore_pressure;
  double pmax = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::two_phase::face_pore_pressure", Kokkos::RangePolicy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& m) {
        const double px = x(q, 0) - displacement, py = x(q, 1);
        if (py < y0 || py > y1) return;
        const double d = (px - f.point[0]) * f.normal[0] + (py - f.point[1]) * f.normal[1];
        if (d >= 0.0 && d <= band && pp(q) > m) m = pp(q);
      },
      Kokkos::Max<double>(pmax));
  return pmax;
}

}  // namespace lsi::mpm::two_phase

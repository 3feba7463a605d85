// The largest pore pressure on the barrier's upstream face: over the material points in front of
// the face within `band` (m) of it, between the base and the crest, of the per-point field
// `pressure` (the reported, cell-averaged field: cell_mean_pore_pressure, or the points' own).
// Pa, compression positive; 0 when no point is there.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/barrier_shape.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"

namespace lsi::mpm::two_phase {

template <class ExecSpace, class MemorySpace>
double face_pore_pressure(const TwoPhaseParticles<MemorySpace>& p,
                          const Kokkos::View<const double*, MemorySpace>& pressure,
                          const BarrierShape& shape, double displacement, double band) {
  const BarrierFace f = shape.face[BarrierShape::Upstream];
  const double y0 = shape.toe[1], y1 = shape.toe[1] + shape.height;
  const auto x = p.solid.position;
  double pmax = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::two_phase::face_pore_pressure", range_policy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& m) {
        const double px = x(q, 0) - displacement, py = x(q, 1);
        if (py < y0 || py > y1) return;
        const double d = (px - f.point[0]) * f.normal[0] + (py - f.point[1]) * f.normal[1];
        if (d >= 0.0 && d <= band && pressure(q) > m) m = pressure(q);
      },
      Kokkos::Max<double>(pmax));
  return pmax;
}

}  // namespace lsi::mpm::two_phase

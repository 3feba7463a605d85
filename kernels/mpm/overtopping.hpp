// Volume of material that has overtopped the barrier: material points downstream of the
// upstream crest corner x_c (they have passed over the face), and the total volume; m^2 (per m),
// counted with the points' INITIAL volumes (the landslide as placed: a spreading flow's current
// volume also counts the gaps that open between separating points, +17 % in a test scene).
// Also the volume of the points whose centre lies inside the barrier: the grid contact stops
// nodes, and a point straddling a face moves with a mean of stopped and free nodes, so points
// creep in (docs/mpm.md, "Known limitations"); this measures how much.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/mpm/barrier_shape.hpp"
#include "kernels/mpm/particles.hpp"

namespace lsi::mpm {

struct OvertoppingReport {
  double overtopped = 0.0;   // m^2
  double total = 0.0;        // m^2
};

template <class ExecSpace, class MemorySpace>
OvertoppingReport overtopping(const Particles<MemorySpace>& p, double crest_x) {
  OvertoppingReport r;
  Kokkos::parallel_reduce(
      "lsi::mpm::overtopping", Kokkos::RangePolicy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& over, double& all) {
        const double v = p.volume0(q);
        all += v;
        if (p.position(q, 0) > crest_x) over += v;
      },
      r.overtopped, r.total);
  return r;
}

// Initial volume (m^2 per m) of the points whose centre lies inside the barrier (shape displaced
// by `displacement`, m, above its base).
template <class ExecSpace, class MemorySpace>
double barrier_interior_volume(const Particles<MemorySpace>& p, const BarrierShape& shape,
                               const double displacement) {
  const double base_y = shape.toe[1];
  double inside = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::barrier_interior_volume", Kokkos::RangePolicy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& v) {
        const double y = p.position(q, 1);
        int k = 0;
        if (y > base_y && shape.outside_distance(p.position(q, 0) - displacement, y, k) < 0.0)
          v += p.volume0(q);
      },
      inside);
  return inside;
}

}  // namespace lsi::mpm

// Volume of material that has overtopped the barrier: material points downstream of the
// upstream crest corner x_c (they have passed over the face), and the total volume; m^2 (per m),
// counted with the points' INITIAL volumes (the landslide as placed: a spreading flow's current
// volume also counts the gaps that open between separating points, +17 % in a test scene).
// Also the volume of the points whose centre lies inside the barrier: the grid contact stops
// nodes, and a point straddling a face moves with a mean of stopped and free nodes, so points
// creep in (docs/theory/mpm.md, "Known limitations"); this measures how much.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/barrier_shape.hpp"
#include "kernels/mpm/particles.hpp"

namespace lsi::mpm {

struct OvertoppingReport {
  double overtopped = 0.0;  // m^2
  double total = 0.0;       // m^2
};

template <class ExecSpace, class MemorySpace>
OvertoppingReport overtopping(const Particles<MemorySpace>& p, double crest_x) {
  OvertoppingReport r;
  Kokkos::parallel_reduce(
      "lsi::mpm::overtopping", range_policy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& over, double& all) {
        const double v = p.volume0(q);
        all += v;
        if (p.position(q, 0) > crest_x) over += v;
      },
      r.overtopped, r.total);
  return r;
}

struct BarrierInterior {
  double inside = 0.0;      // m^2: every point whose centre lies inside the barrier
  double past_crest = 0.0;  // m^2: those of them downstream of the upstream crest corner, which
                            // `overtopping` counts as overtopped
};

// Initial volume (m^2 per m) of the points whose centre lies inside the barrier (shape displaced
// by `displacement`, m, above its base), and the part of it downstream of the upstream crest
// corner: the leaked points that `overtopping` counts, so that the overtopped volume lies between
// overtopped - past_crest and overtopped whichever way the leak is read.
template <class ExecSpace, class MemorySpace>
BarrierInterior barrier_interior(const Particles<MemorySpace>& p, const BarrierShape& shape,
                                 const double displacement) {
  const double base_y = shape.toe[1];
  const double crest_x = shape.crest_upstream_x() + displacement;
  BarrierInterior r;
  Kokkos::parallel_reduce(
      "lsi::mpm::barrier_interior_volume", range_policy<ExecSpace>(0, p.count),
      KOKKOS_LAMBDA(const int q, double& in, double& past) {
        const double x = p.position(q, 0), y = p.position(q, 1);
        int k = 0;
        if (y > base_y && shape.outside_distance(x - displacement, y, k) < 0.0) {
          in += p.volume0(q);
          if (x > crest_x) past += p.volume0(q);
        }
      },
      r.inside, r.past_crest);
  return r;
}

}  // namespace lsi::mpm

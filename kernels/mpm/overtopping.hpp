// Volume of material that has overtopped the barrier: material points downstream of the
// upstream crest corner x_c (they have passed over the face), and the total volume; m^2 (per m),
// counted with the points' INITIAL volumes (the landslide as placed: a spreading flow's current
// volume also counts the gaps that open between separating points, +17 % in a test scene).
#pragma once
#include <Kokkos_Core.hpp>

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

}  // namespace lsi::mpm

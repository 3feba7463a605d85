// Sharing a boundary node's force among bands along a wall or a face. A node carries the
// boundary over its tributary length [s - dx/2, s + dx/2] (s: its coordinate along the boundary
// from where band 0 begins); its force goes to the bands in proportion to their overlap with
// that length (the first band reaching down, the last band up, without end), so that a band
// gets the share of its length whatever the grid's alignment with the band edges, and the
// bands' forces add up to the boundary's force.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/math.hpp"

namespace lsi::mpm {

// Calls add(k, share) for each band k that [s - dx/2, s + dx/2] overlaps, with the share of
// `force` that falls in it; `bands` bands of length `band` from s = 0.
template <class Add>
KOKKOS_INLINE_FUNCTION void share_among_bands(int bands, double band, double s, double dx,
                                              double force, const Add& add) {
  const double lo = s - 0.5 * dx, hi = s + 0.5 * dx;
  int k0 = static_cast<int>(math::floor(lo / band));
  int k1 = static_cast<int>(math::floor(hi / band));
  k0 = k0 < 0 ? 0 : k0 < bands ? k0 : bands - 1;
  k1 = k1 < 0 ? 0 : k1 < bands ? k1 : bands - 1;
  for (int k = k0; k <= k1; ++k) {
    const double b0 = k == 0 ? lo : k * band;
    const double b1 = k == bands - 1 ? hi : (k + 1) * band;
    const double overlap = (hi < b1 ? hi : b1) - (lo > b0 ? lo : b0);
    if (overlap > 0.0) add(k, force * overlap / dx);
  }
}

}  // namespace lsi::mpm

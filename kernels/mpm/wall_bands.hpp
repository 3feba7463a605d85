// The walls' load in bands along each wall: the normal impulse the material gives each band of a
// wall, accumulated on the device step after step until the caller takes it (the mean normal
// stress over an output interval is the impulse over the interval and the band's length). A
// node on a wall carries the wall over its tributary length dx (height_bands.hpp), so the bands
// of a wall add up to the wall's normal reaction. Side walls are banded upwards from the bottom
// wall (or the grid's bottom edge), the bottom and top walls rightwards from the left wall (or
// the grid's left edge); each wall's last band ends at the facing wall (or the grid's edge).
#pragma once
#include <Kokkos_Core.hpp>
#include <array>
#include <cmath>
#include <vector>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/boundary.hpp"
#include "kernels/mpm/height_bands.hpp"

namespace lsi::mpm {

enum WallSide { LeftWall = 0, RightWall = 1, BottomWall = 2, TopWall = 3 };

template <class MemorySpace>
struct WallBands {
  Kokkos::View<double**, MemorySpace> impulse;  // (4, bands): normal impulse per band, N s/m
  double band = 0.0;                            // band length along the wall, m; 0: no bands
  double start[4] = {0.0, 0.0, 0.0, 0.0};       // where band 0 begins along each wall, m
  double end[4] = {0.0, 0.0, 0.0, 0.0};         // where the last band ends, m
  int count[4] = {0, 0, 0, 0};                  // bands per wall (0: the wall is not active)

  bool active() const { return band > 0.0; }

  // Books the impulse (Ix, Iy) that the node at (x, y) gave the walls it touches this step
  // (N s/m, on the walls): the normal component to the touched walls' bands.
  KOKKOS_INLINE_FUNCTION void add(const Boundaries& w, double x, double y, double tol, double dx,
                                  double Ix, double Iy) const {
    auto book = [&](int side, double s, double normal_impulse) {
      const int n = count[side];
      if (n == 0) return;
      share_among_bands(n, band, s - start[side], dx, normal_impulse,
                        [&](int k, double f) { Kokkos::atomic_add(&impulse(side, k), f); });
    };
    if (w.left.active && x <= w.left.position + tol) book(LeftWall, y, -Ix);
    if (w.right.active && x >= w.right.position - tol) book(RightWall, y, Ix);
    if (w.bottom.active && y <= w.bottom.position + tol) book(BottomWall, x, -Iy);
    if (w.top.active && y >= w.top.position - tol) book(TopWall, x, Iy);
  }
};

// Bands of length `band` (m) along the active walls of a grid spanning [lower, upper].
template <class MemorySpace>
WallBands<MemorySpace> make_wall_bands(const Boundaries& w, const double lower[2],
                                       const double upper[2], double band) {
  WallBands<MemorySpace> b;
  if (!(band > 0.0)) return b;
  b.band = band;
  const double y0 = w.bottom.active ? w.bottom.position : lower[1];
  const double y1 = w.top.active ? w.top.position : upper[1];
  const double x0 = w.left.active ? w.left.position : lower[0];
  const double x1 = w.right.active ? w.right.position : upper[0];
  const Wall* walls[4] = {&w.left, &w.right, &w.bottom, &w.top};
  int most = 1;
  for (int side = 0; side < 4; ++side) {
    const bool vertical = side < 2;
    b.start[side] = vertical ? y0 : x0;
    b.end[side] = vertical ? y1 : x1;
    const double length = b.end[side] - b.start[side];
    b.count[side] =
        walls[side]->active && length > 0.0 ? static_cast<int>(std::ceil(length / band - 1e-9)) : 0;
    most = std::max(most, b.count[side]);
  }
  b.impulse = Kokkos::View<double**, MemorySpace>("wall_band_impulse", 4, most);
  return b;
}

// Takes the impulse booked since the last call, per wall and band (N s/m), and resets it.
template <class MemorySpace>
std::array<std::vector<double>, 4> take_wall_band_impulse(const WallBands<MemorySpace>& b) {
  std::array<std::vector<double>, 4> taken;
  if (!b.active()) return taken;
  using Exec = typename MemorySpace::execution_space;
  auto host =
      Kokkos::create_mirror_view(Kokkos::HostSpace(), b.impulse, Kokkos::WithoutInitializing);
  copy_and_wait<Exec>(host, b.impulse);
  for (int side = 0; side < 4; ++side)
    for (int k = 0; k < b.count[side]; ++k) taken[side].push_back(host(side, k));
  fill<Exec>(b.impulse, 0.0);
  return taken;
}

}  // namespace lsi::mpm

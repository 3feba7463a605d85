// The walls' load in bands along each wall: the normal impulse the material gives each band of a
// wall, accumulated on the device step after step until the caller takes it (the mean normal
// stress over an output interval is the impulse over the interval and the band's length). A
// node on a wall carries the wall over its tributary length dx (height_bands.hpp), so the bands
// of a wall add up to the wall's normal reaction. Side walls are banded upwards from the bottom
// wall (or the grid's bottom edge), the bottom and top walls rightwards from the left wall (or
// the grid's left edge); each wall's last band ends at the facing wall (or the grid's edge).
// The grid update adds each wall node's impulse into its line of nodes along the wall (a side
// wall's node rows, a bottom or top wall's node columns); the lines are shared among the bands
// when the caller takes them, line by line in one order. On the host a node row is one thread's
// in the grid update (NodeItems), so a side wall's line is added to by one thread; a bottom or
// top wall's column has nodes on several rows beyond the wall (the stencils reach two rows past
// the material), so each of four consecutive rows adds into a line of its own (row j into slot
// j mod 4), summed in order when taken: the bands are the same from run to run whatever the
// threads. The sharing is linear in the impulse, so sharing the sum over the steps is sharing
// each step's.
#pragma once
#include <Kokkos_Core.hpp>
#include <algorithm>
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
  // (4 walls, kSlots, lines): normal impulse per line of nodes along each wall since the last
  // take, N s/m; a bottom or top wall's node row j adds into slot j mod kSlots, a side wall's
  // nodes into slot 0.
  static constexpr int kSlots = 4;
  Kokkos::View<double***, MemorySpace> line_impulse;
  double band = 0.0;                       // band length along the wall, m; 0: no bands
  double start[4] = {0.0, 0.0, 0.0, 0.0};  // where band 0 begins along each wall, m
  double end[4] = {0.0, 0.0, 0.0, 0.0};    // where the last band ends, m
  int count[4] = {0, 0, 0, 0};             // bands per wall (0: the wall is not active)
  double origin[2] = {0.0, 0.0};           // the grid's first node, m
  double dx = 0.0;                         // the grid's node spacing, m

  bool active() const { return band > 0.0; }

  // Books the impulse (Ix, Iy) that node (i, j) at (x, y) gave the walls it touches this step
  // (N s/m, on the walls): the normal component to the touched walls' lines.
  KOKKOS_INLINE_FUNCTION void add(const Boundaries& w, int i, int j, double x, double y, double tol,
                                  double Ix, double Iy) const {
    auto book = [&](int side, int slot, int line, double normal_impulse) {
      if (count[side] > 0) Kokkos::atomic_add(&line_impulse(side, slot, line), normal_impulse);
    };
    if (w.left.active && x <= w.left.position + tol) book(LeftWall, 0, j, -Ix);
    if (w.right.active && x >= w.right.position - tol) book(RightWall, 0, j, Ix);
    if (w.bottom.active && y <= w.bottom.position + tol) book(BottomWall, j % kSlots, i, -Iy);
    if (w.top.active && y >= w.top.position - tol) book(TopWall, j % kSlots, i, Iy);
  }
};

// Bands of length `band` (m) along the active walls of grid g (its nodes' origin, spacing and
// counts; the walls within its extent).
template <class MemorySpace, class GridT>
WallBands<MemorySpace> make_wall_bands(const Boundaries& w, const GridT& g, double band) {
  WallBands<MemorySpace> b;
  if (!(band > 0.0)) return b;
  const double lower[2] = {g.origin[0], g.origin[1]};
  const double upper[2] = {g.upper(0), g.upper(1)};
  b.band = band;
  b.origin[0] = lower[0];
  b.origin[1] = lower[1];
  b.dx = g.dx;
  const double y0 = w.bottom.active ? w.bottom.position : lower[1];
  const double y1 = w.top.active ? w.top.position : upper[1];
  const double x0 = w.left.active ? w.left.position : lower[0];
  const double x1 = w.right.active ? w.right.position : upper[0];
  const Wall* walls[4] = {&w.left, &w.right, &w.bottom, &w.top};
  for (int side = 0; side < 4; ++side) {
    const bool vertical = side < 2;
    b.start[side] = vertical ? y0 : x0;
    b.end[side] = vertical ? y1 : x1;
    const double length = b.end[side] - b.start[side];
    b.count[side] =
        walls[side]->active && length > 0.0 ? static_cast<int>(std::ceil(length / band - 1e-9)) : 0;
  }
  b.line_impulse = Kokkos::View<double***, MemorySpace>(
      "wall_line_impulse", 4, WallBands<MemorySpace>::kSlots, std::max(g.nx, g.ny));
  return b;
}

// Takes the impulse booked since the last call, per wall and band (N s/m), and resets it: each
// line's impulse shared among the bands its tributary length overlaps, the lines in order.
template <class MemorySpace>
std::array<std::vector<double>, 4> take_wall_band_impulse(const WallBands<MemorySpace>& b) {
  std::array<std::vector<double>, 4> taken;
  if (!b.active()) return taken;
  using Exec = typename MemorySpace::execution_space;
  auto host =
      Kokkos::create_mirror_view(Kokkos::HostSpace(), b.line_impulse, Kokkos::WithoutInitializing);
  copy_and_wait<Exec>(host, b.line_impulse);
  for (int side = 0; side < 4; ++side) {
    taken[side].assign(static_cast<std::size_t>(b.count[side]), 0.0);
    if (b.count[side] == 0) continue;
    const double first = side < 2 ? b.origin[1] : b.origin[0];  // the lines' first node
    for (std::size_t line = 0; line < host.extent(2); ++line) {
      double impulse = 0.0;
      for (std::size_t slot = 0; slot < host.extent(1); ++slot) impulse += host(side, slot, line);
      if (impulse == 0.0) continue;
      const double s = first + static_cast<double>(line) * b.dx;
      share_among_bands(b.count[side], b.band, s - b.start[side], b.dx, impulse,
                        [&](int k, double share) { taken[side][k] += share; });
    }
  }
  fill<Exec>(b.line_impulse, 0.0);
  return taken;
}

}  // namespace lsi::mpm

// The regular background grid: nodes (i, j) at origin + (i, j) dx, flattened as i + nx j.
// Nodal fields live in flat Views; they are reset every step.
#pragma once
#include <Kokkos_Core.hpp>

namespace lsi::mpm {

// A rectangle of nodes, i0..i1 x j0..j1 inclusive (empty when i1 < i0 or j1 < j0).
struct NodeBox {
  int i0 = 0, i1 = -1, j0 = 0, j1 = -1;
  bool empty() const { return i1 < i0 || j1 < j0; }
  NodeBox merged(const NodeBox& o) const {
    if (empty()) return o;
    if (o.empty()) return *this;
    return {i0 < o.i0 ? i0 : o.i0, i1 > o.i1 ? i1 : o.i1, j0 < o.j0 ? j0 : o.j0,
            j1 > o.j1 ? j1 : o.j1};
  }
};

// How a pass over the nodes of a NodeBox is cut into parallel work items. Host threads take whole
// rows: contiguous nodes, few threads. A device takes one node per work item: one thread per
// row would leave a GPU nearly idle (a few thousand threads) and uncoalesced; the grid update of
// 8 M nodes took 3.2 ms that way on an H100 (docs/guide/cuda.md).
template <bool WholeRows>
struct NodeItemsOf {
  static constexpr bool whole_rows = WholeRows;
  int i0, j0, cols, rows;
  explicit NodeItemsOf(const NodeBox& b)
      : i0(b.i0), j0(b.j0), cols(b.i1 - b.i0 + 1), rows(b.j1 - b.j0 + 1) {}
  int count() const { return whole_rows ? rows : rows * cols; }
  // Work item t covers the nodes i_begin..i_end (inclusive) of row j.
  KOKKOS_INLINE_FUNCTION void nodes(const int t, int& j, int& i_begin, int& i_end) const {
    if constexpr (whole_rows) {
      j = j0 + t;
      i_begin = i0;
      i_end = i0 + cols - 1;
    } else {
      j = j0 + t / cols;
      i_begin = i_end = i0 + t % cols;
    }
  }
};
template <class ExecSpace>
using NodeItems = NodeItemsOf<
    Kokkos::SpaceAccessibility<Kokkos::HostSpace, typename ExecSpace::memory_space>::accessible>;

template <class MemorySpace>
struct Grid {
  double origin[2] = {0.0, 0.0};
  double dx = 1.0;
  int nx = 0, ny = 0;                                   // nodes per direction
  Kokkos::View<double*, MemorySpace> mass;              // kg/m
  Kokkos::View<double* [2], MemorySpace> momentum;      // kg/s per m (mass x velocity)
  Kokkos::View<double* [2], MemorySpace> force;         // N/m
  Kokkos::View<double* [2], MemorySpace> velocity;      // m/s, after the update
  Kokkos::View<double* [2], MemorySpace> velocity_old;  // m/s, before the update (FLIP)
  // Bookkeeping that lets the kernels skip the empty part of the grid (host memory, shared by
  // the copies of this Grid): [0..3] the nodes that may hold mass (P2G sets it), [4..7] the nodes
  // whose fields may be nonzero (P2G widens it, the grid update shrinks it back to [0..3]).
  // Outside [4..7] every field is zero. Both are the whole grid until the first P2G; code that
  // writes the nodal fields by other means must call mark_all_active().
  Kokkos::View<int[8], Kokkos::HostSpace> active;

  Grid() = default;
  Grid(const double lower[2], const double upper[2], double cell_size) : dx(cell_size) {
    origin[0] = lower[0];
    origin[1] = lower[1];
    nx = static_cast<int>((upper[0] - lower[0]) / dx + 0.5) + 1;
    ny = static_cast<int>((upper[1] - lower[1]) / dx + 0.5) + 1;
    const int n = nx * ny;
    mass = decltype(mass)("grid_mass", n);
    momentum = decltype(momentum)("grid_momentum", n);
    force = decltype(force)("grid_force", n);
    velocity = decltype(velocity)("grid_velocity", n);
    velocity_old = decltype(velocity_old)("grid_velocity_old", n);
    active = decltype(active)("grid_active");
    mark_all_active();
  }
  int size() const { return nx * ny; }
  double upper(int d) const { return origin[d] + (d == 0 ? nx - 1 : ny - 1) * dx; }

  NodeBox whole() const { return {0, nx - 1, 0, ny - 1}; }
  NodeBox mass_box() const { return get(0); }
  NodeBox dirty_box() const { return get(4); }
  void set_mass_box(const NodeBox& b) const { put(0, b); }
  void set_dirty_box(const NodeBox& b) const { put(4, b); }
  void mark_all_active() const {
    put(0, whole());
    put(4, whole());
  }

 private:
  NodeBox get(int k) const {
    if (active.data() == nullptr) return whole();
    return {active(k), active(k + 1), active(k + 2), active(k + 3)};
  }
  void put(int k, const NodeBox& b) const {
    if (active.data() == nullptr) return;
    active(k) = b.i0;
    active(k + 1) = b.i1;
    active(k + 2) = b.j0;
    active(k + 3) = b.j1;
  }
};

}  // namespace lsi::mpm

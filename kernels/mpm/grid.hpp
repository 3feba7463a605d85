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
// With whole rows, `spans` (host memory; nullptr: none) narrows row j to the nodes
// spans[2 j] .. spans[2 j + 1] (Grid's row spans; an empty row when the first exceeds the
// second): a flow that spreads thin over a long box (an overtopping jet, a deposit on both sides
// of a barrier) leaves most of its box's nodes empty.
template <bool WholeRows>
struct NodeItemsOf {
  static constexpr bool whole_rows = WholeRows;
  int i0, j0, cols, rows;
  const int* spans = nullptr;
  explicit NodeItemsOf(const NodeBox& b, const int* row_spans = nullptr)
      : i0(b.i0), j0(b.j0), cols(b.i1 - b.i0 + 1), rows(b.j1 - b.j0 + 1) {
    if constexpr (WholeRows) spans = row_spans;
  }
  int count() const { return whole_rows ? rows : rows * cols; }
  // Work item t covers the nodes i_begin..i_end (inclusive) of row j.
  KOKKOS_INLINE_FUNCTION void nodes(const int t, int& j, int& i_begin, int& i_end) const {
    if constexpr (whole_rows) {
      j = j0 + t;
      i_begin = i0;
      i_end = i0 + cols - 1;
      if (spans != nullptr) {
        i_begin = spans[2 * j] > i_begin ? spans[2 * j] : i_begin;
        i_end = spans[2 * j + 1] < i_end ? spans[2 * j + 1] : i_end;
      }
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
  // writes the nodal fields by other means must call mark_all_active(). [8], [9]: whether
  // `row_spans` refines the first and the second rectangle row by row (the host's P2G sets
  // them; a rectangle set alone drops its spans).
  Kokkos::View<int[10], Kokkos::HostSpace> active;
  // Per row j of each rectangle above, a span of nodes that holds every node of that row the
  // rectangle stands for: row_spans(0, 2 j) .. row_spans(0, 2 j + 1) of the first,
  // row_spans(1, ...) of the second (an empty row when the first exceeds the second). Set for
  // the rectangles' rows only; a span may reach past the rectangle's columns (the passes over
  // the nodes keep to both, NodeItemsOf).
  Kokkos::View<int**, Kokkos::LayoutRight, Kokkos::HostSpace> row_spans;

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
    row_spans = decltype(row_spans)("grid_row_spans", 2, 2 * static_cast<size_t>(ny));
    mark_all_active();
  }
  int size() const { return nx * ny; }
  double upper(int d) const { return origin[d] + (d == 0 ? nx - 1 : ny - 1) * dx; }

  NodeBox whole() const { return {0, nx - 1, 0, ny - 1}; }
  NodeBox mass_box() const { return get(0); }
  NodeBox dirty_box() const { return get(4); }
  void set_mass_box(const NodeBox& b) const { put(0, b, nullptr); }
  void set_dirty_box(const NodeBox& b) const { put(4, b, nullptr); }
  // The rectangles with their row spans (`spans`: two per row j, at 2 j; rows of b only).
  void set_mass_box(const NodeBox& b, const int* spans) const { put(0, b, spans); }
  void set_dirty_box(const NodeBox& b, const int* spans) const { put(4, b, spans); }
  // The row spans of the rectangles (indexed by the row: 2 j, 2 j + 1), nullptr without.
  const int* mass_rows() const { return rows(0); }
  const int* dirty_rows() const { return rows(4); }
  // After a grid update: nothing but the mass rectangle (and its row spans) may be nonzero.
  void set_dirty_to_mass() const { put(4, mass_box(), mass_rows()); }
  void mark_all_active() const {
    put(0, whole(), nullptr);
    put(4, whole(), nullptr);
  }

 private:
  NodeBox get(int k) const {
    if (active.data() == nullptr) return whole();
    return {active(k), active(k + 1), active(k + 2), active(k + 3)};
  }
  const int* rows(int k) const {
    if (active.data() == nullptr || active(8 + k / 4) == 0) return nullptr;
    return &row_spans(k / 4, 0);
  }
  void put(int k, const NodeBox& b, const int* spans) const {
    if (active.data() == nullptr) return;
    active(k) = b.i0;
    active(k + 1) = b.i1;
    active(k + 2) = b.j0;
    active(k + 3) = b.j1;
    active(8 + k / 4) = spans != nullptr ? 1 : 0;
    int* own = &row_spans(k / 4, 0);
    const int first = b.j0 > 0 ? b.j0 : 0, last = b.j1 < ny - 1 ? b.j1 : ny - 1;
    if (spans != nullptr && spans != own)
      for (int j = first; j <= last; ++j) {
        own[2 * j] = spans[2 * j];
        own[2 * j + 1] = spans[2 * j + 1];
      }
  }
};

}  // namespace lsi::mpm

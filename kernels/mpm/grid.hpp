// The regular background grid: nodes (i, j) at origin + (i, j) dx, flattened as i + nx j.
// Nodal fields live in flat Views; they are reset every step.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/execution_instance.hpp"

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
// On `threads` > 1 host threads with more rows than threads, a work item is a run of consecutive
// rows, one run per thread, cut where the runs hold equal numbers of nodes: a flow's rows differ
// in length (a wedge against the barrier, a thin jet above it), so a thread per equal number of
// rows would leave one thread with most of the nodes. Either way a row is one thread's, its nodes
// visited in order, and the cutting depends on the box, the spans and the threads alone: the
// same sums from run to run.
template <bool WholeRows>
struct NodeItemsOf {
  static constexpr bool whole_rows = WholeRows;
  static constexpr int kMaxRuns = 64;  // more threads than this: one row per work item
  int i0, j0, cols, rows;
  const int* spans = nullptr;
  int runs = 0;  // 0: one row per work item; else the runs of rows
  // Run r: rows j0 + first[r] .. j0 + first[r + 1] - 1 (host, with runs).
  int first[WholeRows ? kMaxRuns + 1 : 1] = {};
  explicit NodeItemsOf(const NodeBox& b, const int* row_spans = nullptr, const int threads = 1)
      : i0(b.i0), j0(b.j0), cols(b.i1 - b.i0 + 1), rows(b.j1 - b.j0 + 1) {
    if constexpr (WholeRows) {
      spans = row_spans;
      if (threads > 1 && threads <= kMaxRuns && rows > threads && !b.empty()) cut_runs(threads);
    }
  }
  int count() const { return whole_rows ? (runs > 0 ? runs : rows) : rows * cols; }
  // Row j's nodes i_begin..i_end (inclusive; none when i_end < i_begin), whole rows only.
  KOKKOS_INLINE_FUNCTION void row(const int j, int& i_begin, int& i_end) const {
    i_begin = i0;
    i_end = i0 + cols - 1;
    if (spans != nullptr) {
      i_begin = spans[2 * j] > i_begin ? spans[2 * j] : i_begin;
      i_end = spans[2 * j + 1] < i_end ? spans[2 * j + 1] : i_end;
    }
  }
  // Calls f(j, i_begin, i_end) for each row of work item t, lowest first (host), or for its one
  // node (device, i_begin == i_end).
  template <class F>
  KOKKOS_INLINE_FUNCTION void visit(const int t, const F& f) const {
    if constexpr (whole_rows) {
      const int r0 = runs > 0 ? first[t] : t, r1 = runs > 0 ? first[t + 1] : t + 1;
      for (int r = r0; r < r1; ++r) {
        int i_begin, i_end;
        row(j0 + r, i_begin, i_end);
        f(j0 + r, i_begin, i_end);
      }
    } else {
      f(j0 + t / cols, i0 + t % cols, i0 + t % cols);
    }
  }

 private:
  // Runs of consecutive rows, `threads` of them, each ending at the first row where the nodes
  // so far reach its share of the box's nodes.
  void cut_runs(const int threads) {
    long total = 0;
    for (int r = 0; r < rows; ++r) total += row_nodes(r);
    runs = threads;
    first[0] = 0;
    long sum = 0;
    int r = 0;
    for (int k = 1; k < threads; ++k) {
      const long share = total * k / threads;
      while (r < rows && sum < share) sum += row_nodes(r++);
      first[k] = r;
    }
    first[threads] = rows;
  }
  long row_nodes(const int r) const {
    int i_begin, i_end;
    row(j0 + r, i_begin, i_end);
    return i_end >= i_begin ? i_end - i_begin + 1 : 0;
  }
};

// The work items of a pass over a NodeBox on the calling thread's instance of ExecSpace.
template <class ExecSpace>
struct NodeItems
    : NodeItemsOf<Kokkos::SpaceAccessibility<Kokkos::HostSpace,
                                             typename ExecSpace::memory_space>::accessible> {
  using Base = NodeItemsOf<
      Kokkos::SpaceAccessibility<Kokkos::HostSpace, typename ExecSpace::memory_space>::accessible>;
  explicit NodeItems(const NodeBox& b, const int* row_spans = nullptr)
      : Base(b, row_spans, instance_concurrency<ExecSpace>()) {}
};

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

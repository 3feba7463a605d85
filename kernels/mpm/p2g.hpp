// Particle to grid: mass, APIC momentum m (v_p + C_p (x_i - x_p)), and force
// -V_p sigma_p grad(w_ip) + w_ip m_p g.
//
// Without data races, in two passes over memory (two parallel regions):
//  1. scatter: the points add their 3 x 3 node contributions into a node-interleaved buffer
//     (mass, momentum x, y, force x, y: 40 contiguous bytes per node instead of three arrays).
//     Duplicated (the default on host spaces): one buffer per thread; the points are cut into as
//     many contiguous chunks as there are copies, and each chunk records the rectangle of nodes it
//     touched and, row by row, a span that holds them (TouchedNodes). Atomic: one buffer and
//     atomic additions (the choice on devices; `Atomic` asks for it on the host too), optionally
//     tiled: a team of threads takes `tile_points` consecutive
//     points, adds them into a tile of nodes in its fast (shared) memory and then adds the tile
//     into the buffer, one atomic addition per node and field instead of one per point
//     (detail::scatter_tiles; the default on a device). Serial: one buffer, plain additions.
//  2. gather: for the nodes in the touched rectangle (and those touched the step before, which
//     must become zero), within each row's span where the scatter recorded them, the buffers are
//     summed into the grid's fields and zeroed on the way, so the next step needs no reset. The
//     grid records the rectangles (Grid::active) and their spans (Grid::row_spans) so that the
//     grid update skips the empty nodes.
// The two passes are generic in the number of fields per node (detail::scatter_points,
// detail::gather_nodes): the two-phase P2G (two_phase/two_phase_p2g.hpp) runs them with 11.
// bench/bench_mpm.cpp and bench/bench_impact.cpp measure the variants (docs/notes/performance.md).
#pragma once
#include <Kokkos_Core.hpp>
#include <climits>
#include <cstddef>
#include <type_traits>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/grid.hpp"
#include "kernels/mpm/host_transpose.hpp"
#include "kernels/mpm/particles.hpp"
#include "kernels/mpm/shape_function.hpp"

namespace lsi::mpm {

namespace detail {
// How both scatters add up on ExecSpace: Serial into one buffer with plain additions; host
// threads into one buffer (copy) per thread, unless `Atomic` asks for atomics; a device with
// atomic additions into one buffer (a copy per concurrent GPU thread would not fit).
template <class ExecSpace, bool Atomic>
struct ScatterMode {
#ifdef KOKKOS_ENABLE_SERIAL
  static constexpr bool serial = std::is_same_v<ExecSpace, Kokkos::Serial>;
#else
  static constexpr bool serial = false;
#endif
  static constexpr bool duplicated =
      !Atomic && !serial &&
      Kokkos::SpaceAccessibility<Kokkos::HostSpace, typename ExecSpace::memory_space>::accessible;
  static constexpr bool atomic = !serial && !duplicated;
};
}  // namespace detail

namespace detail {
// Per node of the single-phase P2G: mass, momentum x, y, force x, y. (Padding the record to 8
// doubles, one cache line, with whole-record additions measured slower: GCC 12 keeps them
// scalar.)
constexpr int kP2GFields = 5;
// The fast memory of one tile of the atomic scatter: 24 KiB, 614 nodes of the single-phase P2G,
// 279 of the two-phase one (an H100 multiprocessor has 228 KiB; its registers, not this, bound
// the teams it runs at once).
constexpr int kTileBytes = 24 * 1024;
// Points per block of the host's blocked scatter (p2g_block).
constexpr int kP2GBlock = 32;

// Where a scatter adds node (i, j): at kFields ((i - i0) + stride (j - j0)) doubles from its
// buffer. The grid-wide buffer is {0, 0, nx}; a tile starts at its rectangle's first node.
struct NodeTile {
  int i0 = 0, j0 = 0, stride = 0;
  KOKKOS_FORCEINLINE_FUNCTION int offset(const int i, const int j) const {
    return (i - i0) + stride * (j - j0);
  }
};
}  // namespace detail

// A P2G's buffers of `Fields` doubles per node, allocated once per solver (zero between calls).
template <class ExecSpace, bool Atomic, int Fields = detail::kP2GFields>
struct P2GScatter {
  using Exec = ExecSpace;
  using Mem = typename ExecSpace::memory_space;
  using Mode = detail::ScatterMode<ExecSpace, Atomic>;
  static constexpr bool duplicated = Mode::duplicated, atomic = Mode::atomic;
  static constexpr int kFields = Fields;
  static constexpr bool device_memory =
      !Kokkos::SpaceAccessibility<Kokkos::HostSpace, Mem>::accessible;

  int copies_count = 0;
  Kokkos::View<double**, Kokkos::LayoutRight, Mem> copies;  // [copy][node * kFields + field]
  Kokkos::View<int* [4], Kokkos::LayoutRight, Mem> boxes;   // nodes each copy touched, i0 i1 j0 j1
  // Host buffers (plain additions) only: the span of each row j that holds the nodes each copy
  // touched, [copy][2 j] .. [copy][2 j + 1] (TouchedNodes); after scatter_points, rows(0, .) the
  // spans over every copy and rows(1, .) those of gather_region (the spans of Grid::row_spans).
  Kokkos::View<int**, Kokkos::LayoutRight, Mem> copy_rows;
  Kokkos::View<int**, Kokkos::LayoutRight, Kokkos::HostSpace> rows;
  int grid_rows = 0;
  // The atomic scatter's tiles (detail::scatter_tiles): points per team (0: no tiles, every
  // point adds into the buffer) and the most nodes a tile holds; a team whose points touch more
  // adds them into the buffer directly. On a device 128 by default (an H100: the dry and the
  // two-phase P2G 3.5 times faster at 8 M points, racecheck clean; docs/guide/cuda.md, "The tiled
  // P2G"); on the host none (the atomic scatter there is a benchmark's and a test's choice).
  int tile_points = device_memory ? 128 : 0;
  int tile_nodes = detail::kTileBytes / (kFields * static_cast<int>(sizeof(double)));
  // The lanes of a warp take points tile_points / 32 apart (a multiple of 32 only) instead of
  // consecutive points, so that they add into fewer common nodes at once.
  bool tile_spread = true;
  // Fewer points than this scatter without tiles: finding each tile's rectangle costs more
  // than the atomics it saves on small sets (an H100: the dry column's P2G 55 us without and
  // 60 us with tiles at 20 000 points, 182 and 106 us at 200 000; docs/guide/cuda.md).
  int tile_min_points = 50000;

  // Tiles of `points` points at any number of points (a setting's explicit choice).
  void use_tiles(const int points) {
    tile_points = points;
    tile_min_points = 0;
  }

  P2GScatter() = default;
  explicit P2GScatter(const Grid<Mem>& g) {
    copies_count = duplicated ? instance_concurrency<ExecSpace>() : 1;
    copies = decltype(copies)("p2g_copies", copies_count, static_cast<size_t>(kFields) * g.size());
    boxes = decltype(boxes)("p2g_boxes", copies_count);
    if constexpr (!atomic) {
      grid_rows = g.ny;
      copy_rows = decltype(copy_rows)("p2g_copy_rows", copies_count, 2 * static_cast<size_t>(g.ny));
      rows = decltype(rows)("p2g_rows", 2, 2 * static_cast<size_t>(g.ny));
    }
  }
};

// The rectangles a P2G leaves on its grid(s): the nodes that may hold mass (Grid::mass_box) and
// those whose fields may be nonzero (Grid::dirty_box), with their row spans (Grid::row_spans;
// nullptr where the scatter has none: the atomic one).
struct P2GBoxes {
  NodeBox mass, dirty;
  const int* mass_rows = nullptr;
  const int* dirty_rows = nullptr;
};

namespace detail {

// The nodes a host scatter touched: their rectangle i0..i1 x j0..j1 and, where `rows` is given,
// a span of each row j that holds its touched nodes, rows[2 j] .. rows[2 j + 1] (rows
// 0..ny - 1; the caller empties them first).
struct TouchedNodes {
  int i0 = INT_MAX, i1 = INT_MIN, j0 = INT_MAX, j1 = INT_MIN;
  int* rows = nullptr;
  int ny = 0;
  // Widens them by the 3 x 3 stencil whose first node is (bi, bj).
  KOKKOS_FORCEINLINE_FUNCTION void widen(const int bi, const int bj) {
    i0 = bi < i0 ? bi : i0;
    i1 = bi + 2 > i1 ? bi + 2 : i1;
    j0 = bj < j0 ? bj : j0;
    j1 = bj + 2 > j1 ? bj + 2 : j1;
    if (rows != nullptr) widen_rows(bi, bi, bj, bj);
  }
  // Widens them by the stencils whose first nodes are (bi[k], bj[k]), k < count: the blocked
  // scatters' points. Points sorted by cell have stencils that start on a few neighbouring rows
  // and columns, so a block widens each of its rows by all of its columns at once (spans that may
  // hold a few nodes more than those touched, never fewer); points further apart row by row.
  KOKKOS_FORCEINLINE_FUNCTION void widen_block(const int* bi, const int* bj, const int count) {
    int a0 = INT_MAX, a1 = INT_MIN, b0 = INT_MAX, b1 = INT_MIN;
    for (int k = 0; k < count; ++k) {
      a0 = bi[k] < a0 ? bi[k] : a0;
      a1 = bi[k] > a1 ? bi[k] : a1;
      b0 = bj[k] < b0 ? bj[k] : b0;
      b1 = bj[k] > b1 ? bj[k] : b1;
    }
    if (count == 0) return;
    i0 = a0 < i0 ? a0 : i0;
    i1 = a1 + 2 > i1 ? a1 + 2 : i1;
    j0 = b0 < j0 ? b0 : j0;
    j1 = b1 + 2 > j1 ? b1 + 2 : j1;
    if (rows == nullptr) return;
    if (b1 - b0 <= kBlockRows) {
      widen_rows(a0, a1, b0, b1);
    } else {
      for (int k = 0; k < count; ++k) widen_rows(bi[k], bi[k], bj[k], bj[k]);
    }
  }

 private:
  // The most rows apart the stencils of a block may start and still widen its rows at once.
  static constexpr int kBlockRows = 3;
  // Rows first_row..last_row + 2 by the nodes first..last + 2.
  KOKKOS_FORCEINLINE_FUNCTION void widen_rows(const int first, const int last, const int first_row,
                                              const int last_row) {
    int* const r = rows;  // locals: the stores below cannot change them
    const int lo = first_row > 0 ? first_row : 0;
    const int hi = last_row + 2 < ny - 1 ? last_row + 2 : ny - 1;  // beyond: the health check's
    for (int j = lo; j <= hi; ++j) {
      r[2 * j] = first < r[2 * j] ? first : r[2 * j];
      r[2 * j + 1] = last + 2 > r[2 * j + 1] ? last + 2 : r[2 * j + 1];
    }
  }
};

template <bool Atomic>
KOKKOS_FORCEINLINE_FUNCTION void scatter_add(double* a, double v) {
  if constexpr (Atomic)
    Kokkos::atomic_add(a, v);
  else
    *a += v;
}

// The tiled atomic scatter. Team t takes points [t P, (t + 1) P) (P = tile_points), finds the
// rectangle of their stencils, and if it holds at most tile_nodes nodes: zeroes a tile of that
// rectangle in the team's scratch (shared) memory, adds the points into it (atomic additions in
// fast memory), then adds the tile's nonzero values into the buffer (one atomic addition per node
// and field; consecutive threads write consecutive doubles of a row). Otherwise (points far
// apart) the team adds its points into the buffer directly. Points with nearby indices are
// nearby in space (the builders fill the cells row by row, a cell's points one after the other;
// the flow keeps neighbours together), so 128 points of a column (32 cells) touch about 35 x 4
// nodes: about 1 global addition per point and field instead of 9. With tile_spread the lanes of
// a warp take points tile_points / 32 apart (one per cell) rather than consecutive points, which
// would add into the same nodes at the same time.
template <class S, class PositionView, class PointFn>
void scatter_tiles(S& scatter, const PositionView& position, const int n_points, const double ox,
                   const double oy, const double inv_dx, const int nx, const PointFn& point_fn) {
  using ExecSpace = typename S::Exec;
  using Policy = Kokkos::TeamPolicy<ExecSpace>;
  using Member = typename Policy::member_type;
  using Tile = Kokkos::View<double*, typename ExecSpace::scratch_memory_space,
                            Kokkos::MemoryTraits<Kokkos::Unmanaged>>;
  using Ints = Kokkos::View<int*, typename ExecSpace::scratch_memory_space,
                            Kokkos::MemoryTraits<Kokkos::Unmanaged>>;
  constexpr int F = S::kFields;
  constexpr bool host =
      Kokkos::SpaceAccessibility<Kokkos::HostSpace, typename ExecSpace::memory_space>::accessible;
  const int per_team = scatter.tile_points, capacity = scatter.tile_nodes;
  const bool spread = scatter.tile_spread && per_team % 32 == 0;
  const int league = (n_points + per_team - 1) / per_team;
  if (league == 0) return;
  const auto copies = scatter.copies;
  const size_t scratch = Ints::shmem_size(4) + Tile::shmem_size(static_cast<size_t>(F) * capacity);
  const auto body = KOKKOS_LAMBDA(const Member& team) {
    double* buf = &copies(0, 0);
    const int begin = team.league_rank() * per_team;
    const int end = begin + per_team < n_points ? begin + per_team : n_points;
    // The rectangle of the team's stencils, with atomic min/max in fast memory between
    // barriers (every thread then reads the same rectangle; two nested team reductions of
    // Kokkos 3.4 raced on an H100: compute-sanitizer's racecheck, wrong sums under it).
    Ints box(team.team_scratch(0), 4);
    Tile tile(team.team_scratch(0), static_cast<size_t>(F) * capacity);
    Kokkos::single(Kokkos::PerTeam(team), [&]() {
      box(0) = INT_MAX;
      box(1) = INT_MIN;
      box(2) = INT_MAX;
      box(3) = INT_MIN;
    });
    team.team_barrier();
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, begin, end), [&](const int q) {
      const int bi = quadratic_bspline(position(q, 0) - ox, inv_dx).base;
      const int bj = quadratic_bspline(position(q, 1) - oy, inv_dx).base;
      Kokkos::atomic_fetch_min(&box(0), bi);
      Kokkos::atomic_fetch_max(&box(1), bi);
      Kokkos::atomic_fetch_min(&box(2), bj);
      Kokkos::atomic_fetch_max(&box(3), bj);
    });
    team.team_barrier();
    const NodeTile local{box(0), box(2), box(1) - box(0) + 3};
    const int height = box(3) - box(2) + 3;
    if (local.stride * height > capacity) {  // too spread out for a tile
      Kokkos::parallel_for(Kokkos::TeamThreadRange(team, begin, end), [&](const int q) {
        int bi, bj;
        point_fn(q, buf, NodeTile{0, 0, nx}, bi, bj);
      });
    } else {
      const int values = F * local.stride * height;
      Kokkos::parallel_for(Kokkos::TeamThreadRange(team, values),
                           [&](const int k) { tile(k) = 0.0; });
      team.team_barrier();
      Kokkos::parallel_for(Kokkos::TeamThreadRange(team, per_team), [&](const int k) {
        const int q = begin + (spread ? (k % 32) * (per_team / 32) + k / 32 : k);
        if (q >= end) return;
        int bi, bj;
        point_fn(q, tile.data(), local, bi, bj);
      });
      team.team_barrier();
      Kokkos::parallel_for(Kokkos::TeamThreadRange(team, values), [&](const int k) {
        const double v = tile(k);
        if (v == 0.0) return;  // adding zero changes nothing
        const int node = k / F, field = k - F * node;
        const int row = node / local.stride, i = local.i0 + (node - row * local.stride);
        Kokkos::atomic_add(buf + F * (i + nx * (local.j0 + row)) + field, v);
      });
    }
    // A block may run several teams in turn: the next one rewrites the box and the tile.
    team.team_barrier();
  };
  // A device: one thread per point. The host (tests only): as many threads per team as Kokkos
  // allows (2 with 2 OpenMP threads), so that the barriers and the atomics in the team's scratch
  // memory run concurrently there too.
  int team_size = per_team;
  if constexpr (host) {
    Policy probe(league, 1);
    probe.set_scratch_size(0, Kokkos::PerTeam(scratch));
    const int most = probe.team_size_max(body, Kokkos::ParallelForTag());
    team_size = most < per_team ? most : per_team;
  }
  auto policy = team_policy<ExecSpace>(league, team_size);
  policy.set_scratch_size(0, Kokkos::PerTeam(scratch));
  Kokkos::parallel_for("lsi::mpm::p2g_scatter_tiles", policy, body);
}

// Pass 1 of a P2G: point_fn(q, buf, tile, bi, bj) adds point q's contributions into the
// interleaved buffer `buf` (with scatter_add<S::atomic>, node (i, j) at buf + kFields
// tile.offset(i, j)) and returns the first node (bi, bj) of its 3 x 3 stencil; every node it
// writes must lie in the stencil. `position`: the points' positions (the stencil of the atomic
// path's rectangle). Returns the rectangle of touched nodes, not clipped to the grid.
// block_fn(q0, q1, buf, touched), where given (the host's plain additions only): adds
// points [q0, q1) into `buf` (node (i, j) at kFields (i + nx j)) and widens `touched`
// (TouchedNodes) by their stencils; point_fn one point after the other otherwise. With plain
// additions, the touched nodes' row spans are left in scatter.rows(0, .) (rows of the returned
// rectangle within the grid).
template <class S, class PositionView, class PointFn, class BlockFn>
NodeBox scatter_points(S& scatter, const PositionView& position, const int n_points,
                       const double ox, const double oy, const double inv_dx, const int nx,
                       const PointFn& point_fn, const BlockFn& block_fn) {
  using ExecSpace = typename S::Exec;
  const int nc = scatter.copies_count;
  const auto copies = scatter.copies;
  const auto boxes = scatter.boxes;
  NodeBox touched;
  if constexpr (S::atomic) {
    // The rectangle first, then the scatter, as two kernels: a reduction kernel is sized for its
    // reduction (on an H100, 256 blocks of 256 threads, one block per multiprocessor: 12.5 %
    // occupancy, measured with Nsight Compute), and the scatter needs every warp it can get to
    // hide the latency of its atomics.
    int i0 = INT_MAX, i1 = INT_MIN, j0 = INT_MAX, j1 = INT_MIN;
    Kokkos::parallel_reduce(
        "lsi::mpm::p2g_box", range_policy<ExecSpace>(0, n_points),
        KOKKOS_LAMBDA(const int q, int& a0, int& a1, int& b0, int& b1) {
          const int bi = quadratic_bspline(position(q, 0) - ox, inv_dx).base;
          const int bj = quadratic_bspline(position(q, 1) - oy, inv_dx).base;
          if (bi < a0) a0 = bi;
          if (bi + 2 > a1) a1 = bi + 2;
          if (bj < b0) b0 = bj;
          if (bj + 2 > b1) b1 = bj + 2;
        },
        Kokkos::Min<int>(i0), Kokkos::Max<int>(i1), Kokkos::Min<int>(j0), Kokkos::Max<int>(j1));
    if (scatter.tile_points > 0 && n_points >= scatter.tile_min_points) {
      scatter_tiles(scatter, position, n_points, ox, oy, inv_dx, nx, point_fn);
    } else {
      Kokkos::parallel_for(
          "lsi::mpm::p2g_scatter", range_policy<ExecSpace>(0, n_points),
          KOKKOS_LAMBDA(const int q) {
            int bi, bj;
            point_fn(q, &copies(0, 0), NodeTile{0, 0, nx}, bi, bj);
          });
    }
    if (n_points > 0) touched = {i0, i1, j0, j1};
  } else {
    // One contiguous chunk of points per copy: a copy is never written by two threads at once.
    const auto copy_rows = scatter.copy_rows;
    const int ny = scatter.grid_rows;
    Kokkos::parallel_for(
        "lsi::mpm::p2g_scatter", range_policy<ExecSpace>(0, nc), KOKKOS_LAMBDA(const int c) {
          const int begin = static_cast<int>(static_cast<long>(n_points) * c / nc);
          const int end = static_cast<int>(static_cast<long>(n_points) * (c + 1) / nc);
          double* buf = &copies(c, 0);
          TouchedNodes touched_here;
          touched_here.rows = &copy_rows(c, 0);
          touched_here.ny = ny;
          for (int j = 0; j < ny; ++j) {
            touched_here.rows[2 * j] = INT_MAX;
            touched_here.rows[2 * j + 1] = INT_MIN;
          }
          // Named here, outside the `if constexpr`: nvcc rejects a lambda whose first use (and so
          // capture) of a variable is inside one.
          [[maybe_unused]] const auto& block = block_fn;
          [[maybe_unused]] const auto& point = point_fn;
          [[maybe_unused]] const int row_nodes = nx;
          if constexpr (!std::is_same_v<BlockFn, std::nullptr_t>) {
            for (int q = begin; q < end; q += kP2GBlock)
              block(q, q + kP2GBlock < end ? q + kP2GBlock : end, buf, touched_here);
          } else {
            for (int q = begin; q < end; ++q) {
              int bi, bj;
              point(q, buf, NodeTile{0, 0, row_nodes}, bi, bj);
              touched_here.widen(bi, bj);
            }
          }
          boxes(c, 0) = touched_here.i0;
          boxes(c, 1) = touched_here.i1;
          boxes(c, 2) = touched_here.j0;
          boxes(c, 3) = touched_here.j1;
        });
    execution_instance<ExecSpace>().fence();
    auto host = Kokkos::create_mirror_view(boxes);  // the same memory on host spaces
    Kokkos::deep_copy(host, boxes);
    for (int c = 0; c < nc; ++c) {
      const NodeBox b{host(c, 0), host(c, 1), host(c, 2), host(c, 3)};
      if (!b.empty()) touched = touched.merged(b);
    }
    // The touched nodes' row spans over every copy (host memory: no atomic scatter here).
    if (!touched.empty()) {
      int* const spans = &scatter.rows(0, 0);
      const int first = touched.j0 > 0 ? touched.j0 : 0,
                last = touched.j1 < ny ? touched.j1 : ny - 1;
      for (int j = first; j <= last; ++j) {
        int lo = INT_MAX, hi = INT_MIN;
        for (int c = 0; c < nc; ++c) {
          lo = copy_rows(c, 2 * j) < lo ? copy_rows(c, 2 * j) : lo;
          hi = copy_rows(c, 2 * j + 1) > hi ? copy_rows(c, 2 * j + 1) : hi;
        }
        spans[2 * j] = lo;
        spans[2 * j + 1] = hi;
      }
    }
  }
  return touched;
}

template <class S, class PositionView, class PointFn>
NodeBox scatter_points(S& scatter, const PositionView& position, const int n_points,
                       const double ox, const double oy, const double inv_dx, const int nx,
                       const PointFn& point_fn) {
  return scatter_points(scatter, position, n_points, ox, oy, inv_dx, nx, point_fn, nullptr);
}

// The nodes pass 2 of a P2G visits: the touched nodes clipped to the grid `whole` (returned in
// touched) and those of `previous_dirty` (last step's values, which must become zero).
inline NodeBox gather_region(NodeBox& touched, const NodeBox& whole,
                             const NodeBox& previous_dirty) {
  // Never outside the grid (points beyond its edge are the health check's business).
  if (!touched.empty()) {
    touched = {touched.i0 < 0 ? 0 : touched.i0, touched.i1 > whole.i1 ? whole.i1 : touched.i1,
               touched.j0 < 0 ? 0 : touched.j0, touched.j1 > whole.j1 ? whole.j1 : touched.j1};
  }
  return touched.merged(previous_dirty);
}

// The row spans of gather_region's `region` (into scatter.rows(1, .), a scatter with row spans
// only): per row, from the first to the last node touched now (scatter.rows(0, .), in `touched`)
// or that may be nonzero from before (`previous_rows`, or where nullptr the whole row of
// `previous_dirty`).
template <class S>
const int* region_rows(const S& scatter, const NodeBox& touched, const NodeBox& region,
                       const NodeBox& previous_dirty, const int* previous_rows) {
  const int* now = &scatter.rows(0, 0);
  int* out = &scatter.rows(1, 0);
  for (int j = region.j0; j <= region.j1; ++j) {
    int lo = INT_MAX, hi = INT_MIN;
    if (!touched.empty() && j >= touched.j0 && j <= touched.j1) {
      lo = now[2 * j];
      hi = now[2 * j + 1];
    }
    if (!previous_dirty.empty() && j >= previous_dirty.j0 && j <= previous_dirty.j1) {
      const int plo = previous_rows ? previous_rows[2 * j] : previous_dirty.i0;
      const int phi = previous_rows ? previous_rows[2 * j + 1] : previous_dirty.i1;
      lo = plo < lo ? plo : lo;
      hi = phi > hi ? phi : hi;
    }
    out[2 * j] = lo;
    out[2 * j + 1] = hi;
  }
  return out;
}

// What a P2G's gather visits and leaves on its grid(s), from scatter_points' rectangle of
// touched nodes: the touched nodes clipped to the grid (the mass rectangle), gather_region (the
// dirty rectangle) and, where the scatter records them, the row spans of both.
template <class S>
P2GBoxes gather_boxes(const S& scatter, NodeBox touched, const NodeBox& whole,
                      const NodeBox& previous_dirty, const int* previous_rows) {
  const NodeBox region = gather_region(touched, whole, previous_dirty);
  P2GBoxes boxes{touched, region};
  if constexpr (!S::atomic) {
    boxes.mass_rows = &scatter.rows(0, 0);
    boxes.dirty_rows = region_rows(scatter, touched, region, previous_dirty, previous_rows);
  }
  return boxes;
}

// The sums of node n = i + nx j over a scatter's buffers (F fields) into acc; the buffers are
// zeroed on the way, so the next step needs no reset.
template <int F, class Copies, class Boxes>
KOKKOS_FORCEINLINE_FUNCTION void take_node_sums(const Copies& copies, const Boxes& boxes,
                                                const int nc, const int i, const int j, const int n,
                                                double acc[F]) {
  for (int k = 0; k < F; ++k) acc[k] = 0.0;
  for (int c = 0; c < nc; ++c) {
    if (nc > 1 && (i < boxes(c, 0) || i > boxes(c, 1) || j < boxes(c, 2) || j > boxes(c, 3)))
      continue;  // this copy touched no node here: it holds zeros
    double* b = &copies(c, static_cast<size_t>(F) * n);
    for (int k = 0; k < F; ++k) {
      acc[k] += b[k];
      b[k] = 0.0;
    }
  }
}

// Pass 2 of a P2G: for the nodes of gather_region (and its row spans: gather_boxes), sums the
// buffers, zeroes them and calls store(n, acc) with the kFields sums of node n. Returns the new
// rectangles. previous_rows: the row spans of previous_dirty (nullptr: whole rows).
template <class S, class StoreFn>
P2GBoxes gather_nodes(S& scatter, NodeBox touched, const NodeBox& whole,
                      const NodeBox& previous_dirty, const int* previous_rows, const int nx,
                      const StoreFn& store) {
  using ExecSpace = typename S::Exec;
  constexpr int F = S::kFields;
  const int nc = scatter.copies_count;
  const auto copies = scatter.copies;
  const auto boxes = scatter.boxes;
  const P2GBoxes left = gather_boxes(scatter, touched, whole, previous_dirty, previous_rows);
  const NodeBox region = left.dirty;
  if (!region.empty()) {
    const NodeItems<ExecSpace> items(region, left.dirty_rows);
    Kokkos::parallel_for(
        "lsi::mpm::p2g_gather", range_policy<ExecSpace>(0, items.count()),
        KOKKOS_LAMBDA(const int t) {
          items.visit(t, [&](const int j, const int i_begin, const int i_end) {
            for (int i = i_begin; i <= i_end; ++i) {  // a row of the region, or one node
              const int n = i + nx * j;
              double acc[F];
              take_node_sums<F>(copies, boxes, nc, i, j, n, acc);
              store(n, acc);
            }
          });
        });
  }
  return left;
}

// The APIC momentum w (m v + m C (x_i - x_p)) of the nodes of stencil row b, separable:
// wx_a P + wxd_a Q with P = wy (m v + m C_.y dy_b) and Q = wy m C_.x (wy: the row's weight, dyb:
// its offset y_b - y_p; mv = m v, mC = m C). Used per phase by both P2Gs.
KOKKOS_FORCEINLINE_FUNCTION void apic_row_factors(const double wy, const double dyb,
                                                  const double mv[2], const double mC[2][2],
                                                  double P[2], double Q[2]) {
  P[0] = wy * (mv[0] + mC[0][1] * dyb);
  P[1] = wy * (mv[1] + mC[1][1] * dyb);
  Q[0] = wy * mC[0][0];
  Q[1] = wy * mC[1][0];
}

// The 3 x 3 node contributions of point q into the interleaved buffer `buf` (node (i, j) at
// kP2GFields tile.offset(i, j)); returns the first node of the stencil in (bi, bj).
template <bool Atomic, class MemorySpace>
KOKKOS_FORCEINLINE_FUNCTION void p2g_point(const Particles<MemorySpace>& p, const int q,
                                           double* buf, const NodeTile& tile, const double ox,
                                           const double oy, const double dx, const double inv_dx,
                                           const double gx, const double gy, int& bi, int& bj) {
  constexpr int F = kP2GFields;
  const double xp = p.position(q, 0) - ox, yp = p.position(q, 1) - oy;
  const Stencil1D sx = quadratic_bspline(xp, inv_dx), sy = quadratic_bspline(yp, inv_dx);
  const double m = p.mass(q), V = p.volume(q);
  const double mv[2] = {m * p.velocity(q, 0), m * p.velocity(q, 1)};
  const double mC[2][2] = {{m * p.affine(q, 0, 0), m * p.affine(q, 0, 1)},
                           {m * p.affine(q, 1, 0), m * p.affine(q, 1, 1)}};
  const double Vs[3] = {V * p.stress(q, 0), V * p.stress(q, 1), V * p.stress(q, 2)};
  // Separable weights w = wx(a) wy(b). Per node i:
  //   mass     w m
  //   momentum w (m v + m C (x_i - x_p))             = wx P[r] + wx dxa Q[r]
  //   force   -V sigma grad(w) + w m g               = dwx F1[r] + wx F0[r]
  // with the row factors P, Q, F0, F1 below.
  const double* wx = sx.w;
  const double* dwx = sx.dw;
  double wxd[3];
  offset_weights(sx, xp, dx, wxd);
  for (int b = 0; b < 3; ++b) {
    const double wy = sy.w[b], dwy = sy.dw[b], dyb = (sy.base + b) * dx - yp;
    double P[2], Q[2];
    apic_row_factors(wy, dyb, mv, mC, P, Q);
    const double F1[2] = {-Vs[0] * wy, -Vs[2] * wy};
    const double F0[2] = {-Vs[2] * dwy + wy * m * gx, -Vs[1] * dwy + wy * m * gy};
    double* row = buf + F * tile.offset(sx.base, sy.base + b);
    for (int a = 0; a < 3; ++a) {
      double* node = row + F * a;
      scatter_add<Atomic>(node + 0, wx[a] * wy * m);
      scatter_add<Atomic>(node + 1, wx[a] * P[0] + wxd[a] * Q[0]);
      scatter_add<Atomic>(node + 2, wx[a] * P[1] + wxd[a] * Q[1]);
      scatter_add<Atomic>(node + 3, dwx[a] * F1[0] + wx[a] * F0[0]);
      scatter_add<Atomic>(node + 4, dwx[a] * F1[1] + wx[a] * F0[1]);
    }
  }
  bi = sx.base;
  bj = sy.base;
}

// The host's scatter of points [q0, q1) (plain additions into one buffer): the 3 x 3 x 5
// contributions of every point in one loop, which has no branches and no dependence between
// the points, so that the compiler vectorises it over the points (component arrays,
// particles.hpp); then the additions point by point (neighbouring points add into the same
// nodes), 8 points' values transposed in registers where host_transpose.hpp is compiled in. The
// same sums as p2g_point. Widens `touched` by the stencils.
KOKKOS_FORCEINLINE_FUNCTION void p2g_block(const PointArrays a, const int q0, const int q1,
                                           double* const buf, const int nx, const double ox,
                                           const double oy, const double dx, const double inv_dx,
                                           const double gx, const double gy,
                                           TouchedNodes& touched) {
  constexpr int F = kP2GFields, B = kP2GBlock;
  alignas(64) double add[3][3 * F][B];
  int first_i[B], first_j[B];
#pragma GCC ivdep
  for (int q = q0; q < q1; ++q) {
    const int k = q - q0;
    const double xp = a.position(q, 0) - ox, yp = a.position(q, 1) - oy;
    const Stencil1D sx = quadratic_bspline(xp, inv_dx), sy = quadratic_bspline(yp, inv_dx);
    const double m = a.mass(q), V = a.volume(q);
    const double mv[2] = {m * a.velocity(q, 0), m * a.velocity(q, 1)};
    const double mC[2][2] = {{m * a.affine(q, 0, 0), m * a.affine(q, 0, 1)},
                             {m * a.affine(q, 1, 0), m * a.affine(q, 1, 1)}};
    const double Vs[3] = {V * a.stress(q, 0), V * a.stress(q, 1), V * a.stress(q, 2)};
    double wxd[3];
    offset_weights(sx, xp, dx, wxd);
#pragma GCC unroll 3
    for (int b = 0; b < 3; ++b) {
      const double wy = sy.w[b], dwy = sy.dw[b], dyb = (sy.base + b) * dx - yp;
      double P[2], Q[2];
      apic_row_factors(wy, dyb, mv, mC, P, Q);
      const double F1[2] = {-Vs[0] * wy, -Vs[2] * wy};
      const double F0[2] = {-Vs[2] * dwy + wy * m * gx, -Vs[1] * dwy + wy * m * gy};
#pragma GCC unroll 3
      for (int c = 0; c < 3; ++c) {
        add[b][F * c + 0][k] = sx.w[c] * wy * m;
        add[b][F * c + 1][k] = sx.w[c] * P[0] + wxd[c] * Q[0];
        add[b][F * c + 2][k] = sx.w[c] * P[1] + wxd[c] * Q[1];
        add[b][F * c + 3][k] = sx.dw[c] * F1[0] + sx.w[c] * F0[0];
        add[b][F * c + 4][k] = sx.dw[c] * F1[1] + sx.w[c] * F0[1];
      }
    }
    first_i[k] = sx.base;
    first_j[k] = sy.base;
  }
  touched.widen_block(first_i, first_j, q1 - q0);
  int k = 0;
#if LSI_MPM_HOST_TRANSPOSE
  // 8 points at a time: each row's 15 values of the 8 points transposed in registers (values
  // 0..7 and 8..14 with a zero, two 8 x 8 transposes), then added 8 + 4 + 2 + 1 values wide
  // (never past the row's 15th value). The points in their order, as below: the same sums,
  // bitwise.
  static_assert(3 * F == 15 && B % 8 == 0);
  using host_simd::V8;
  for (; k + 8 <= q1 - q0; k += 8) {
    V8 t[3][2][8];
    for (int b = 0; b < 3; ++b) {
      for (int p = 0; p < 8; ++p) {
        t[b][0][p] = host_simd::load8(&add[b][p][k]);
        t[b][1][p] = p < 7 ? host_simd::load8(&add[b][8 + p][k]) : V8{};
      }
      host_simd::transpose8(t[b][0]);
      host_simd::transpose8(t[b][1]);
    }
    for (int p = 0; p < 8; ++p) {
      const int bi = first_i[k + p], bj = first_j[k + p], n = bi + nx * bj;
      for (int b = 0; b < 3; ++b) {
        double* row = buf + F * (n + nx * b);
        host_simd::store8(row, host_simd::load8(row) + t[b][0][p]);
        host_simd::add7(row + 8, t[b][1][p]);
      }
    }
  }
#endif
  for (; k < q1 - q0; ++k) {
    const int bi = first_i[k], bj = first_j[k], n = bi + nx * bj;
    for (int b = 0; b < 3; ++b) {
      double* row = buf + F * (n + nx * b);
      for (int v = 0; v < 3 * F; ++v) row[v] += add[b][v][k];
    }
  }
}

// p2g_block as the block function of scatter_points.
template <class MemorySpace>
struct P2GBlock {
  Particles<MemorySpace> p;
  int nx;
  double ox, oy, dx, inv_dx, gx, gy;
  KOKKOS_INLINE_FUNCTION void operator()(const int q0, const int q1, double* buf,
                                         TouchedNodes& touched) const {
    p2g_block(PointArrays(p), q0, q1, buf, nx, ox, oy, dx, inv_dx, gx, gy, touched);
  }
};

}  // namespace detail

template <class ExecSpace, bool Atomic, class MemorySpace>
void p2g(const Particles<MemorySpace>& p, const Grid<MemorySpace>& g,
         P2GScatter<ExecSpace, Atomic>& scatter, const double gravity[2]) {
  using S = P2GScatter<ExecSpace, Atomic>;
  const double ox = g.origin[0], oy = g.origin[1], dx = g.dx, inv_dx = 1.0 / g.dx;
  const int nx = g.nx;
  const double gx = gravity[0], gy = gravity[1];
  // Host buffers with plain additions: the blocked scatter (p2g_block).
  using Block = std::conditional_t<S::atomic, std::nullptr_t, detail::P2GBlock<MemorySpace>>;
  Block block{};
  if constexpr (!S::atomic) block = {p, nx, ox, oy, dx, inv_dx, gx, gy};
  const NodeBox touched = detail::scatter_points(
      scatter, p.position, p.count, ox, oy, inv_dx, nx,
      KOKKOS_LAMBDA(const int q, double* buf, const detail::NodeTile& tile, int& bi, int& bj) {
        detail::p2g_point<S::atomic>(p, q, buf, tile, ox, oy, dx, inv_dx, gx, gy, bi, bj);
      },
      block);
  const auto mass = g.mass;
  const auto momentum = g.momentum;
  const auto force = g.force;
  const P2GBoxes boxes = detail::gather_nodes(
      scatter, touched, g.whole(), g.dirty_box(), g.dirty_rows(), nx,
      KOKKOS_LAMBDA(const int n, const double* acc) {
        mass(n) = acc[0];
        momentum(n, 0) = acc[1];
        momentum(n, 1) = acc[2];
        force(n, 0) = acc[3];
        force(n, 1) = acc[4];
      });
  g.set_mass_box(boxes.mass, boxes.mass_rows);
  g.set_dirty_box(boxes.dirty, boxes.dirty_rows);
}

}  // namespace lsi::mpm

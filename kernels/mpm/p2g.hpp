// Particle to grid: mass, APIC momentum m (v_p + C_p (x_i - x_p)), and force
// -V_p sigma_p grad(w_ip) + w_ip m_p g.
//
// Without data races, in two passes over memory (two parallel regions):
//  1. scatter: the points add their 3 x 3 node contributions into a node-interleaved buffer
//     (mass, momentum x, y, force x, y: 40 contiguous bytes per node instead of three arrays).
//     Duplicated (the default on host spaces): one buffer per thread; the points are cut into as
//     many contiguous chunks as there are copies, and each chunk records the rectangle of nodes it
//     touched. Atomic: one buffer and atomic additions (the choice on devices; `Atomic` asks for
//     it on the host too). Serial: one buffer, plain additions.
//  2. gather: for the nodes in the touched rectangle (and those touched the step before, which
//     must become zero), the buffers are summed into the grid's fields and zeroed on the way, so
//     the next step needs no reset. The grid records the rectangles (Grid::active) so that the
//     grid update skips the empty nodes.
// The two passes are generic in the number of fields per node (detail::scatter_points,
// detail::gather_nodes): the two-phase P2G (two_phase/two_phase_p2g.hpp) runs them with 11.
// bench/bench_mpm.cpp and bench/bench_impact.cpp measure the variants (docs/performance.md).
#pragma once
#include <Kokkos_Core.hpp>
#include <climits>
#include <type_traits>

#include "kernels/mpm/grid.hpp"
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
}

// A P2G's buffers of `Fields` doubles per node, allocated once per solver (zero between calls).
template <class ExecSpace, bool Atomic, int Fields = detail::kP2GFields>
struct P2GScatter {
  using Exec = ExecSpace;
  using Mem = typename ExecSpace::memory_space;
  using Mode = detail::ScatterMode<ExecSpace, Atomic>;
  static constexpr bool duplicated = Mode::duplicated, atomic = Mode::atomic;
  static constexpr int kFields = Fields;

  int copies_count = 0;
  Kokkos::View<double**, Kokkos::LayoutRight, Mem> copies;   // [copy][node * kFields + field]
  Kokkos::View<int* [4], Kokkos::LayoutRight, Mem> boxes;    // nodes each copy touched, i0 i1 j0 j1

  P2GScatter() = default;
  explicit P2GScatter(const Grid<Mem>& g) {
    copies_count = duplicated ? ExecSpace().concurrency() : 1;
    copies = decltype(copies)("p2g_copies", copies_count, static_cast<size_t>(kFields) * g.size());
    boxes = decltype(boxes)("p2g_boxes", copies_count);
  }
};

// The rectangles a P2G leaves on its grid(s): the nodes that may hold mass (Grid::mass_box) and
// those whose fields may be nonzero (Grid::dirty_box).
struct P2GBoxes {
  NodeBox mass, dirty;
};

namespace detail {

template <bool Atomic>
KOKKOS_FORCEINLINE_FUNCTION void scatter_add(double* a, double v) {
  if constexpr (Atomic) Kokkos::atomic_add(a, v);
  else *a += v;
}

// Pass 1 of a P2G: point_fn(q, buf, bi, bj) adds point q's contributions into the interleaved
// buffer `buf` (with scatter_add<S::atomic>, node n at buf + kFields n) and returns the first
// node (bi, bj) of its 3 x 3 stencil; every node it writes must lie in the stencil. `position`:
// the points' positions (the stencil of the atomic path's rectangle). Returns the rectangle of
// touched nodes, not clipped to the grid.
template <class S, class PositionView, class PointFn>
NodeBox scatter_points(S& scatter, const PositionView& position, const int n_points,
                       const double ox, const double oy, const double inv_dx,
                       const PointFn& point_fn) {
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
        "lsi::mpm::p2g_box", Kokkos::RangePolicy<ExecSpace>(0, n_points),
        KOKKOS_LAMBDA(const int q, int& a0, int& a1, int& b0, int& b1) {
          const int bi = quadratic_bspline(position(q, 0) - ox, inv_dx).base;
          const int bj = quadratic_bspline(position(q, 1) - oy, inv_dx).base;
          if (bi < a0) a0 = bi;
          if (bi + 2 > a1) a1 = bi + 2;
          if (bj < b0) b0 = bj;
          if (bj + 2 > b1) b1 = bj + 2;
        },
        Kokkos::Min<int>(i0), Kokkos::Max<int>(i1), Kokkos::Min<int>(j0), Kokkos::Max<int>(j1));
    Kokkos::parallel_for(
        "lsi::mpm::p2g_scatter", Kokkos::RangePolicy<ExecSpace>(0, n_points),
        KOKKOS_LAMBDA(const int q) {
          int bi, bj;
          point_fn(q, &copies(0, 0), bi, bj);
        });
    if (n_points > 0) touched = {i0, i1, j0, j1};
  } else {
    // One contiguous chunk of points per copy: a copy is never written by two threads at once.
    Kokkos::parallel_for(
        "lsi::mpm::p2g_scatter", Kokkos::RangePolicy<ExecSpace>(0, nc),
        KOKKOS_LAMBDA(const int c) {
          const int begin = static_cast<int>(static_cast<long>(n_points) * c / nc);
          const int end = static_cast<int>(static_cast<long>(n_points) * (c + 1) / nc);
          double* buf = &copies(c, 0);
          int a0 = INT_MAX, a1 = INT_MIN, b0 = INT_MAX, b1 = INT_MIN;
          for (int q = begin; q < end; ++q) {
            int bi, bj;
            point_fn(q, buf, bi, bj);
            a0 = bi < a0 ? bi : a0;
            a1 = bi + 2 > a1 ? bi + 2 : a1;
            b0 = bj < b0 ? bj : b0;
            b1 = bj + 2 > b1 ? bj + 2 : b1;
          }
          boxes(c, 0) = a0;
          boxes(c, 1) = a1;
          boxes(c, 2) = b0;
          boxes(c, 3) = b1;
        });
    Kokkos::fence();
    auto host = Kokkos::create_mirror_view(boxes);   // the same memory on host spaces
    Kokkos::deep_copy(host, boxes);
    for (int c = 0; c < nc; ++c) {
      const NodeBox b{host(c, 0), host(c, 1), host(c, 2), host(c, 3)};
      if (!b.empty()) touched = touched.merged(b);
    }
  }
  return touched;
}

// Pass 2 of a P2G: for the touched nodes (clipped to the grid `whole`) and those of
// `previous_dirty` (last step's values, which must become zero), sums the buffers, zeroes them
// and calls store(n, acc) with the kFields sums of node n. Returns the new rectangles.
template <class S, class StoreFn>
P2GBoxes gather_nodes(S& scatter, NodeBox touched, const NodeBox& whole,
                      const NodeBox& previous_dirty, const int nx, const StoreFn& store) {
  using ExecSpace = typename S::Exec;
  constexpr int F = S::kFields;
  const int nc = scatter.copies_count;
  const auto copies = scatter.copies;
  const auto boxes = scatter.boxes;
  // Never outside the grid (points beyond its edge are the health check's business).
  if (!touched.empty()) {
    touched = {touched.i0 < 0 ? 0 : touched.i0, touched.i1 > whole.i1 ? whole.i1 : touched.i1,
               touched.j0 < 0 ? 0 : touched.j0, touched.j1 > whole.j1 ? whole.j1 : touched.j1};
  }
  const NodeBox region = touched.merged(previous_dirty);
  if (!region.empty()) {
    const NodeItems<ExecSpace> items(region);
    Kokkos::parallel_for(
        "lsi::mpm::p2g_gather", Kokkos::RangePolicy<ExecSpace>(0, items.count()),
        KOKKOS_LAMBDA(const int t) {
          int j, i_begin, i_end;
          items.nodes(t, j, i_begin, i_end);
          for (int i = i_begin; i <= i_end; ++i) {   // a row of the region, or one node
            const int n = i + nx * j;
            double acc[F];
            for (int k = 0; k < F; ++k) acc[k] = 0.0;
            for (int c = 0; c < nc; ++c) {
              if (nc > 1 && (i < boxes(c, 0) || i > boxes(c, 1) || j < boxes(c, 2) ||
                             j > boxes(c, 3)))
                continue;   // this copy touched no node here: it holds zeros
              double* b = &copies(c, static_cast<size_t>(F) * n);
              for (int k = 0; k < F; ++k) {
                acc[k] += b[k];
                b[k] = 0.0;
              }
            }
            store(n, acc);
          }
        });
  }
  return {touched, region};
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

// The 3 x 3 node contributions of point q into the interleaved buffer `buf`; returns the first
// node of the stencil in (bi, bj) (for the touched-node rectangle).
template <bool Atomic, class MemorySpace>
KOKKOS_FORCEINLINE_FUNCTION void p2g_point(const Particles<MemorySpace>& p, const int q,
                                           double* buf, const double ox, const double oy,
                                           const double dx, const double inv_dx, const int nx,
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
    double* row = buf + F * (sx.base + nx * (sy.base + b));
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

}  // namespace detail

template <class ExecSpace, bool Atomic, class MemorySpace>
void p2g(const Particles<MemorySpace>& p, const Grid<MemorySpace>& g,
         P2GScatter<ExecSpace, Atomic>& scatter, const double gravity[2]) {
  using S = P2GScatter<ExecSpace, Atomic>;
  const double ox = g.origin[0], oy = g.origin[1], dx = g.dx, inv_dx = 1.0 / g.dx;
  const int nx = g.nx;
  const double gx = gravity[0], gy = gravity[1];
  const NodeBox touched = detail::scatter_points(
      scatter, p.position, p.count, ox, oy, inv_dx,
      KOKKOS_LAMBDA(const int q, double* buf, int& bi, int& bj) {
        detail::p2g_point<S::atomic>(p, q, buf, ox, oy, dx, inv_dx, nx, gx, gy, bi, bj);
      });
  const auto mass = g.mass;
  const auto momentum = g.momentum;
  const auto force = g.force;
  const P2GBoxes boxes = detail::gather_nodes(
      scatter, touched, g.whole(), g.dirty_box(), nx,
      KOKKOS_LAMBDA(const int n, const double* acc) {
        mass(n) = acc[0];
        momentum(n, 0) = acc[1];
        momentum(n, 1) = acc[2];
        force(n, 0) = acc[3];
        force(n, 1) = acc[4];
      });
  g.set_mass_box(boxes.mass);
  g.set_dirty_box(boxes.dirty);
}

}  // namespace lsi::mpm

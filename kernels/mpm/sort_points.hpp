// Sorting the material points by grid cell: the points of a cell, and of neighbouring cells of a
// row, then lie next to each other in memory, so that P2G and G2P, which visit the points in
// index order, find the nodes of consecutive points in the caches (and the per-thread chunks of
// the P2G scatter touch small rectangles of nodes). The builders create the points in this order;
// a flow mixes them as it runs, and the solvers sort again every `sort_interval` steps
// (SolverSettings).
//
// The sort is a stable counting sort on the index of the cell that holds each point (i + nx j):
// points of one cell keep their order, so a set of points that is already in cell order is left
// exactly as it is (no field is touched), and the order, hence every result, is the same for a
// given run on any number of threads. The permutation is applied in place to every field (the
// Views keep their memory, so handles held elsewhere stay valid); `Particles::id` travels with
// the point and names it among the initial points (outputs write the points in id order).
// Moving points changes the order of the sums over points (P2G, reductions) and so the results
// by round-off only.
#pragma once
#include <Kokkos_Core.hpp>
#include <vector>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/particles.hpp"

namespace lsi::mpm {

// The permutation of a sort and the scratch memory to apply it, kept by a solver between sorts.
template <class ExecSpace>
class PointSorter {
 public:
  using Mem = typename ExecSpace::memory_space;

  // Computes the cell order of the points at `position` on the grid (origin, dx, nx x ny nodes).
  // Returns false, and leaves nothing to apply, where the points are in that order already.
  template <class PositionView>
  bool order(const PositionView& position, const int count, const double ox, const double oy,
             const double dx, const int nx, const int ny) {
    if (static_cast<int>(from_.extent(0)) != count) {
      from_ = Kokkos::View<int*, Mem>("point_sort_from", count);
      scratch_ = Kokkos::View<double**, Kokkos::LayoutLeft, Mem>("point_sort_scratch", count, 4);
    }
    count_ = count;
    const auto key = from_;  // the cells first, the permutation after
    const double inv_dx = 1.0 / dx;
    const int cells_x = nx - 1, cells = (nx - 1) * (ny - 1);
    Kokkos::parallel_for(
        "lsi::mpm::point_cells", range_policy<ExecSpace>(0, count), KOKKOS_LAMBDA(const int q) {
          // Outside the grid (the health check stops such a run): the nearest cell.
          const double fx = (position(q, 0) - ox) * inv_dx, fy = (position(q, 1) - oy) * inv_dx;
          int i = fx > 0.0 ? static_cast<int>(fx) : 0, j = fy > 0.0 ? static_cast<int>(fy) : 0;
          i = i < cells_x - 1 ? i : cells_x - 1;
          j = j < cells / cells_x - 1 ? j : cells / cells_x - 1;
          key(q) = i + cells_x * j;
        });
    auto host = Kokkos::create_mirror_view(Kokkos::HostSpace(), key, Kokkos::WithoutInitializing);
    copy_and_wait<ExecSpace>(host, key);
    bool sorted = true;
    for (int q = 1; q < count && sorted; ++q) sorted = host(q - 1) <= host(q);
    if (sorted) return false;
    // Counting sort: first[c] = the first place of cell c; from(place) = the point that goes there.
    std::vector<int> first(static_cast<size_t>(cells) + 1, 0);
    for (int q = 0; q < count; ++q) ++first[host(q) + 1];
    for (int c = 0; c < cells; ++c) first[c + 1] += first[c];
    std::vector<int> from(static_cast<size_t>(count));
    for (int q = 0; q < count; ++q) from[first[host(q)]++] = q;
    for (int q = 0; q < count; ++q) host(q) = from[q];
    copy_and_wait<ExecSpace>(from_, host);
    return true;
  }

  // An order of one's own: point from[q] goes to place q (a permutation of 0..n-1; benchmarks
  // and tests shuffle points with it).
  void use_order(const std::vector<int>& from) {
    count_ = static_cast<int>(from.size());
    from_ = Kokkos::View<int*, Mem>("point_sort_from", count_);
    scratch_ = Kokkos::View<double**, Kokkos::LayoutLeft, Mem>("point_sort_scratch", count_, 4);
    auto host = Kokkos::create_mirror_view(from_);
    for (int q = 0; q < count_; ++q) host(q) = from[q];
    Kokkos::deep_copy(from_, host);
  }

  // Moves the points of a View of the last order(): field(q) = field(from(q)) for every
  // component. A View of one or more components per point (rank 1 to 3, up to 4 components).
  template <class FieldView>
  void apply(const FieldView& field) const {
    using T = typename FieldView::non_const_value_type;
    constexpr int rank = FieldView::rank;
    const int c1 = rank > 1 ? static_cast<int>(field.extent(1)) : 1;
    const int c2 = rank > 2 ? static_cast<int>(field.extent(2)) : 1;
    const auto from = from_;
    const auto scratch = scratch_;
    Kokkos::parallel_for(
        "lsi::mpm::point_sort_gather", range_policy<ExecSpace>(0, count_),
        KOKKOS_LAMBDA(const int q) {
          const int r = from(q);
          for (int a = 0; a < c1; ++a)
            for (int b = 0; b < c2; ++b) scratch(q, a * c2 + b) = element(field, r, a, b);
        });
    Kokkos::parallel_for(
        "lsi::mpm::point_sort_store", range_policy<ExecSpace>(0, count_),
        KOKKOS_LAMBDA(const int q) {
          for (int a = 0; a < c1; ++a)
            for (int b = 0; b < c2; ++b)
              element(field, q, a, b) = static_cast<T>(scratch(q, a * c2 + b));
        });
  }

  // Every field of a set of points.
  template <class MemorySpace>
  void apply(const Particles<MemorySpace>& p) const {
    apply(p.position);
    apply(p.velocity);
    apply(p.affine);
    apply(p.velocity_gradient);
    apply(p.stress);
    apply(p.mass);
    apply(p.volume);
    apply(p.volume0);
    apply(p.plastic_work);
    apply(p.deviatoric_strain);
    apply(p.material);
    apply(p.id);
  }

 private:
  template <class FieldView>
  KOKKOS_FORCEINLINE_FUNCTION static auto& element(const FieldView& f, const int q,
                                                   [[maybe_unused]] const int a,
                                                   [[maybe_unused]] const int b) {
    if constexpr (FieldView::rank == 1)
      return f(q);
    else if constexpr (FieldView::rank == 2)
      return f(q, a);
    else
      return f(q, a, b);
  }

  int count_ = 0;
  Kokkos::View<int*, Mem> from_;
  Kokkos::View<double**, Kokkos::LayoutLeft, Mem> scratch_;
};

}  // namespace lsi::mpm

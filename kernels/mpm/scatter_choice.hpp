// The P2G scatter of a solver, atomic or with per-thread buffers (p2g.hpp), chosen once when the
// solver is built; visit() hands the chosen one to a P2G call.
#pragma once
#include <utility>
#include <variant>

#include "kernels/mpm/grid.hpp"
#include "kernels/mpm/p2g.hpp"

namespace lsi::mpm {

template <class ExecSpace, int Fields = detail::kP2GFields>
class ScatterChoice {
 public:
  using Mem = typename ExecSpace::memory_space;

  ScatterChoice() = default;
  // tile_points: SolverSettings::scatter_tile_points (< 0: the scatter's default).
  ScatterChoice(const Grid<Mem>& grid, bool atomic, int tile_points) {
    if (atomic)
      scatter_.template emplace<P2GScatter<ExecSpace, true, Fields>>(grid);
    else
      scatter_.template emplace<P2GScatter<ExecSpace, false, Fields>>(grid);
    if (tile_points >= 0) visit([&](auto& s) { s.use_tiles(tile_points); });
  }

  template <class F>
  void visit(F&& f) {
    std::visit(std::forward<F>(f), scatter_);
  }

 private:
  std::variant<P2GScatter<ExecSpace, false, Fields>, P2GScatter<ExecSpace, true, Fields>> scatter_;
};

}  // namespace lsi::mpm

// Two-phase P2G and grid update in one pass over the nodes: the P2G's scatter
// (two_phase_p2g.hpp, detail::two_phase_scatter), then, per node of the gather's rectangle
// (within its row spans, p2g.hpp), the
// buffers' sums (stored into the grids as two_phase_p2g stores them) and at once the node's
// update (two_phase_grid_update.hpp, update_two_phase_node) from those sums still in registers.
// The same results as two_phase_p2g followed by two_phase_grid_update, bitwise: the same sums,
// the same per-node arithmetic, and the reductions over the same work items in the same order.
// It saves the grid update's parallel region and its reading back of the eleven fields.
// For the solver's steps without anything between the two (no wall correction, whose mirror
// reaction reads the grid after P2G; no transfer-dissipation account of the grid after P2G).
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/mpm/boundary.hpp"
#include "kernels/mpm/p2g.hpp"
#include "kernels/mpm/two_phase/two_phase_grid.hpp"
#include "kernels/mpm/two_phase/two_phase_grid_update.hpp"
#include "kernels/mpm/two_phase/two_phase_p2g.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"

namespace lsi::mpm::two_phase {

template <class ExecSpace, bool SemiImplicit, bool Atomic, class MemorySpace>
GridUpdateReport two_phase_p2g_grid_update_impl(const TwoPhaseParticles<MemorySpace>& p,
                                                const TwoPhaseGrid<MemorySpace>& g,
                                                TwoPhaseScatter<ExecSpace, Atomic>& scatter,
                                                const double gravity[2], double liquid_density,
                                                double darcy_gravity, const Boundaries& walls,
                                                const Boundaries& liquid_walls, double dt) {
  namespace nf = node_field;
  using S = TwoPhaseScatter<ExecSpace, Atomic>;
  constexpr int F = S::kFields;
  const NodeBox touched = detail::two_phase_scatter(p, g, scatter, gravity, liquid_density,
                                                    darcy_gravity, nullptr, nullptr);
  const P2GBoxes left = lsi::mpm::detail::gather_boxes(scatter, touched, g.solid.whole(),
                                                       g.solid.dirty_box(), g.solid.dirty_rows());
  for (const auto* grid : {&g.solid, &g.liquid}) {
    grid->set_mass_box(left.mass, left.mass_rows);
    grid->set_dirty_box(left.dirty, left.dirty_rows);
  }
  const int nc = scatter.copies_count;
  const auto copies = scatter.copies;
  const auto boxes = scatter.boxes;
  const auto solid = g.solid;
  const auto liquid = g.liquid;
  const auto drag = g.drag;
  return update_two_phase_nodes<ExecSpace, SemiImplicit>(
      SemiImplicit ? "lsi::mpm::two_phase::p2g_grid_update_semi_implicit"
                   : "lsi::mpm::two_phase::p2g_grid_update_explicit",
      g, left.dirty, left.dirty_rows, walls, liquid_walls, dt, gravity,
      KOKKOS_LAMBDA(const int ii, const int j, const int i) {
        double acc[F];
        lsi::mpm::detail::take_node_sums<F>(copies, boxes, nc, ii, j, i, acc);
        const TwoPhaseNodeSums n{acc[nf::SolidMass],
                                 acc[nf::LiquidMass],
                                 {acc[nf::SolidMomentumX], acc[nf::SolidMomentumY]},
                                 {acc[nf::LiquidMomentumX], acc[nf::LiquidMomentumY]},
                                 {acc[nf::MixtureForceX], acc[nf::MixtureForceY]},
                                 {acc[nf::LiquidForceX], acc[nf::LiquidForceY]},
                                 acc[nf::Drag]};
        solid.mass(i) = n.mS;
        solid.momentum(i, 0) = n.pS[0];
        solid.momentum(i, 1) = n.pS[1];
        solid.force(i, 0) = n.fS[0];
        solid.force(i, 1) = n.fS[1];
        liquid.mass(i) = n.mL;
        liquid.momentum(i, 0) = n.pL[0];
        liquid.momentum(i, 1) = n.pL[1];
        liquid.force(i, 0) = n.fL[0];
        liquid.force(i, 1) = n.fL[1];
        drag(i) = n.Q;
        return n;
      });
}

// two_phase_p2g (without the wall correction) followed by two_phase_grid_update, in one pass
// over the nodes (see the file comment).
template <class ExecSpace, bool Atomic, class MemorySpace>
GridUpdateReport two_phase_p2g_grid_update(const TwoPhaseParticles<MemorySpace>& p,
                                           const TwoPhaseGrid<MemorySpace>& g,
                                           TwoPhaseScatter<ExecSpace, Atomic>& scatter,
                                           const double gravity[2], double liquid_density,
                                           double darcy_gravity, const Boundaries& walls,
                                           const Boundaries& liquid_walls, double dt, Drag drag) {
  return drag == Drag::SemiImplicit
             ? two_phase_p2g_grid_update_impl<ExecSpace, true>(
                   p, g, scatter, gravity, liquid_density, darcy_gravity, walls, liquid_walls, dt)
             : two_phase_p2g_grid_update_impl<ExecSpace, false>(
                   p, g, scatter, gravity, liquid_density, darcy_gravity, walls, liquid_walls, dt);
}

}  // namespace lsi::mpm::two_phase

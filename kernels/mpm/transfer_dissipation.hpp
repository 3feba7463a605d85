// Kinetic energy lost in the transfers between the points and the grid: the numerical
// dissipation of MPM that no constitutive term books, measured step by step (optional: three
// reductions a step, off unless a scene asks for it).
//
// In a step the points' kinetic energy K_p goes to the grid by P2G (grid kinetic energy from the
// nodal momenta, sum |p_i|^2 / (2 m_i)), the grid update and the contacts change the nodal
// velocities (the work of the forces, which the energy balance books), and G2P brings the new
// nodal velocities back to the points. What P2G and G2P change is the transfer loss of the step:
//   (K_p before P2G - K_grid after P2G) + (K_grid after the update - K_p after G2P).
// It is >= 0 for PIC (a projection onto the grid and an average back: both lose energy); APIC's
// P2G adds the energy of the points' affine velocity to the grid, and its G2P takes more back, so
// only the sum over a step means something. Accumulated over a run it is the part of the energy
// residual (Solver::energy_residual) that the transfers explain: in a violent impact, the kinetic
// energy destroyed where streams of different velocity merge on the grid (docs/theory/mpm.md, "Energy
// lost in the transfers").
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/execution_instance.hpp"
#include "kernels/mpm/grid.hpp"

namespace lsi::mpm {

// Kinetic energy of one phase of the points (J/m): sum m |v|^2 / 2.
template <class ExecSpace, class Masses, class Velocities>
double points_kinetic_energy(const Masses& mass, const Velocities& velocity) {
  double k = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::points_kinetic_energy", range_policy<ExecSpace>(0, mass.extent(0)),
      KOKKOS_LAMBDA(const int q, double& sum) {
        sum += 0.5 * mass(q) * (velocity(q, 0) * velocity(q, 0) + velocity(q, 1) * velocity(q, 1));
      },
      k);
  return k;
}

// Kinetic energy of the grid (J/m), from the nodal momenta as P2G leaves them (AfterP2G), or
// from the nodal velocities that G2P will read (AfterUpdate). Nodes without mass carry none.
enum class GridState { AfterP2G, AfterUpdate };

template <class ExecSpace, class MemorySpace>
double grid_kinetic_energy(const Grid<MemorySpace>& g, GridState state) {
  const auto m = g.mass;
  const auto p = g.momentum;
  const auto v = g.velocity;
  const bool from_momentum = state == GridState::AfterP2G;
  double k = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::grid_kinetic_energy", range_policy<ExecSpace>(0, g.size()),
      KOKKOS_LAMBDA(const int i, double& sum) {
        const double mi = m(i);
        if (!(mi > 0.0)) return;
        sum += from_momentum ? 0.5 * (p(i, 0) * p(i, 0) + p(i, 1) * p(i, 1)) / mi
                             : 0.5 * mi * (v(i, 0) * v(i, 0) + v(i, 1) * v(i, 1));
      },
      k);
  return k;
}

// The running account of one solver: the solver records the three kinetic energies of a step
// (points before P2G, grid after P2G, grid after the update and the contacts) and closes the
// step with the points' kinetic energy after G2P, which is also the next step's "points before"
// (nothing changes the points' velocities between steps), so that it is reduced once a step.
struct TransferDissipation {
  double accumulated = 0.0;  // J/m, since the start of the run
  double points_before = 0.0, grid_after_p2g = 0.0, grid_after_update = 0.0;
  bool points_before_current = false;  // points_before left by the last step

  void close_step(double points_after) {
    accumulated += (points_before - grid_after_p2g) + (grid_after_update - points_after);
    points_before = points_after;
    points_before_current = true;
  }
};

}  // namespace lsi::mpm

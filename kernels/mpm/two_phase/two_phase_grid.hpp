// The two-phase background grid: two single-phase grids on the same nodes, plus the nodal Darcy
// drag coefficient.
//   solid:  mass = solid mass m_S,i; momentum = solid momentum; force = MIXTURE force
//           (-V sigma grad w with the total stress sigma' - p I, + (m_S + m_L) g + traction);
//           velocity / velocity_old = solid velocity after / before the update.
//   liquid: mass = liquid mass m_L,i; momentum = liquid momentum; force = liquid force
//           (+V n p grad w + m_L g); velocity / velocity_old = liquid velocity.
//   drag:   Q_i = sum_p w_ip V_p n_p^2 rho_L g / k_p, kg/s per m (drag force = Q_i (v_L - v_S)).
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/mpm/grid.hpp"

namespace lsi::mpm::two_phase {

template <class MemorySpace>
struct TwoPhaseGrid {
  Grid<MemorySpace> solid, liquid;
  Kokkos::View<double*, MemorySpace> drag;
  // Scratch of pore_pressure_update.hpp (nodal volume, cell sums of the pressure projection).
  Kokkos::View<double*, MemorySpace> smooth_value, smooth_weight;

  TwoPhaseGrid() = default;
  TwoPhaseGrid(const double lower[2], const double upper[2], double cell_size)
      : solid(lower, upper, cell_size), liquid(lower, upper, cell_size) {
    drag = decltype(drag)("grid_drag", solid.size());
    smooth_value = decltype(smooth_value)("grid_smooth_value", solid.size());
    smooth_weight = decltype(smooth_weight)("grid_smooth_weight", solid.size());
  }
  int size() const { return solid.size(); }
  double dx() const { return solid.dx; }
};

}  // namespace lsi::mpm::two_phase

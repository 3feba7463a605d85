// The regular background grid: nodes (i, j) at origin + (i, j) dx, flattened as i + nx j.
// Nodal fields live in flat Views; they are reset every step.
#pragma once
#include <Kokkos_Core.hpp>

namespace lsi::mpm {

template <class MemorySpace>
struct Grid {
  double origin[2] = {0.0, 0.0};
  double dx = 1.0;
  int nx = 0, ny = 0;                                 // nodes per direction
  Kokkos::View<double*, MemorySpace> mass;            // kg/m
  Kokkos::View<double* [2], MemorySpace> momentum;    // kg/s per m (mass x velocity)
  Kokkos::View<double* [2], MemorySpace> force;       // N/m
  Kokkos::View<double* [2], MemorySpace> velocity;    // m/s, after the update
  Kokkos::View<double* [2], MemorySpace> velocity_old;  // m/s, before the update (FLIP)

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
  }
  int size() const { return nx * ny; }
  double upper(int d) const { return origin[d] + (d == 0 ? nx - 1 : ny - 1) * dx; }
};

}  // namespace lsi::mpm

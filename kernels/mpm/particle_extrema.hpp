// Extrema over the material points that the solvers need once, at construction: the largest
// speed and the largest expansion V / V0 (the first time step, time_step.hpp) and the lightest
// point's mass (the small-mass threshold), and the material's front. Free
// functions rather than lambdas in the constructors: nvcc does not accept an extended
// __host__ __device__ lambda whose enclosing function is a constructor.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/execution_instance.hpp"
#include "kernels/common/math.hpp"

namespace lsi::mpm {

// Largest |v| over the points of one velocity field (n x 2), m/s; 0 with no points.
template <class ExecSpace, class VelocityView>
double largest_speed(const VelocityView& v, int count) {
  double vmax = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::largest_speed", range_policy<ExecSpace>(0, count),
      KOKKOS_LAMBDA(const int q, double& vm) {
        const double s = math::sqrt(v(q, 0) * v(q, 0) + v(q, 1) * v(q, 1));
        if (s > vm) vm = s;
      },
      Kokkos::Max<double>(vmax));
  return count > 0 ? vmax : 0.0;
}

// Largest coordinate `axis` (0: x, 1: y) of the points' centres (m): the material's front along
// that axis (an output of every run); the lowest double with no points.
template <class ExecSpace, class PositionView>
double largest_coordinate(const PositionView& x, int count, int axis) {
  double most = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::largest_coordinate", range_policy<ExecSpace>(0, count),
      KOKKOS_LAMBDA(const int q, double& m) {
        if (x(q, axis) > m) m = x(q, axis);
      },
      Kokkos::Max<double>(most));
  return most;
}

// Largest V / V0 over the points, at least 1 (time_step.hpp); 1 with no points.
template <class ExecSpace, class VolumeView>
double largest_expansion(const VolumeView& volume, const VolumeView& volume0, int count) {
  double jmax = 1.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::largest_expansion", range_policy<ExecSpace>(0, count),
      KOKKOS_LAMBDA(const int q, double& jm) {
        const double J = volume(q) / volume0(q);
        if (J > jm) jm = J;
      },
      Kokkos::Max<double>(jmax));
  return jmax > 1.0 ? jmax : 1.0;
}

// Smallest point mass, kg/m; 0 with no points.
template <class ExecSpace, class MassView>
double lightest_mass(const MassView& mass, int count) {
  double mmin = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::lightest_point", range_policy<ExecSpace>(0, count),
      KOKKOS_LAMBDA(const int q, double& m) {
        if (mass(q) < m) m = mass(q);
      },
      Kokkos::Min<double>(mmin));
  return count > 0 ? mmin : 0.0;
}

}  // namespace lsi::mpm

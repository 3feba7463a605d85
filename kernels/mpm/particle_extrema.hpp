// Extrema over the material points that the solvers need once, at construction: the largest
// speed (the first time step) and the lightest point's mass (the small-mass threshold). Free
// functions rather than lambdas in the constructors: nvcc does not accept an extended
// __host__ __device__ lambda whose enclosing function is a constructor.
#pragma once
#include <Kokkos_Core.hpp>

#include "kernels/common/math.hpp"

namespace lsi::mpm {

// Largest |v| over the points of one velocity field (n x 2), m/s; 0 with no points.
template <class ExecSpace, class VelocityView>
double largest_speed(const VelocityView& v, int count) {
  double vmax = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::largest_speed", Kokkos::RangePolicy<ExecSpace>(0, count),
      KOKKOS_LAMBDA(const int q, double& vm) {
        const double s = math::sqrt(v(q, 0) * v(q, 0) + v(q, 1) * v(q, 1));
        if (s > vm) vm = s;
      },
      Kokkos::Max<double>(vmax));
  return count > 0 ? vmax : 0.0;
}

// Smallest point mass, kg/m; 0 with no points.
template <class ExecSpace, class MassView>
double lightest_mass(const MassView& mass, int count) {
  double mmin = 0.0;
  Kokkos::parallel_reduce(
      "lsi::mpm::lightest_point", Kokkos::RangePolicy<ExecSpace>(0, count),
      KOKKOS_LAMBDA(const int q, double& m) {
        if (mass(q) < m) m = mass(q);
      },
      Kokkos::Min<double>(mmin));
  return count > 0 ? mmin : 0.0;
}

}  // namespace lsi::mpm

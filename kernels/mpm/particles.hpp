// Material points as flat structure-of-arrays Views (no object per particle). 2D plane strain:
// the stress keeps sigma_zz. Units SI, per metre of out-of-plane width.
#pragma once
#include <Kokkos_Core.hpp>

namespace lsi::mpm {

enum StressComponent { XX = 0, YY = 1, XY = 2, ZZ = 3 };

template <class MemorySpace>
struct Particles {
  int count = 0;
  Kokkos::View<double* [2], MemorySpace> position;              // m
  Kokkos::View<double* [2], MemorySpace> velocity;              // m/s
  Kokkos::View<double* [2][2], MemorySpace> affine;             // APIC C = B D^-1, 1/s
  Kokkos::View<double* [2][2], MemorySpace> velocity_gradient;  // L = grad v of the last step, 1/s
  Kokkos::View<double* [4], MemorySpace> stress;                // Cauchy, Pa (tension positive)
  Kokkos::View<double*, MemorySpace> mass;                      // kg/m
  Kokkos::View<double*, MemorySpace> volume;                    // m^2 (current)
  Kokkos::View<double*, MemorySpace> volume0;                   // m^2 (initial)
  Kokkos::View<double*, MemorySpace> plastic_work;              // J/m dissipated (accumulated)
  Kokkos::View<double*, MemorySpace> deviatoric_strain;  // accumulated equivalent shear strain
  Kokkos::View<int*, MemorySpace> material;              // index into the material table

  Particles() = default;
  explicit Particles(int n) : count(n) {
    position = decltype(position)("p_position", n);
    velocity = decltype(velocity)("p_velocity", n);
    affine = decltype(affine)("p_affine", n);
    velocity_gradient = decltype(velocity_gradient)("p_velocity_gradient", n);
    stress = decltype(stress)("p_stress", n);
    mass = decltype(mass)("p_mass", n);
    volume = decltype(volume)("p_volume", n);
    volume0 = decltype(volume0)("p_volume0", n);
    plastic_work = decltype(plastic_work)("p_plastic_work", n);
    deviatoric_strain = decltype(deviatoric_strain)("p_deviatoric_strain", n);
    material = decltype(material)("p_material", n);
  }
};

}  // namespace lsi::mpm

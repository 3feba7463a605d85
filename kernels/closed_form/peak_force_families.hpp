// Literature peak-force families (the paper's introduction), force per metre normal to the face,
// with the user's coefficients. v_n = v0 sin(beta) as in the empirical model.
//   hydrostatic   F = k rho g h^2 / 2          (peak pressure k rho g h at the base, triangular)
//   hydrodynamic  F = alpha rho v_n^2 h        (pressure alpha rho v_n^2, uniform over h)
//   mixed         F = alpha rho v_n^2 h + k rho g h^2 / 2
// No named coefficient set is shipped: see docs/theory/models.md, "Literature peak-force families".
#pragma once
#include <Kokkos_Macros.hpp>

#include "kernels/common/constants.hpp"

namespace lsi {

KOKKOS_INLINE_FUNCTION double hydrostatic_peak_force(double k, double density, double thickness) {
  return 0.5 * k * density * gravity * thickness * thickness;
}
KOKKOS_INLINE_FUNCTION double hydrodynamic_peak_force(double alpha, double density,
                                                      double normal_velocity, double thickness) {
  return alpha * density * normal_velocity * normal_velocity * thickness;
}
KOKKOS_INLINE_FUNCTION double mixed_peak_force(double alpha, double k, double density,
                                               double normal_velocity, double thickness) {
  return hydrodynamic_peak_force(alpha, density, normal_velocity, thickness) +
         hydrostatic_peak_force(k, density, thickness);
}

}  // namespace lsi

// Isotropic linear elasticity in plane strain (eps_zz = 0): d(sigma) = lambda tr(d eps) I + 2 G d eps.
// Strain increment components: de[0] = d eps_xx, de[1] = d eps_yy, de[2] = d eps_xy (tensor).
#pragma once
#include "kernels/mpm/constitutive/material.hpp"

namespace lsi::mpm {

KOKKOS_INLINE_FUNCTION void elastic_increment(const PreparedMaterial& m, const double de[3],
                                              double s[4]) {
  const double G = m.shear_modulus, lam = m.lame_lambda;
  const double tr = de[0] + de[1];
  s[0] += lam * tr + 2.0 * G * de[0];
  s[1] += lam * tr + 2.0 * G * de[1];
  s[2] += 2.0 * G * de[2];
  s[3] += lam * tr;
}
KOKKOS_INLINE_FUNCTION void elastic_increment(const Material& m, const double de[3], double s[4]) {
  elastic_increment(PreparedMaterial(m), de, s);
}

// Elastic strain energy density 1/2 sigma : C^-1 : sigma (J/m^3), with C^-1 from E and nu.
KOKKOS_INLINE_FUNCTION double elastic_energy_density(const Material& m, const double s[4]) {
  const double E = m.young_modulus, nu = m.poisson_ratio;
  const double tr = s[0] + s[1] + s[3];
  const double ss = s[0] * s[0] + s[1] * s[1] + s[3] * s[3] + 2.0 * s[2] * s[2];
  return 0.5 * ((1.0 + nu) * ss - nu * tr * tr) / E;
}

}  // namespace lsi::mpm

// Material parameters of one body (plane strain), SI units. Elastic constants are derived once.
#pragma once
#include "kernels/common/math.hpp"

namespace lsi::mpm {

struct Material {
  enum class Model : int { LinearElastic = 0, MohrCoulomb = 1 };
  Model model = Model::LinearElastic;
  double density = 1000.0;          // kg/m^3
  double young_modulus = 1e6;       // Pa
  double poisson_ratio = 0.3;
  // Mohr-Coulomb only:
  double friction_angle = 0.0;      // phi, rad
  double dilatancy_angle = 0.0;     // psi, rad (non-associated when psi != phi)
  double cohesion = 0.0;            // c, Pa
  double tension_cutoff = 0.0;      // largest principal stress allowed, Pa (<= c cot(phi))

  KOKKOS_INLINE_FUNCTION double shear_modulus() const {
    return young_modulus / (2.0 * (1.0 + poisson_ratio));
  }
  KOKKOS_INLINE_FUNCTION double lame_lambda() const {
    return young_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
  }
  KOKKOS_INLINE_FUNCTION double bulk_modulus() const {
    return young_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio));
  }
  // P-wave speed sqrt((K + 4G/3) / rho): the fastest wave, which sets the time step (eq. 24 uses
  // sqrt(E/rho); the constrained modulus is the correct one in plane strain and is larger).
  KOKKOS_INLINE_FUNCTION double wave_speed() const {
    return math::sqrt((bulk_modulus() + 4.0 / 3.0 * shear_modulus()) / density);
  }
};

// A material with the constants the kernels need every step computed once (moduli, and the
// trigonometric functions of the Mohr-Coulomb angles).
struct PreparedMaterial {
  Material material;
  double shear_modulus = 0.0, lame_lambda = 0.0;
  double sin_phi = 0.0, cos_phi = 1.0, sin_psi = 0.0;
  // Cohesionless Mohr-Coulomb with no tensile strength: a point of it at zero stress that has
  // expanded is disconnected (stress_update.hpp).
  bool disconnects = false;

  PreparedMaterial() = default;
  KOKKOS_INLINE_FUNCTION explicit PreparedMaterial(const Material& m)
      : material(m),
        shear_modulus(m.shear_modulus()),
        lame_lambda(m.lame_lambda()),
        sin_phi(math::sin(m.friction_angle)),
        cos_phi(math::cos(m.friction_angle)),
        sin_psi(math::sin(m.dilatancy_angle)),
        disconnects(m.model == Material::Model::MohrCoulomb && m.cohesion == 0.0 &&
                    m.tension_cutoff <= 0.0) {}
};

}  // namespace lsi::mpm

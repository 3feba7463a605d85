// Material parameters of one body (plane strain), SI units. Elastic constants are derived once.
#pragma once
#include "kernels/common/math.hpp"

namespace lsi::mpm {

struct Material {
  enum class Model : int { LinearElastic = 0, MohrCoulomb = 1 };
  Model model = Model::LinearElastic;
  double density = 1000.0;     // kg/m^3
  double young_modulus = 1e6;  // Pa
  double poisson_ratio = 0.3;
  // Mohr-Coulomb only:
  double friction_angle = 0.0;   // phi, rad
  double dilatancy_angle = 0.0;  // psi, rad (non-associated when psi != phi)
  double cohesion = 0.0;         // c, Pa
  double tension_cutoff = 0.0;   // largest principal stress allowed, Pa (<= c cot(phi))
  // Rate-dependent friction, mu(I) (optional; constitutive/inertial_friction.hpp): sin(phi) rises
  // from sin(friction_angle) at rest to sin(limit_friction_angle) at large inertial numbers
  // I = gamma_dot d / sqrt(p / rho_s). Off while reference_inertial_number is 0.
  double limit_friction_angle = 0.0;       // phi_2, rad (>= friction_angle)
  double reference_inertial_number = 0.0;  // I0 (> 0 switches mu(I) on)
  double grain_diameter = 0.0;             // d, m
  double grain_density = 0.0;              // rho_s, kg/m^3 (of the grains, not the bulk)

  KOKKOS_INLINE_FUNCTION bool rate_dependent() const {
    return model == Model::MohrCoulomb && reference_inertial_number > 0.0;
  }

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
// trigonometric functions of the Mohr-Coulomb angles and the constants of its return mapping,
// constitutive/mohr_coulomb.hpp).
struct PreparedMaterial {
  Material material;
  double shear_modulus = 0.0, lame_lambda = 0.0;
  double sin_phi = 0.0, cos_phi = 1.0, sin_psi = 0.0;
  // Cohesionless Mohr-Coulomb with no tensile strength: a point of it at zero stress that has
  // expanded is disconnected (stress_update.hpp).
  bool disconnects = false;
  // The return mapping's constants (mohr_coulomb.hpp; SI units): the apex c cot(phi) (1e300
  // without friction), the cap of the principal stresses min(tension cut-off, apex), 1 / E, and
  // the elastic products of the yield and flow directions: A = n_f . D n_g of the main plane and
  // 1 / A, and B and 1 / (A^2 - B^2) of the two edges (upper: s1 = s2, lower: s2 = s3).
  double apex = 1e300, principal_cap = 1e300, inverse_young = 0.0;
  double main_plane = 0.0, inverse_main = 0.0, edge_upper = 0.0, edge_lower = 0.0;
  double inverse_det_upper = 0.0, inverse_det_lower = 0.0;

  // mu(I) (Material::rate_dependent): sin(phi_2) - sin(phi_s) and d sqrt(rho_s), so that
  // sin(phi) = sin_phi + inertial_rise I / (I0 + I) (constitutive/inertial_friction.hpp).
  bool rate_dependent = false;
  double inertial_rise = 0.0, inertial_length = 0.0;

  PreparedMaterial() = default;
  KOKKOS_INLINE_FUNCTION explicit PreparedMaterial(const Material& m)
      : material(m),
        shear_modulus(m.shear_modulus()),
        lame_lambda(m.lame_lambda()),
        sin_psi(math::sin(m.dilatancy_angle)),
        disconnects(m.model == Material::Model::MohrCoulomb && m.cohesion == 0.0 &&
                    m.tension_cutoff <= 0.0),
        rate_dependent(m.rate_dependent()) {
    inverse_young = 1.0 / m.young_modulus;
    set_friction(math::sin(m.friction_angle), math::cos(m.friction_angle));
    if (rate_dependent) {
      inertial_rise = math::sin(m.limit_friction_angle) - sin_phi;
      inertial_length = m.grain_diameter * math::sqrt(m.grain_density);
    }
  }

  // The constants that depend on the friction angle: set once for a rate-independent material,
  // per point and step for mu(I) (whose angle never falls below the static one, so the
  // dilatancy angle stays below it).
  KOKKOS_INLINE_FUNCTION void set_friction(const double sphi, const double cphi) {
    const double G = shear_modulus, L = lame_lambda, spsi = sin_psi;
    sin_phi = sphi;
    cos_phi = cphi;
    apex = sphi > 0.0 ? material.cohesion * cphi / sphi : 1e300;
    principal_cap = math::min(material.tension_cutoff, apex);
    const double A = 4.0 * L * sphi * spsi + 4.0 * G * (1.0 + sphi * spsi);
    main_plane = A;
    edge_upper = 4.0 * L * sphi * spsi + 2.0 * G * (1.0 - sphi) * (1.0 - spsi);
    edge_lower = 4.0 * L * sphi * spsi + 2.0 * G * (1.0 + sphi) * (1.0 + spsi);
    inverse_main = 1.0 / A;
    inverse_det_upper = 1.0 / (A * A - edge_upper * edge_upper);
    inverse_det_lower = 1.0 / (A * A - edge_lower * edge_lower);
  }
};

}  // namespace lsi::mpm

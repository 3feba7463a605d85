// The `inertial_friction` block of a Mohr-Coulomb material, in the scene's units: the mu(I)
// rate-dependent friction of kernels/mpm/constitutive/inertial_friction.hpp, for the landslide of
// an impact scene (landslide.material) and the named materials of an `mpm_case`
// (docs/reference/scene_schema.md; read by io/inertial_friction_parser.hpp).
#pragma once
#include <optional>

namespace lsi {

struct InertialFrictionInput {
  double limit_friction_angle_deg = 0.0;   // phi_2, reached at large inertial numbers
  double reference_inertial_number = 0.0;  // I0
  double grain_diameter_mm = 0.0;          // d
  double grain_density_kg_m3 = 0.0;        // rho_s, of the grains (not the bulk)
};

}  // namespace lsi

#include "model/mpm_case.hpp"
#include "kernels/common/math.hpp"

namespace lsi {

void set_inertial_friction(const InertialFrictionInput& in, mpm::Material& m) {
  constexpr double deg = math::pi() / 180.0;
  m.limit_friction_angle = deg * in.limit_friction_angle_deg;
  m.reference_inertial_number = in.reference_inertial_number;
  m.grain_diameter = 1e-3 * in.grain_diameter_mm;
  m.grain_density = in.grain_density_kg_m3;
}

}  // namespace lsi

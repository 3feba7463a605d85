// Reads the `inertial_friction` block of a material (one parser for impact and verification
// scenes).
#pragma once
#include <optional>

#include "io/json_fields.hpp"
#include "model/inertial_friction_input.hpp"

namespace lsi {

// Reads `material.inertial_friction` if present (all four keys required; unknown keys, values
// out of range and a limit angle below `static_angle_deg`, the material's friction_angle_deg,
// are InputErrors naming the field).
std::optional<InertialFrictionInput> parse_inertial_friction(
    const json_fields::ObjectReader& material, double static_angle_deg);

}  // namespace lsi

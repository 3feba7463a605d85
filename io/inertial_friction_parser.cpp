#include "io/inertial_friction_parser.hpp"

#include "io/json_fields.hpp"

namespace lsi {

std::optional<InertialFrictionInput> parse_inertial_friction(
    const json_fields::ObjectReader& material, double static_angle_deg) {
  namespace jf = json_fields;
  const auto f = material.optional_object("inertial_friction",
                                          {"limit_friction_angle_deg", "reference_inertial_number",
                                           "grain_diameter_mm", "grain_density_kg_m3"});
  if (!f) return std::nullopt;
  InertialFrictionInput in;
  in.limit_friction_angle_deg =
      f->number("limit_friction_angle_deg", jf::interval('[', 0, 90, ')', "deg"));
  if (in.limit_friction_angle_deg < static_angle_deg)
    f->fail_at("limit_friction_angle_deg",
               "must not be below friction_angle_deg (" + jf::format_number(static_angle_deg) +
                   ", the static angle): friction rises with the inertial number");
  in.reference_inertial_number = f->number("reference_inertial_number", jf::greater_than(0));
  in.grain_diameter_mm = f->number("grain_diameter_mm", jf::greater_than(0, "mm"));
  in.grain_density_kg_m3 = f->number("grain_density_kg_m3", jf::greater_than(0, "kg/m^3"));
  return in;
}

}  // namespace lsi

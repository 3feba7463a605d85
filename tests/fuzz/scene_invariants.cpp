#include "scene_invariants.hpp"

#include <climits>
#include <cmath>
#include <string>

#include "io/json_fields.hpp"
#include "fuzz_target.hpp"

namespace lsi::fuzz {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string show(const std::string& name, double v) {
  return name + " = " + json_fields::format_number(v);
}

void finite(const std::string& name, double v) {
  require(std::isfinite(v), show(name, v) + " is not finite");
}

void positive(const std::string& name, double v) {
  finite(name, v);
  require(v > 0, show(name, v) + " is not > 0");
}

void at_least(const std::string& name, double v, double lo) {
  finite(name, v);
  require(v >= lo, show(name, v) + " is not >= " + json_fields::format_number(lo));
}

// v in the interval `open` lo, hi `close` ('(' / '[' and ')' / ']').
void between(const std::string& name, double v, char open, double lo, double hi, char close) {
  finite(name, v);
  const bool above = open == '[' ? v >= lo : v > lo;
  const bool below = close == ']' ? v <= hi : v < hi;
  require(above && below, show(name, v) + " is not in " + open + json_fields::format_number(lo) +
                              ", " + json_fields::format_number(hi) + close);
}

void check_landslide(const SceneLandslide& l) {
  positive("landslide.thickness_m", l.thickness_m);
  positive("landslide.velocity_m_s", l.velocity_m_s);
  positive("landslide.density_kg_m3", l.density_kg_m3);
  at_least("landslide.base_friction", l.base_friction, 0);
  if (l.shape.kind == LandslideShape::Kind::FrontBodyTail) {
    between("landslide.shape.body_squares", l.shape.body_squares, '[', 0, 1000000, ']');
    require(l.shape.length_m == 0.0, "front-body-tail landslide with a length_m");
  } else {
    require(l.shape.kind == LandslideShape::Kind::Rectangle, "unknown landslide shape kind");
    positive("landslide.shape.length_m", l.shape.length_m);
    require(l.shape.body_squares == 0, "rectangular landslide with body_squares");
  }
  const LandslideMaterial& m = l.material;
  between("landslide.material.porosity", m.porosity, '(', 0, 1, ')');
  between("landslide.material.friction_angle_deg", m.friction_angle_deg, '[', 0, 90, ')');
  at_least("landslide.material.cohesion_kpa", m.cohesion_kpa, 0);
  positive("landslide.material.young_modulus_mpa", m.young_modulus_mpa);
  between("landslide.material.poisson_ratio", m.poisson_ratio, '(', -1, 0.5, ')');
  positive("landslide.material.hydraulic_conductivity_m_s", m.hydraulic_conductivity_m_s);
  positive("landslide.material.liquid_bulk_modulus_mpa", m.liquid_bulk_modulus_mpa);
  positive("landslide.material.liquid_viscosity_kpa_s", m.liquid_viscosity_kpa_s);
  if (const auto& f = m.inertial_friction) {
    between("landslide.material.inertial_friction.limit_friction_angle_deg",
            f->limit_friction_angle_deg, '[', m.friction_angle_deg, 90, ')');
    positive("landslide.material.inertial_friction.reference_inertial_number",
             f->reference_inertial_number);
    positive("landslide.material.inertial_friction.grain_diameter_mm", f->grain_diameter_mm);
    positive("landslide.material.inertial_friction.grain_density_kg_m3", f->grain_density_kg_m3);
  }
  // What the closed forms read: L1,0, the cross-section and the mass per metre.
  positive("landslide equivalent length L1,0 (m)", l.equivalent_length_m());
  positive("landslide cross-section area (m^2)", l.area_m2());
  positive("landslide mass per metre (kg/m)", l.mass_kg_per_m());
}

void check_barrier(const SceneBarrier& b) {
  positive("barrier.height_m", b.height_m);
  positive("barrier.base_width_m", b.base_width_m);
  between("barrier.top_width_m", b.top_width_m, '[', 0, b.base_width_m, ']');
  between("barrier.face_angle_deg", b.face_angle_deg, '(', 0, 90, ']');
  require(b.density_kg_m3.has_value() != b.mass_kg_per_m.has_value(),
          "barrier: not exactly one of density_kg_m3 and mass_kg_per_m");
  if (b.density_kg_m3) positive("barrier.density_kg_m3", *b.density_kg_m3);
  if (b.mass_kg_per_m) positive("barrier.mass_kg_per_m", *b.mass_kg_per_m);
  at_least("barrier.base_friction", b.base_friction, 0);
  at_least("barrier.face_friction", b.face_friction, 0);
  // The geometry check: the upstream face's run-out fits in B - b (1e-9 m tolerance).
  if (b.face_angle_deg != 90.0) {
    const double run_out = b.height_m / std::tan(b.face_angle_deg * kPi / 180.0);
    require(run_out <= b.base_width_m - b.top_width_m + 1e-9,
            show("barrier face run-out H / tan(beta)", run_out) + " exceeds B - b");
  }
  positive("barrier cross-section area (m^2)", b.area_m2());
  positive("barrier mass per metre (kg/m)", b.mass());
}

void check_methods(const SceneMethods& m) {
  require(m.empirical || m.analytical || m.literature || m.mpm, "a scene with no method");
  if (m.empirical) {
    positive("methods.empirical.a1", m.empirical->a1);
    between("methods.empirical.a2", m.empirical->a2, '[', -5, 5, ']');
    between("methods.empirical.tau", m.empirical->tau, '(', 0, 1, ')');
    at_least("methods.empirical.kappa", m.empirical->kappa, 0);
  }
  if (m.analytical) {
    if (m.analytical->lambda)
      between("methods.analytical.lambda", *m.analytical->lambda, '(', 0, 1, ']');
    if (m.analytical->tau) between("methods.analytical.tau", *m.analytical->tau, '(', 0, 1, ')');
  }
  if (m.literature) {
    const std::string& f = m.literature->family;
    require(f == "hydrostatic" || f == "hydrodynamic" || f == "mixed", "literature family " + f);
    require(m.literature->hydrostatic_k.has_value() == (f != "hydrodynamic"),
            "literature: hydrostatic_k present exactly when the family uses it");
    require(m.literature->hydrodynamic_alpha.has_value() == (f != "hydrostatic"),
            "literature: hydrodynamic_alpha present exactly when the family uses it");
    if (m.literature->hydrostatic_k)
      positive("methods.literature.hydrostatic_k", *m.literature->hydrostatic_k);
    if (m.literature->hydrodynamic_alpha)
      positive("methods.literature.hydrodynamic_alpha", *m.literature->hydrodynamic_alpha);
  }
  // m.mpm: checked as the impact case's settings (check_mpm_case), its defaults filled in.
}

void check_settings(const MpmSettings& s, MpmCaseKind kind) {
  positive("methods.mpm.cell_size_m", s.cell_size_m);
  const int n = static_cast<int>(std::lround(std::sqrt(s.particles_per_cell)));
  require(s.particles_per_cell >= 1 && s.particles_per_cell <= 64 && n * n == s.particles_per_cell,
          "methods.mpm.particles_per_cell = " + std::to_string(s.particles_per_cell) +
              " is not a perfect square in [1, 64]");
  between("methods.mpm.courant", s.courant, '(', 0, 10, ']');
  positive("methods.mpm.end_time_s", s.end_time_s);
  positive("methods.mpm.max_time_step_s", s.max_time_step_s);
  positive("methods.mpm.output_interval_s", s.output_interval_s);
  between("methods.mpm.flip_ratio", s.flip_ratio, '[', 0, 1, ']');
  between("methods.mpm.small_mass_fraction", s.small_mass_fraction, '[', 0, 0.1, ']');
  at_least("methods.mpm.snapshot_interval_s", s.snapshot_interval_s, 0);
  if (kind == MpmCaseKind::Verification) {
    require(s.end_time_given, "verification scene without end_time_s");
    require(!s.cell_pore_pressure, "verification scene with an impact-only key");
  }
  require(!s.cell_pore_pressure || s.saturated,
          "methods.mpm.pore_pressure \"cell\" on a dry scene");
}

void check_grid(const MpmCase& c) {
  for (int d = 0; d < 2; ++d) {
    finite("domain lower[" + std::to_string(d) + "]", c.lower[d]);
    finite("domain upper[" + std::to_string(d) + "]", c.upper[d]);
    require(c.lower[d] < c.upper[d], "empty domain in direction " + std::to_string(d));
    finite("gravity[" + std::to_string(d) + "]", c.gravity[d]);
  }
  // mpm::Grid: n = int((upper - lower) / dx + 0.5) + 1 nodes per direction, nx * ny as an int;
  // the points are at most particles_per_cell per cell. All must fit an int.
  const double dx = c.settings.cell_size_m;
  const double nx = std::floor((c.upper[0] - c.lower[0]) / dx + 0.5) + 1;
  const double ny = std::floor((c.upper[1] - c.lower[1]) / dx + 0.5) + 1;
  require(
      std::isfinite(nx) && std::isfinite(ny) && nx * ny * c.settings.particles_per_cell <= INT_MAX,
      "the MPM grid has " + json_fields::format_number(nx) + " x " +
          json_fields::format_number(ny) + " nodes (x " +
          std::to_string(c.settings.particles_per_cell) +
          " points per cell): more than the solver's int indices hold");
  const mpm::Wall* walls[] = {&c.walls.left, &c.walls.right, &c.walls.bottom, &c.walls.top};
  for (const mpm::Wall* w : walls) {
    if (!w->active) continue;
    finite("wall position_m", w->position);
    require(w->friction >= 0, show("wall friction", w->friction) + " (not >= 0)");
    finite("wall friction", w->friction);
  }
}

void check_material(const mpm::Material& m, MpmCaseKind kind) {
  positive("material density (kg/m^3)", m.density);
  positive("material Young's modulus (Pa)", m.young_modulus);
  between("material Poisson's ratio", m.poisson_ratio, '(', -1, 0.5, ')');
  if (m.model == mpm::Material::Model::MohrCoulomb) {
    between("material friction angle (rad)", m.friction_angle, '[', 0, kPi / 2, ')');
    between("material dilatancy angle (rad)", m.dilatancy_angle, '[', 0, m.friction_angle, ']');
    at_least("material cohesion (Pa)", m.cohesion, 0);
    at_least("material tension cut-off (Pa)", m.tension_cutoff, 0);
    if (m.rate_dependent()) {
      between("material limit friction angle (rad)", m.limit_friction_angle, '[', m.friction_angle,
              kPi / 2, ')');
      positive("material reference inertial number", m.reference_inertial_number);
      positive("material grain diameter (m)", m.grain_diameter);
      positive("material grain density (kg/m^3)", m.grain_density);
    }
  } else {
    require(kind == MpmCaseKind::Verification, "impact landslide that is not Mohr-Coulomb");
  }
}

void check_body(const mpm::BodySpec& b, const MpmCase& c) {
  require(b.material >= 0 && static_cast<std::size_t>(b.material) < c.materials.size(),
          "body material index " + std::to_string(b.material) + " out of range");
  require(b.polygon.size() >= 3, "a body polygon with fewer than 3 vertices");
  for (const auto& v : b.polygon)
    for (int d = 0; d < 2; ++d) {
      finite("body vertex", v[d]);
      require(v[d] >= c.lower[d] && v[d] <= c.upper[d],
              show("body vertex", v[d]) + " outside the domain");
    }
  finite("body velocity x", b.velocity[0]);
  finite("body velocity y", b.velocity[1]);
  require(
      b.points_per_cell_direction * b.points_per_cell_direction == c.settings.particles_per_cell,
      "points_per_cell_direction does not match particles_per_cell");
  require(b.geostatic_k0 == -1.0 || (std::isfinite(b.geostatic_k0) && b.geostatic_k0 >= 0),
          show("geostatic_k0", b.geostatic_k0) + " (not >= 0 or off)");
  finite("body surface_y", b.surface_y);
  finite("body gravity", b.gravity);
}

void check_impact(const MpmCase& c) {
  require(c.barrier.has_value(), "an impact case without a barrier");
  require(c.materials.size() == 1 && c.bodies.size() == 1,
          "an impact case with other than one body");
  const mpm::Barrier& b = *c.barrier;
  positive("MPM barrier height", b.shape.height);
  positive("MPM barrier base width", b.shape.base_width);
  at_least("MPM barrier top width", b.shape.top_width, 0);
  between("MPM barrier face angle (rad)", b.shape.face_angle, '(', 0, kPi / 2, ']');
  for (const auto& f : b.shape.face)
    for (int d = 0; d < 2; ++d) {
      finite("MPM barrier face point", f.point[d]);
      finite("MPM barrier face normal", f.normal[d]);
    }
  at_least("MPM barrier face friction", b.face_friction, 0);
  positive("MPM barrier mass (kg/m)", b.motion.mass);
  at_least("MPM barrier base friction", b.motion.base_friction, 0);
  positive("landslide initial kinetic energy (J/m)", c.landslide_initial_kinetic_energy);
  if (c.two_phase) {
    between("MPM porosity", c.two_phase->porosity, '(', 0, 1, ')');
    positive("MPM hydraulic conductivity (m/s)", c.two_phase->conductivity);
    positive("MPM liquid bulk modulus (Pa)", c.two_phase->liquid.bulk_modulus);
    positive("MPM liquid density", c.two_phase->liquid.density);
    require(c.materials[0].density > c.two_phase->liquid.density,
            show("MPM grain density", c.materials[0].density) + " not above the liquid's");
  }
}

}  // namespace

void check_scene(const Scene& scene) {
  require(!scene.name.empty(), "a scene with an empty name");
  require(scene.source.is_object(), "a scene whose source is not an object");
  check_landslide(scene.landslide);
  check_barrier(scene.barrier);
  check_methods(scene.methods);
}

void check_mpm_case(const MpmCase& c, MpmCaseKind kind) {
  require(!c.name.empty(), "an MPM case with an empty name");
  check_settings(c.settings, kind);
  check_grid(c);
  require(!c.materials.empty() && c.materials.size() == c.material_names.size(),
          "MPM materials and their names differ in number");
  for (const auto& m : c.materials) check_material(m, kind);
  require(!c.bodies.empty(), "an MPM case without bodies");
  for (const auto& b : c.bodies) check_body(b, c);
  if (kind == MpmCaseKind::Impact)
    check_impact(c);
  else
    require(!c.barrier && !c.two_phase, "a verification case with a barrier or two phases");
}

}  // namespace lsi::fuzz

#include "io/resolved_scene.hpp"

#include "kernels/closed_form/two_body_model.hpp"

namespace lsi {

using nlohmann::json;

json mpm_settings_json(const MpmSettings& s, bool impact) {
  json j;
  j["cell_size_m"] = s.cell_size_m;
  j["particles_per_cell"] = s.particles_per_cell;
  j["courant"] = s.courant;
  if (s.end_time_given) j["end_time_s"] = s.end_time_s;
  j["max_time_step_s"] = s.max_time_step_s;
  if (s.output_interval_s > 0) j["output_interval_s"] = s.output_interval_s;
  if (s.apic) {
    j["transfer"] = "apic";
  } else if (s.flip_ratio == 0.0) {
    j["transfer"] = "pic";
  } else {
    j["transfer"] = "flip";
    j["flip_ratio"] = s.flip_ratio;
  }
  j["scatter"] = s.atomic_scatter ? "atomic" : "duplicated";
  if (s.snapshot_interval_s > 0) j["snapshot_interval_s"] = s.snapshot_interval_s;
  // The two-phase solver has no small-mass threshold (the parser refuses the key there).
  if (!(impact && s.saturated)) j["small_mass_fraction"] = s.small_mass_fraction;
  j["transfer_dissipation"] = s.transfer_dissipation;
  if (impact) {
    j["phases"] = s.saturated ? "saturated" : "dry";
    if (s.saturated) {
      j["drag"] = s.semi_implicit_drag ? "semi-implicit" : "explicit";
      j["pore_pressure"] = s.cell_pore_pressure ? "cell" : "point";
      j["pore_pressure_output"] = s.cell_mean_pore_pressure_output ? "cell" : "point";
    }
    j["peak_force_window_s"] = s.peak_force_window_s;
    if (s.face_band_m > 0) j["face_band_m"] = s.face_band_m;
  } else if (s.wall_band_m > 0) {
    j["wall_band_m"] = s.wall_band_m;
  }
  return j;
}

namespace {

const char* barrier_model_name(BarrierModel m) {
  return m == BarrierModel::Momentum ? "momentum" : "paper";
}

json landslide_json(const SceneLandslide& l) {
  json shape;
  if (l.shape.kind == LandslideShape::Kind::Rectangle) {
    shape = {{"kind", "rectangle"}, {"length_m", l.shape.length_m}};
  } else {
    shape = {{"kind", "front-body-tail"}, {"body_squares", l.shape.body_squares}};
  }
  const LandslideMaterial& m = l.material;
  json material = {{"porosity", m.porosity},
                   {"friction_angle_deg", m.friction_angle_deg},
                   {"cohesion_kpa", m.cohesion_kpa},
                   {"young_modulus_mpa", m.young_modulus_mpa},
                   {"poisson_ratio", m.poisson_ratio},
                   {"hydraulic_conductivity_m_s", m.hydraulic_conductivity_m_s},
                   {"liquid_bulk_modulus_mpa", m.liquid_bulk_modulus_mpa},
                   {"liquid_viscosity_kpa_s", m.liquid_viscosity_kpa_s}};
  if (const auto& f = m.inertial_friction)
    material["inertial_friction"] = {{"limit_friction_angle_deg", f->limit_friction_angle_deg},
                                     {"reference_inertial_number", f->reference_inertial_number},
                                     {"grain_diameter_mm", f->grain_diameter_mm},
                                     {"grain_density_kg_m3", f->grain_density_kg_m3}};
  return {{"thickness_m", l.thickness_m},
          {"velocity_m_s", l.velocity_m_s},
          {"density_kg_m3", l.density_kg_m3},
          {"shape", shape},
          {"material", material},
          {"base_friction", l.base_friction}};
}

json barrier_json(const SceneBarrier& b) {
  json j = {{"height_m", b.height_m},
            {"base_width_m", b.base_width_m},
            {"top_width_m", b.top_width_m},
            {"face_angle_deg", b.face_angle_deg},
            {"base_friction", b.base_friction},
            {"face_friction", b.face_friction},
            {"fixed", b.fixed}};
  if (b.mass_kg_per_m)
    j["mass_kg_per_m"] = *b.mass_kg_per_m;
  else if (b.density_kg_m3)
    j["density_kg_m3"] = *b.density_kg_m3;
  return j;
}

}  // namespace

json resolved_scene_json(const Scene& scene, const MpmSettings* mpm_as_run) {
  json methods = json::object();
  const SceneMethods& m = scene.methods;
  if (m.empirical)
    methods["empirical"] = {{"a1", m.empirical->a1},
                            {"a2", m.empirical->a2},
                            {"tau", m.empirical->tau},
                            {"kappa", m.empirical->kappa},
                            {"barrier_model", barrier_model_name(m.empirical->barrier_model)}};
  if (m.analytical) {
    // The paper's calibrated pair for this barrier where the scene gives none (the
    // momentum-consistent barrier takes the fixed barrier's pulse: model/closed_form_methods).
    const bool momentum = m.analytical->barrier_model == BarrierModel::Momentum;
    const TwoBodyCoefficients c = default_two_body_coefficients(scene.barrier.fixed || momentum);
    methods["analytical"] = {{"lambda", m.analytical->lambda.value_or(c.lambda)},
                             {"tau", m.analytical->tau.value_or(c.tau)},
                             {"barrier_model", barrier_model_name(m.analytical->barrier_model)}};
  }
  if (m.literature) {
    json lit = {{"family", m.literature->family}};
    if (m.literature->hydrostatic_k) lit["hydrostatic_k"] = *m.literature->hydrostatic_k;
    if (m.literature->hydrodynamic_alpha)
      lit["hydrodynamic_alpha"] = *m.literature->hydrodynamic_alpha;
    methods["literature"] = lit;
  }
  if (mpm_as_run != nullptr)
    methods["mpm"] = mpm_settings_json(*mpm_as_run, /*impact=*/true);
  else if (m.mpm)
    methods["mpm"] = mpm_settings_json(*m.mpm, /*impact=*/true);
  return {{"name", scene.name},
          {"landslide", landslide_json(scene.landslide)},
          {"barrier", barrier_json(scene.barrier)},
          {"methods", methods}};
}

json resolved_mpm_case_json(const MpmCase& c) {
  json j = c.source;
  if (!j.is_object()) j = json::object();
  j["methods"]["mpm"] = mpm_settings_json(c.settings, /*impact=*/false);
  return j;
}

}  // namespace lsi

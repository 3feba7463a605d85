// Scene parser and validator. The schema is documented in docs/reference/scene_schema.md; keep the two in
// step (key names, ranges, defaults).
#include "io/scene_parser.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "io/inertial_friction_parser.hpp"
#include "io/json_fields.hpp"
#include "io/mpm_scene.hpp"
#include "kernels/common/math.hpp"
#include "sweeps/sampled_scene.hpp"

namespace lsi {

namespace {

using nlohmann::json;
using namespace json_fields;

// Tolerance of the face run-out check H / tan(beta) <= B - b (the sweep kernel's).
constexpr double kGeometryToleranceM = sweeps::face_run_out_tolerance_m;

const std::vector<std::string> kTopKeys = {"name", "landslide", "barrier", "methods"};
const std::vector<std::string> kLandslideKeys = {"thickness_m", "velocity_m_s", "density_kg_m3",
                                                 "shape",       "material",     "base_friction"};
const std::vector<std::string> kShapeKeys = {"kind", "body_squares", "length_m"};
const std::vector<std::string> kMaterialKeys = {"porosity",
                                                "friction_angle_deg",
                                                "cohesion_kpa",
                                                "young_modulus_mpa",
                                                "poisson_ratio",
                                                "hydraulic_conductivity_m_s",
                                                "liquid_bulk_modulus_mpa",
                                                "liquid_viscosity_kpa_s",
                                                "inertial_friction"};
const std::vector<std::string> kBarrierKeys = {"height_m",       "base_width_m",  "top_width_m",
                                               "face_angle_deg", "density_kg_m3", "mass_kg_per_m",
                                               "base_friction",  "face_friction", "fixed"};
const std::vector<std::string> kMethodKeys = {"empirical", "analytical", "literature", "mpm"};
const std::vector<std::string> kEmpiricalKeys = {"a1", "a2", "tau", "kappa", "barrier_model"};
const std::vector<std::string> kAnalyticalKeys = {"lambda", "tau", "barrier_model"};
const std::vector<std::string> kBarrierModels = {"paper", "momentum"};
const std::vector<std::string> kLiteratureKeys = {"family", "hydrostatic_k", "hydrodynamic_alpha"};
const std::vector<std::string> kLiteratureFamilies = {"hydrostatic", "hydrodynamic", "mixed"};

std::string format_rounded(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// The range of a scene key that studies may sample, from the one table the sweep kernel checks its
// samples against (sweeps/sampled_scene.hpp, scene_field_range).
namespace sf = sweeps;
Range range_of(sweeps::SceneField field, std::string unit = {}) {
  const sweeps::FieldRange f = sweeps::scene_field_range(field);
  Range r;
  if (std::isfinite(f.lo)) r.lo = Bound{f.lo, f.lo_closed, {}};
  if (std::isfinite(f.hi)) r.hi = Bound{f.hi, f.hi_closed, {}};
  r.unit = std::move(unit);
  return r;
}

LandslideShape parse_shape(const ObjectReader& landslide) {
  const ObjectReader r = landslide.object("shape", kShapeKeys);
  LandslideShape shape;
  const std::string kind = r.choice("kind", {"front-body-tail", "rectangle"});
  if (kind == "front-body-tail") {
    if (r.has("length_m")) {
      r.fail_at("length_m",
                "not allowed when kind = \"front-body-tail\" (allowed: kind, body_squares)");
    }
    shape.kind = LandslideShape::Kind::FrontBodyTail;
    shape.body_squares = static_cast<int>(r.integer("body_squares", range_of(sf::body_squares)));
    shape.length_m = 0.0;
  } else {
    if (r.has("body_squares")) {
      r.fail_at("body_squares", "not allowed when kind = \"rectangle\" (allowed: kind, length_m)");
    }
    shape.kind = LandslideShape::Kind::Rectangle;
    shape.body_squares = 0;
    shape.length_m = r.number("length_m", range_of(sf::length_m, "m"));
  }
  return shape;
}

LandslideMaterial parse_material(const ObjectReader& landslide) {
  LandslideMaterial m;  // defaults
  const std::optional<ObjectReader> r = landslide.optional_object("material", kMaterialKeys);
  if (!r) return m;
  m.porosity = r->number_or("porosity", m.porosity, range_of(sf::porosity));
  m.friction_angle_deg = r->number_or("friction_angle_deg", m.friction_angle_deg,
                                      range_of(sf::friction_angle_deg, "deg"));
  m.inertial_friction = parse_inertial_friction(*r, m.friction_angle_deg);
  m.cohesion_kpa = r->number_or("cohesion_kpa", m.cohesion_kpa, range_of(sf::cohesion_kpa, "kPa"));
  m.young_modulus_mpa = r->number_or("young_modulus_mpa", m.young_modulus_mpa,
                                     range_of(sf::young_modulus_mpa, "MPa"));
  m.poisson_ratio = r->number_or("poisson_ratio", m.poisson_ratio, range_of(sf::poisson_ratio));
  m.hydraulic_conductivity_m_s =
      r->number_or("hydraulic_conductivity_m_s", m.hydraulic_conductivity_m_s,
                   range_of(sf::hydraulic_conductivity_m_s, "m/s"));
  m.liquid_bulk_modulus_mpa = r->number_or("liquid_bulk_modulus_mpa", m.liquid_bulk_modulus_mpa,
                                           range_of(sf::liquid_bulk_modulus_mpa, "MPa"));
  m.liquid_viscosity_kpa_s = r->number_or("liquid_viscosity_kpa_s", m.liquid_viscosity_kpa_s,
                                          range_of(sf::liquid_viscosity_kpa_s, "kPa s"));
  return m;
}

SceneLandslide parse_landslide(const ObjectReader& root) {
  const ObjectReader r = root.object("landslide", kLandslideKeys);
  SceneLandslide s;
  s.thickness_m = r.number("thickness_m", range_of(sf::thickness_m, "m"));
  s.velocity_m_s = r.number("velocity_m_s", range_of(sf::velocity_m_s, "m/s"));
  s.density_kg_m3 = r.number("density_kg_m3", range_of(sf::density_kg_m3, "kg/m^3"));
  s.shape = parse_shape(r);
  s.material = parse_material(r);
  s.base_friction = r.number_or("base_friction", 0.0, range_of(sf::flow_base_friction));
  // Each value is in range, but their product may not be: L1,0 = (2 + i) h (or the rectangle's
  // length), the cross-section L1,0 h and the mass per metre rho_m L1,0 h overflow a double for
  // huge values (h = 1e308) and underflow to 0 for tiny ones; the methods need them finite.
  const double mass = s.mass_kg_per_m();
  if (!(std::isfinite(mass) && mass > 0)) {
    const bool rectangle = s.shape.kind == LandslideShape::Kind::Rectangle;
    fail(r.path() + ": thickness_m = " + format_number(s.thickness_m) +
         (rectangle ? ", shape.length_m = " + format_number(s.shape.length_m)
                    : ", shape.body_squares = " + std::to_string(s.shape.body_squares)) +
         ", density_kg_m3 = " + format_number(s.density_kg_m3) + " give a mass per metre " +
         (rectangle ? "rho_m L h" : "rho_m (2 + i) h^2") + " = " + format_number(mass) +
         " kg/m: must be finite and > 0");
  }
  return s;
}

SceneBarrier parse_barrier(const ObjectReader& root) {
  const ObjectReader r = root.object("barrier", kBarrierKeys);
  SceneBarrier b;
  b.height_m = r.number("height_m", range_of(sf::height_m, "m"));
  b.base_width_m = r.number("base_width_m", range_of(sf::base_width_m, "m"));
  const Range top_range{Bound{0.0, true, {}}, Bound{b.base_width_m, true, "base_width_m"}, "m"};
  b.top_width_m = r.number("top_width_m", top_range);
  b.face_angle_deg = r.number("face_angle_deg", range_of(sf::face_angle_deg, "deg"));

  // The upstream face runs out H / tan(beta) horizontally; it must fit in B - b.
  const double beta = math::degrees_to_radians(b.face_angle_deg);
  const double run_out = b.face_angle_deg == 90.0 ? 0.0 : b.height_m / std::tan(beta);
  const double room = b.base_width_m - b.top_width_m;
  if (run_out > room + kGeometryToleranceM) {
    const double min_angle_deg = std::atan2(b.height_m, room) * 180.0 / math::pi();
    r.fail_at("face_angle_deg",
              "the upstream face would run out H / tan(beta) = " + format_rounded(run_out) +
                  " m but base_width_m - top_width_m = " + format_rounded(room) +
                  " m (with height_m = " + format_number(b.height_m) +
                  " this needs face_angle_deg >= " + format_rounded(min_angle_deg) + ")");
  }

  // Each of H, B, b is in range, but the cross-section (B + b) H / 2 may overflow (or underflow).
  const double area = b.area_m2();
  if (!(std::isfinite(area) && area > 0)) {
    fail(r.path() + ": height_m = " + format_number(b.height_m) + ", base_width_m = " +
         format_number(b.base_width_m) + ", top_width_m = " + format_number(b.top_width_m) +
         " give a cross-section (B + b) H / 2 = " + format_number(area) +
         " m^2: must be finite and > 0");
  }

  const bool has_density = r.has("density_kg_m3");
  const bool has_mass = r.has("mass_kg_per_m");
  if (has_density && has_mass) {
    fail(r.path_of("density_kg_m3") + " = " + format_value(*r.find("density_kg_m3")) + " and " +
         r.path_of("mass_kg_per_m") + " = " + format_value(*r.find("mass_kg_per_m")) +
         ": give exactly one of density_kg_m3 (> 0, kg/m^3) and mass_kg_per_m (> 0, kg/m)");
  }
  if (!has_density && !has_mass) {
    fail(r.path_of("density_kg_m3") + " / " + r.path_of("mass_kg_per_m") +
         ": missing (required: exactly one of density_kg_m3 > 0, kg/m^3, and mass_kg_per_m > 0, "
         "kg/m)");
  }
  b.density_kg_m3 =
      r.optional_number("density_kg_m3", range_of(sf::barrier_density_kg_m3, "kg/m^3"));
  b.mass_kg_per_m = r.optional_number("mass_kg_per_m", range_of(sf::barrier_mass_kg_per_m, "kg/m"));
  if (b.density_kg_m3 && !(std::isfinite(b.mass()) && b.mass() > 0)) {
    r.fail_at("density_kg_m3", "with the cross-section (B + b) H / 2 = " + format_number(area) +
                                   " m^2 gives a mass per metre of " + format_number(b.mass()) +
                                   " kg/m: must be finite and > 0");
  }
  b.base_friction = r.number_or("base_friction", 0.5, range_of(sf::base_friction));
  b.face_friction = r.number_or("face_friction", 0.3, range_of(sf::face_friction));
  b.fixed = r.boolean_or("fixed", false);
  return b;
}

EmpiricalParameters parse_empirical(const ObjectReader& methods) {
  const ObjectReader r = methods.object("empirical", kEmpiricalKeys);
  EmpiricalParameters p;
  p.a1 = r.number_or("a1", p.a1, range_of(sf::empirical_a1));
  p.a2 = r.number_or("a2", p.a2, range_of(sf::empirical_a2));
  p.tau = r.number_or("tau", p.tau, range_of(sf::empirical_tau));
  p.kappa = r.number_or("kappa", p.kappa, range_of(sf::empirical_kappa));
  p.barrier_model = r.choice("barrier_model", kBarrierModels, std::string("paper")) == "momentum"
                        ? BarrierModel::Momentum
                        : BarrierModel::Paper;
  // The momentum-consistent barrier takes a pulse of destroyed momentum; a static residual load
  // after it is a different mechanism (docs/theory/models.md, "Momentum-consistent barrier").
  if (p.barrier_model == BarrierModel::Momentum && p.kappa > 0.0)
    r.fail_at("kappa",
              "must be 0 with \"barrier_model\": \"momentum\" (the static load after the "
              "pulse is not modelled there)");
  return p;
}

AnalyticalParameters parse_analytical(const ObjectReader& methods) {
  const ObjectReader r = methods.object("analytical", kAnalyticalKeys);
  AnalyticalParameters p;
  p.lambda = r.optional_number("lambda", range_of(sf::analytical_lambda));
  p.tau = r.optional_number("tau", range_of(sf::analytical_tau));
  p.barrier_model = r.choice("barrier_model", kBarrierModels, std::string("paper")) == "momentum"
                        ? BarrierModel::Momentum
                        : BarrierModel::Paper;
  return p;
}

LiteratureParameters parse_literature(const ObjectReader& methods) {
  const ObjectReader r = methods.object("literature", kLiteratureKeys);
  LiteratureParameters p;
  p.family = r.choice("family", kLiteratureFamilies, std::string("mixed"));
  p.hydrostatic_k = r.optional_number("hydrostatic_k", greater_than(0));
  p.hydrodynamic_alpha = r.optional_number("hydrodynamic_alpha", greater_than(0));

  const bool needs_k = p.family != "hydrodynamic";
  const bool needs_alpha = p.family != "hydrostatic";
  const std::string family = "family = \"" + p.family + "\"";
  // A coefficient the family does not use would be ignored silently: reject it.
  if (!needs_k && p.hydrostatic_k) r.fail_at("hydrostatic_k", "not used by " + family);
  if (!needs_alpha && p.hydrodynamic_alpha)
    r.fail_at("hydrodynamic_alpha", "not used by " + family);
  // No named coefficient set is shipped: the coefficients the family uses are always required.
  if (needs_k && !p.hydrostatic_k) r.fail_missing("hydrostatic_k", "number > 0 when " + family);
  if (needs_alpha && !p.hydrodynamic_alpha) {
    r.fail_missing("hydrodynamic_alpha", "number > 0 when " + family);
  }
  return p;
}

SceneMethods parse_methods(const ObjectReader& root) {
  SceneMethods m;
  if (!root.has("methods")) {
    m.empirical = EmpiricalParameters{};
    m.analytical = AnalyticalParameters{};
    return m;
  }
  const ObjectReader r = root.object("methods", kMethodKeys);
  if (r.json().empty()) {
    fail(r.path() + " = {}: no method selected (allowed: " + join(kMethodKeys) + ")");
  }
  if (r.has("empirical")) m.empirical = parse_empirical(r);
  if (r.has("analytical")) m.analytical = parse_analytical(r);
  if (r.has("literature")) m.literature = parse_literature(r);
  if (const json* mpm = r.find("mpm")) {
    if (!mpm->is_object()) r.fail_at("mpm", "must be an object");
    // Checked here whichever methods a command runs (`lsi run --methods analytical`, a sweep of
    // the closed forms): a wrong key or value of the block is an error even when the MPM does
    // not run. What needs the landslide and the barrier too (the cell size against the
    // thickness, the explicit drag's cost) is checked when the MPM case is built (mpm_impact.cpp).
    m.mpm = parse_mpm_settings(*mpm, r.path() + ".mpm", /*impact=*/true);
  }
  return m;
}

}  // namespace

Scene parse_scene(const json& j) {
  if (!j.is_object()) {
    fail(std::string("(top level) = ") + format_value(j) + ": a scene must be a JSON object");
  }
  const ObjectReader root(j, "", kTopKeys);
  Scene scene;
  scene.name = root.string("name");
  scene.landslide = parse_landslide(root);
  scene.barrier = parse_barrier(root);
  scene.methods = parse_methods(root);
  scene.source = j;
  return scene;
}

json read_scene_document(const std::string& path, const std::string& kind) {
  namespace fs = std::filesystem;
  // Messages are one line: a path with a control character (a study's "scene": "a\nb.json") is
  // shown quoted and escaped.
  const bool plain = std::none_of(path.begin(), path.end(), [](char c) {
    return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
  });
  const std::string shown =
      plain ? path : json(path).dump(-1, ' ', false, json::error_handler_t::replace);
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(shown + ": " + kind + " file not found");
  if (fs::is_directory(path, ec)) fail(shown + ": is a directory, not a " + kind + " file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(shown + ": cannot open " + kind + " file: " + std::strerror(errno));
  // Bounded: a device or pipe that never ends (/dev/zero) is refused, not read until memory runs
  // out. The largest shipped input is a few kilobytes.
  std::string text;
  char block[1 << 16];
  while (text.size() <= kMaxInputFileBytes && in.read(block, sizeof block).gcount() > 0)
    text.append(block, static_cast<std::size_t>(in.gcount()));
  if (in.bad()) fail(shown + ": cannot read " + kind + " file");
  if (text.size() > kMaxInputFileBytes)
    fail(shown + ": the " + kind + " file is larger than " +
         std::to_string(kMaxInputFileBytes >> 20) + " MiB (allowed: at most that; is it a " + kind +
         " file?)");

  const json j = parse_json_document(text, shown);
  if (!j.is_object()) {
    fail(shown + ": the top level must be a JSON object, got " + std::string(j.type_name()));
  }
  return j;
}

Scene load_scene(const std::string& path) { return parse_scene(read_scene_document(path)); }

}  // namespace lsi

#include "io/mpm_scene.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>

#include "io/inertial_friction_parser.hpp"
#include "io/json_fields.hpp"
#include "model/scene.hpp"
#include "kernels/mpm/solver.hpp"
#include "kernels/common/math.hpp"

namespace lsi {
namespace jf = json_fields;

namespace {
// Moduli and strengths are read in MPa or kPa and used in Pa: the value in Pa must stay a finite
// double (a Young's modulus of 1e308 MPa would be inf Pa).
jf::Range pascal_range(double lo, bool lo_inclusive, double factor, const std::string& unit) {
  double hi = std::numeric_limits<double>::max() / factor;
  while (!std::isfinite(hi * factor)) hi = std::nextafter(hi, 0.0);  // one step for 1e6
  return jf::Range{jf::Bound{lo, lo_inclusive, {}}, jf::Bound{hi, true, {}}, unit};
}
}  // namespace

MpmSettings parse_mpm_settings(const nlohmann::json& block, const std::string& path, bool impact) {
  std::vector<std::string> keys = {"cell_size_m",
                                   "particles_per_cell",
                                   "courant",
                                   "end_time_s",
                                   "max_time_step_s",
                                   "output_interval_s",
                                   "transfer",
                                   "flip_ratio",
                                   "scatter",
                                   "snapshot_interval_s",
                                   "small_mass_fraction",
                                   "transfer_dissipation"};
  if (impact)
    keys.insert(keys.end(), {"phases", "drag", "pore_pressure", "pore_pressure_output",
                             "peak_force_window_s", "face_band_m"});
  else
    keys.push_back("wall_band_m");
  if (impact && block.is_object() && block.contains("base_friction"))
    jf::fail(jf::join_path(path, "base_friction") + " = " +
             jf::format_value(block["base_friction"]) +
             ": moved to landslide.base_friction (the flow's friction on its base is the "
             "landslide's, read by the MPM and the momentum-consistent closed forms)");
  const jf::ObjectReader r(block, path, keys);
  MpmSettings s;
  s.cell_size_m = r.number("cell_size_m", jf::greater_than(0, "m"));
  s.particles_per_cell =
      static_cast<int>(r.number_or("particles_per_cell", 4, jf::interval('[', 1, 64, ']')));
  const int n = static_cast<int>(std::lround(std::sqrt(s.particles_per_cell)));
  if (n * n != s.particles_per_cell)
    r.fail_at("particles_per_cell",
              "must be a perfect square (1, 4, 9, 16, ...): n x n points per cell");
  s.courant = r.number_or("courant", 0.5, jf::interval('(', 0, 10, ']'));
  if (impact) {
    const auto t = r.optional_number("end_time_s", jf::greater_than(0, "s"));
    s.end_time_given = t.has_value();
    s.end_time_s = t.value_or(1.0);  // replaced by the impact scene's default
    s.saturated = r.choice("phases", {"saturated", "dry"}, std::string("saturated")) == "saturated";
    s.semi_implicit_drag = r.choice("drag", {"semi-implicit", "explicit"},
                                    std::string("semi-implicit")) == "semi-implicit";
    if (!s.saturated && r.has("drag"))
      r.fail_at("drag", "only used with \"phases\": \"saturated\"");
    // The pore pressure per point (the paper's single-point formulation) or projected to its
    // cell's mean every step (removes the volumetric locking next to walls: docs/theory/two_phase.md,
    // "The face jet").
    s.cell_pore_pressure =
        r.choice("pore_pressure", {"point", "cell"}, std::string("point")) == "cell";
    if (!s.saturated && r.has("pore_pressure"))
      r.fail_at("pore_pressure", "only used with \"phases\": \"saturated\"");
    s.cell_mean_pore_pressure_output =
        r.choice("pore_pressure_output", {"cell", "point"}, std::string("cell")) == "cell";
    if (!s.saturated && r.has("pore_pressure_output"))
      r.fail_at("pore_pressure_output", "only used with \"phases\": \"saturated\"");
    s.peak_force_window_s =
        r.number_or("peak_force_window_s", kDefaultPeakForceWindow, jf::greater_than(0, "s"));
    s.face_band_m = r.optional_number("face_band_m", jf::greater_than(0, "m")).value_or(0.0);
  } else {
    s.end_time_s = r.number("end_time_s", jf::greater_than(0, "s"));
    s.wall_band_m = r.optional_number("wall_band_m", jf::greater_than(0, "m")).value_or(0.0);
  }
  // Not below the solvers' smallest step, under which a run stops as "the time step collapsed".
  s.max_time_step_s =
      r.number_or("max_time_step_s", 1e300, jf::at_least(mpm::Settings{}.min_time_step, "s"));
  // Impact scenes get their default interval from the impact's time scale (impact_case): their
  // end time only bounds the run, which ends at rest.
  s.output_interval_s =
      r.number_or("output_interval_s", s.end_time_given && !impact ? s.end_time_s / 200 : 0.0,
                  jf::greater_than(0, "s"));
  if (s.end_time_given && !(s.end_time_s / 200 > 0))  // the default interval underflows to 0
    r.fail_at("end_time_s",
              "too small: the default output_interval_s = end_time_s / 200 is 0 "
              "(give output_interval_s > 0 s)");
  const std::string transfer = r.choice("transfer", {"apic", "flip", "pic"}, std::string("apic"));
  s.apic = transfer == "apic";
  if (transfer == "flip") {
    s.flip_ratio = r.number_or("flip_ratio", 0.99, jf::interval('[', 0, 1, ']'));
  } else if (transfer == "pic") {
    s.flip_ratio = 0.0;
  }
  if (transfer != "flip" && r.has("flip_ratio")) {
    r.fail_at("flip_ratio", "only used with \"transfer\": \"flip\"");
  }
  // The two-phase solver has no small-mass threshold: a saturated scene asking for one would
  // silently run without it.
  if (impact && s.saturated && r.has("small_mass_fraction"))
    r.fail_at("small_mass_fraction", "only used with \"phases\": \"dry\"");
  // Impact scenes (violent, splashing flows) default to the small-mass threshold; verification
  // scenes to exact momentum conservation.
  s.small_mass_fraction =
      r.number_or("small_mass_fraction", impact ? 1e-3 : 0.0, jf::interval('[', 0, 0.1, ']'));
  s.atomic_scatter =
      r.choice("scatter", {"duplicated", "atomic"}, std::string("duplicated")) == "atomic";
  s.snapshot_interval_s =
      r.optional_number("snapshot_interval_s", jf::greater_than(0, "s")).value_or(0.0);
  s.transfer_dissipation = r.boolean_or("transfer_dissipation", false);
  return s;
}

bool is_mpm_case(const nlohmann::json& scene) {
  return scene.is_object() && scene.contains("mpm_case");
}

namespace {
std::array<double, 2> pair_of(const jf::ObjectReader& r, const std::string& key,
                              const jf::Range& range) {
  const nlohmann::json* v = r.find(key);
  if (!v) r.fail_missing(key, "[number, number]");
  if (!v->is_array() || v->size() != 2) r.fail_at(key, "must be an array of two numbers");
  return {jf::check_number((*v)[0], r.path_of(key) + "[0]", range),
          jf::check_number((*v)[1], r.path_of(key) + "[1]", range)};
}

mpm::Wall parse_wall(const jf::ObjectReader& walls, const std::string& side) {
  mpm::Wall w;
  if (auto o = walls.optional_object(side, {"position_m", "friction", "no_slip", "fixed"})) {
    w.active = true;
    w.position = o->number("position_m", jf::any_number("m"));
    w.friction = o->number_or("friction", 0.0, jf::at_least(0));
    if (o->boolean_or("no_slip", false)) {
      if (o->has("friction")) o->fail_at("no_slip", "give either friction or no_slip");
      w.no_slip = true;
    }
    w.bilateral = o->boolean_or("fixed", false);
  }
  return w;
}
}  // namespace

MpmCase parse_mpm_case(const nlohmann::json& scene) {
  const jf::ObjectReader top(scene, "", {"name", "mpm_case", "methods"});
  MpmCase c;
  c.source = scene;
  c.name = top.string("name");
  const jf::ObjectReader m =
      top.object("mpm_case", {"domain_m", "gravity_m_s2", "walls", "materials", "bodies"});
  const jf::ObjectReader d = m.object("domain_m", {"x", "y"});
  const auto x = pair_of(d, "x", jf::any_number("m")), y = pair_of(d, "y", jf::any_number("m"));
  if (!(x[1] > x[0])) d.fail_at("x", "must be increasing [x_min, x_max]");
  if (!(y[1] > y[0])) d.fail_at("y", "must be increasing [y_min, y_max]");
  c.lower = {x[0], y[0]};
  c.upper = {x[1], y[1]};
  if (m.has("gravity_m_s2")) {
    c.gravity = pair_of(m, "gravity_m_s2", jf::any_number("m/s^2"));
    const double magnitude = std::hypot(c.gravity[0], c.gravity[1]);  // the bodies' geostatic g
    if (!std::isfinite(magnitude))
      m.fail_at("gravity_m_s2", "its magnitude sqrt(gx^2 + gy^2) = " +
                                    jf::format_number(magnitude) + " m/s^2: must be finite");
  }
  if (auto w = m.optional_object("walls", {"left", "right", "bottom", "top"})) {
    c.walls.left = parse_wall(*w, "left");
    c.walls.right = parse_wall(*w, "right");
    c.walls.bottom = parse_wall(*w, "bottom");
    c.walls.top = parse_wall(*w, "top");
  }
  const nlohmann::json* mats = m.find("materials");
  if (!mats) m.fail_missing("materials", "object of named materials");
  if (!mats->is_object() || mats->empty())
    m.fail_at("materials", "must be a non-empty object of named materials");
  constexpr double deg = math::pi() / 180.0;
  for (const auto& [name, value] : mats->items()) {
    const jf::ObjectReader r(
        value, m.path_of("materials") + "." + name,
        {"model", "density_kg_m3", "young_modulus_mpa", "poisson_ratio", "friction_angle_deg",
         "dilatancy_angle_deg", "cohesion_kpa", "tension_cutoff_kpa", "inertial_friction"});
    mpm::Material mat;
    const std::string model = r.choice("model", {"linear-elastic", "mohr-coulomb"});
    mat.model = model == "mohr-coulomb" ? mpm::Material::Model::MohrCoulomb
                                        : mpm::Material::Model::LinearElastic;
    mat.density = r.number("density_kg_m3", jf::greater_than(0, "kg/m^3"));
    mat.young_modulus = 1e6 * r.number("young_modulus_mpa", pascal_range(0, false, 1e6, "MPa"));
    mat.poisson_ratio = r.number("poisson_ratio", jf::interval('(', -1, 0.5, ')'));
    if (mat.model == mpm::Material::Model::MohrCoulomb) {
      const double friction_angle_deg =
          r.number("friction_angle_deg", jf::interval('[', 0, 90, ')'));
      mat.friction_angle = deg * friction_angle_deg;
      mat.dilatancy_angle =
          deg * r.number_or("dilatancy_angle_deg", 0.0, jf::interval('[', 0, 90, ')'));
      if (mat.dilatancy_angle > mat.friction_angle)
        r.fail_at("dilatancy_angle_deg", "must not exceed friction_angle_deg");
      mat.cohesion = 1e3 * r.number_or("cohesion_kpa", 0.0, pascal_range(0, true, 1e3, "kPa"));
      mat.tension_cutoff =
          1e3 * r.number_or("tension_cutoff_kpa", 0.0, pascal_range(0, true, 1e3, "kPa"));
      // mu(I): friction_angle_deg is then the static angle phi_s.
      if (const auto f = parse_inertial_friction(r, friction_angle_deg))
        set_inertial_friction(*f, mat);
    } else {
      for (const char* k : {"friction_angle_deg", "dilatancy_angle_deg", "cohesion_kpa",
                            "tension_cutoff_kpa", "inertial_friction"})
        if (r.has(k)) r.fail_at(k, "only used by \"model\": \"mohr-coulomb\"");
    }
    c.material_names.push_back(name);
    c.materials.push_back(mat);
  }
  const nlohmann::json* bodies = m.find("bodies");
  if (!bodies) m.fail_missing("bodies", "array of bodies");
  if (!bodies->is_array() || bodies->empty()) m.fail_at("bodies", "must be a non-empty array");
  const jf::ObjectReader methods = top.object("methods", {"mpm"});
  if (!methods.has("mpm")) methods.fail_missing("mpm", "the MPM settings");
  c.settings = parse_mpm_settings(methods.json().at("mpm"), "methods.mpm");
  {
    // The solver indexes grid nodes and material points with int (mpm::Grid: nx * ny): at most
    // INT_MAX / particles_per_cell nodes.
    const double dx = c.settings.cell_size_m;
    const double nx = std::floor((c.upper[0] - c.lower[0]) / dx + 0.5) + 1;
    const double ny = std::floor((c.upper[1] - c.lower[1]) / dx + 0.5) + 1;
    const double most = double(INT_MAX) / c.settings.particles_per_cell;
    if (!(nx * ny <= most))
      jf::fail("methods.mpm.cell_size_m = " + jf::format_number(dx) + ": the grid over " +
               d.path() + " would have " + jf::format_number(nx) + " x " + jf::format_number(ny) +
               " nodes, more than " + jf::format_number(std::floor(most)) +
               " (the solver's int indices / particles_per_cell): use a larger cell or a "
               "smaller domain");
    // At most kMaxWallBands bands along the longer side: each is a history of the result.
    constexpr double kMaxWallBands = 1000;
    const double longest = std::max(c.upper[0] - c.lower[0], c.upper[1] - c.lower[1]);
    const double band = c.settings.wall_band_m;
    if (band > 0.0 && band < longest / kMaxWallBands)
      jf::fail("methods.mpm.wall_band_m = " + jf::format_number(band) + ": must be >= " +
               jf::format_number(longest / kMaxWallBands) + " m (the domain's longer side / " +
               jf::format_number(kMaxWallBands) + ": at most that many bands along a wall)");
  }
  // Material points must stay more than one cell inside the grid (quadratic B-splines reach one
  // node beyond their cell): bodies start at least two cells inside the domain.
  const double pad = 2.0 * c.settings.cell_size_m;
  const int n = static_cast<int>(std::lround(std::sqrt(c.settings.particles_per_cell)));
  for (size_t i = 0; i < bodies->size(); ++i) {
    const jf::ObjectReader b((*bodies)[i], m.path_of("bodies") + "[" + std::to_string(i) + "]",
                             {"material", "polygon_m", "velocity_m_s", "geostatic_k0"});
    mpm::BodySpec body;
    const std::string mat = b.string("material");
    auto it = std::find(c.material_names.begin(), c.material_names.end(), mat);
    if (it == c.material_names.end())
      b.fail_at("material", "unknown material (defined: " + jf::join(c.material_names, true) + ")");
    body.material = static_cast<int>(it - c.material_names.begin());
    const nlohmann::json* poly = b.find("polygon_m");
    if (!poly) b.fail_missing("polygon_m", "array of >= 3 [x, y] vertices");
    if (!poly->is_array() || poly->size() < 3)
      b.fail_at("polygon_m", "must be an array of >= 3 [x, y] vertices");
    for (size_t k = 0; k < poly->size(); ++k) {
      const std::string p = b.path_of("polygon_m") + "[" + std::to_string(k) + "]";
      const auto& v = (*poly)[k];
      if (!v.is_array() || v.size() != 2)
        jf::fail(p + " = " + jf::format_value(v) + ": must be [x, y]");
      const double vx = jf::check_number(
          v[0], p + "[0]", jf::interval('[', c.lower[0] + pad, c.upper[0] - pad, ']', "m"));
      const double vy = jf::check_number(
          v[1], p + "[1]", jf::interval('[', c.lower[1] + pad, c.upper[1] - pad, ']', "m"));
      body.polygon.push_back({vx, vy});
    }
    if (b.has("velocity_m_s")) body.velocity = pair_of(b, "velocity_m_s", jf::any_number("m/s"));
    if (auto k0 = b.optional_number("geostatic_k0", jf::at_least(0))) {
      body.geostatic_k0 = *k0;
      double top_y = -1e300;
      for (const auto& v : body.polygon) top_y = std::max(top_y, v[1]);
      body.surface_y = top_y;
      body.gravity = std::hypot(c.gravity[0], c.gravity[1]);
    }
    body.points_per_cell_direction = n;
    c.bodies.push_back(body);
  }
  return c;
}

}  // namespace lsi

#include "drivers/mpm_impact.hpp"

#include <algorithm>
#include <cmath>

#include "drivers/json_fields.hpp"
#include "kernels/common/constants.hpp"

namespace lsi {
namespace {
using CaseTwoPhase = MpmCase::TwoPhase;
}  // namespace

std::vector<std::array<double, 2>> landslide_polygon(const SceneLandslide& l, double front_x,
                                                     double base_y) {
  const double h = l.thickness_m;
  if (l.shape.kind == LandslideShape::Kind::Rectangle) {
    const double L = l.shape.length_m;
    return {{front_x - L, base_y}, {front_x, base_y}, {front_x, base_y + h}, {front_x - L, base_y + h}};
  }
  // Front: 45 deg over h; body: i squares; tail: slope down over 3h. Area h^2 (1/2 + i + 3/2).
  const double body_end = front_x - h - l.shape.body_squares * h;
  return {{body_end - 3.0 * h, base_y}, {front_x, base_y}, {front_x - h, base_y + h},
          {body_end, base_y + h}};
}

MpmCase impact_case(const Scene& scene) {
  if (!scene.methods.mpm) throw InputError("methods.mpm: missing (the MPM settings)");
  MpmCase c;
  c.name = scene.name;
  c.source = scene.source;
  c.settings = parse_mpm_settings(*scene.methods.mpm, "methods.mpm", /*impact=*/true);
  const SceneLandslide& l = scene.landslide;
  const SceneBarrier& b = scene.barrier;
  const double dx = c.settings.cell_size_m, h = l.thickness_m, v0 = l.velocity_m_s;
  const double g = lsi::gravity;
  const double length = l.shape.kind == LandslideShape::Kind::Rectangle
                            ? l.shape.length_m
                            : (4.0 + l.shape.body_squares) * h;   // front h + body + tail 3h
  // At least 4 cells through the thickness, or the flow is not resolved at all.
  if (h < 4.0 * dx)
    throw InputError("methods.mpm.cell_size_m = " + json_fields::format_value(dx) +
                     ": must be <= landslide.thickness_m / 4 = " +
                     json_fields::format_value(h / 4) + " m (at least 4 cells through the flow)");
  if (!c.settings.end_time_given) {
    // The landslide passes in L / v0; twice that, plus the fall of the flow from the height of
    // the barrier, lets the barrier come to rest (the run ends earlier once all is at rest).
    c.settings.end_time_s = 2.0 * length / v0 + 2.0 * std::sqrt(2.0 * std::max(b.height_m, h) / g);
  }
  if (!(c.settings.output_interval_s > 0.0)) c.settings.output_interval_s = c.settings.end_time_s / 400;

  // Geometry: base y = 0, barrier toe x = 0, landslide front toe touching it.
  constexpr double kPi = 3.14159265358979323846;
  const double beta = b.face_angle_deg * kPi / 180.0;
  const double run_up = v0 * v0 / (2.0 * g);   // height a frictionless jet could climb
  const double pad = 3.0 * dx;
  const double x_left = -length - std::max(length, 4.0 * h) - pad;
  // Downstream: room for the barrier to slide (up to the landslide's length) and for what
  // overtops it; empty grid nodes cost little.
  const double x_right = b.base_width_m + length + 3.0 * std::max(b.height_m, h) + run_up + pad;
  const double y_top = std::max(b.height_m, h) + 2.0 * run_up + h + pad;
  auto snap_down = [&](double v) { return std::floor(v / dx) * dx; };
  auto snap_up = [&](double v) { return std::ceil(v / dx) * dx; };
  c.lower = {snap_down(x_left), -pad};
  c.upper = {snap_up(x_right), snap_up(y_top)};
  c.gravity = {0.0, -g};
  c.walls.bottom = {true, 0.0, c.settings.base_friction, false};
  // Upstream: a smooth wall far behind the tail. Downstream and above: no-slip walls that catch
  // what overtops or splashes (a smooth wall would send a fast overtopping flow up the wall and
  // out of the grid); they are far from the barrier and do not touch what acts on it.
  c.walls.left = {true, c.lower[0] + 2.0 * dx, 0.0, false};
  c.walls.right = {true, c.upper[0] - 4.0 * dx, -1.0, false};
  c.walls.top = {true, c.upper[1] - 4.0 * dx, -1.0, false};

  mpm::Material m;
  m.model = mpm::Material::Model::MohrCoulomb;
  m.density = l.density_kg_m3;   // dry: the mixture's density; saturated: the grains' (below)
  if (c.settings.saturated) {
    // Saturated mixture rho_m = (1 - n) rho_S + n rho_L with water (rho_L = 1000 kg/m^3).
    CaseTwoPhase tp;
    tp.liquid.density = 1000.0;
    tp.liquid.bulk_modulus = 1e6 * l.material.liquid_bulk_modulus_mpa;
    tp.porosity = l.material.porosity;
    tp.conductivity = l.material.hydraulic_conductivity_m_s;
    tp.drag = c.settings.semi_implicit_drag ? mpm::two_phase::Drag::SemiImplicit
                                            : mpm::two_phase::Drag::Explicit;
    const double n = tp.porosity;
    if (!(n > 0.0 && n < 1.0))
      throw InputError("landslide.material.porosity = " + json_fields::format_value(n) +
                       ": must be in (0, 1) for a saturated MPM landslide");
    const double rho_s = (l.density_kg_m3 - n * tp.liquid.density) / (1.0 - n);
    if (!(rho_s > tp.liquid.density))
      throw InputError("landslide.density_kg_m3 = " + json_fields::format_value(l.density_kg_m3) +
                       ": must exceed " + json_fields::format_value(tp.liquid.density) +
                       " kg/m^3 (water) for a saturated MPM landslide (grain density " +
                       json_fields::format_value(rho_s) + " kg/m^3 from porosity " +
                       json_fields::format_value(n) + ")");
    m.density = rho_s;
    c.two_phase = tp;
  }
  m.young_modulus = 1e6 * l.material.young_modulus_mpa;
  m.poisson_ratio = l.material.poisson_ratio;
  m.friction_angle = l.material.friction_angle_deg * kPi / 180.0;
  m.dilatancy_angle = 0.0;
  m.cohesion = 1e3 * l.material.cohesion_kpa;
  m.tension_cutoff = 0.0;
  c.materials = {m};
  c.material_names = {"landslide"};

  mpm::BodySpec body;
  body.polygon = landslide_polygon(l, 0.0, 0.0);
  body.material = 0;
  body.velocity = {v0, 0.0};
  body.points_per_cell_direction =
      static_cast<int>(std::lround(std::sqrt(c.settings.particles_per_cell)));
  body.geostatic_k0 = 1.0 - std::sin(m.friction_angle);   // Jaky, normally consolidated
  body.surface_from_polygon = true;
  body.gravity = g;
  c.bodies = {body};
  c.landslide_initial_kinetic_energy = 0.5 * l.mass_kg_per_m() * v0 * v0;

  mpm::Barrier barrier;
  barrier.shape = mpm::BarrierShape(0.0, 0.0, b.height_m, b.base_width_m, b.top_width_m, beta);
  barrier.face_friction = b.face_friction;
  barrier.fixed = b.fixed;
  barrier.motion.mass = b.mass();
  barrier.motion.base_friction = b.base_friction;
  barrier.motion.gravity = g;
  c.barrier = barrier;
  return c;
}

}  // namespace lsi

#include "model/mpm_impact.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "model/input_error.hpp"
#include "model/messages.hpp"
#include "kernels/common/constants.hpp"
#include "kernels/mpm/two_phase/two_phase_time_step.hpp"
#include "kernels/common/math.hpp"

namespace lsi {
namespace {

// The default end time of an impact, in impact time scales 2 L / v0 + 2 sqrt(2 max(H, h) / g):
// a bound, not the end (the run ends when all is at rest); a run that reaches it is reported as
// cut short (EndState).
constexpr double kEndTimeScales = 10.0;
// The most steps an explicit-drag run may need by its permeability limit alone.
constexpr double kMaxExplicitDragSteps = 1e8;
using CaseTwoPhase = MpmCase::TwoPhase;

// The solver indexes grid nodes and material points with int (mpm::Grid: nx * ny): the grid may
// hold at most INT_MAX / particles_per_cell nodes. A cell far too fine for the size of the flow
// (its length, its run-up v0^2 / 2g) and of the barrier would overflow them.
void check_grid_size(const MpmCase& c, double thickness) {
  const double dx = c.settings.cell_size_m;
  const double nx = std::floor((c.upper[0] - c.lower[0]) / dx + 0.5) + 1;
  const double ny = std::floor((c.upper[1] - c.lower[1]) / dx + 0.5) + 1;
  const double most = double(INT_MAX) / c.settings.particles_per_cell;
  if (nx * ny <= most) return;  // false for NaN too
  const double width = c.upper[0] - c.lower[0], height = c.upper[1] - c.lower[1];
  const double least = std::sqrt(width * height / most);  // cell size that would fit
  char domain[64], remedy[96];
  std::snprintf(domain, sizeof domain, "%.3g m x %.3g m", width, height);
  if (least <= thickness / 4)  // false for NaN and inf too
    std::snprintf(remedy, sizeof remedy, "needs cell_size_m >= about %.3g m", least);
  else if (std::isfinite(width * height))
    std::snprintf(remedy, sizeof remedy,
                  "too large for any cell_size_m <= landslide.thickness_m / 4");
  else  // a subnormal cell size: the domain snapped to it overflows
    std::snprintf(remedy, sizeof remedy, "use a larger cell_size_m");
  throw InputError("methods.mpm.cell_size_m = " + format_number(dx) +
                   ": the MPM grid over this scene's domain (" + domain +
                   ": the flow's length and run-up v0^2 / 2g, the barrier) would have " +
                   format_number(nx) + " x " + format_number(ny) + " nodes, more than " +
                   format_number(std::floor(most)) +
                   " (the solver's int indices / particles_per_cell): " + remedy);
}

// landslide.material.KEY, read in MPa or kPa (`factor` to Pa), in Pa: it must stay a finite double
// (a Young's modulus of 1e308 MPa would be inf Pa).
double in_pascal(double value, double factor, const std::string& key, const std::string& unit) {
  const double pa = value * factor;
  if (std::isfinite(pa)) return pa;
  double most = std::numeric_limits<double>::max() / factor;
  while (!std::isfinite(most * factor)) most = std::nextafter(most, 0.0);
  throw InputError("landslide.material." + key + " = " + format_number(value) +
                   ": must be <= " + format_number(most) + " (" + unit +
                   ") for the MPM (in Pa it overflows a double)");
}
}  // namespace

std::vector<std::array<double, 2>> landslide_polygon(const SceneLandslide& l, double front_x,
                                                     double base_y) {
  const double h = l.thickness_m;
  if (l.shape.kind == LandslideShape::Kind::Rectangle) {
    const double L = l.shape.length_m;
    return {
        {front_x - L, base_y}, {front_x, base_y}, {front_x, base_y + h}, {front_x - L, base_y + h}};
  }
  // Front: 45 deg over h; body: i squares; tail: slope down over 3h. Area h^2 (1/2 + i + 3/2).
  const double body_end = front_x - h - l.shape.body_squares * h;
  return {{body_end - 3.0 * h, base_y},
          {front_x, base_y},
          {front_x - h, base_y + h},
          {body_end, base_y + h}};
}

MpmCase impact_case(const Scene& scene) {
  if (!scene.methods.mpm) throw InputError("methods.mpm: missing (the MPM settings)");
  MpmCase c;
  c.name = scene.name;
  c.source = scene.source;
  c.settings = *scene.methods.mpm;
  const SceneLandslide& l = scene.landslide;
  const SceneBarrier& b = scene.barrier;
  const double dx = c.settings.cell_size_m, h = l.thickness_m, v0 = l.velocity_m_s;
  const double g = lsi::gravity;
  const double length = l.shape.kind == LandslideShape::Kind::Rectangle
                            ? l.shape.length_m
                            : (4.0 + l.shape.body_squares) * h;  // front h + body + tail 3h
  // At least 4 cells through the thickness, or the flow is not resolved at all.
  if (h < 4.0 * dx)
    throw InputError("methods.mpm.cell_size_m = " + format_value(dx) +
                     ": must be <= landslide.thickness_m / 4 = " + format_value(h / 4) +
                     " m (at least 4 cells through the flow)");
  // The run ends once the flow has lost all but 1e-3 of its kinetic energy, which must therefore
  // be finite and positive: v0 = 1e-300 m/s underflows it to 0, v0 = 1e200 m/s overflows it.
  const double kinetic_energy = 0.5 * l.mass_kg_per_m() * v0 * v0;
  if (!(std::isfinite(kinetic_energy) && kinetic_energy > 0))
    throw InputError(
        "landslide.velocity_m_s = " + format_number(v0) +
        ": the landslide's kinetic energy m1 v0^2 / 2 = " + format_number(kinetic_energy) +
        " J/m (m1 = " + format_number(l.mass_kg_per_m()) +
        " kg/m): must be finite and > 0 for the MPM impact");
  // The time scale of the impact: the landslide passes in L / v0; twice that, plus the fall of
  // the flow from the height of the barrier. The run ends once the landslide and the barrier are
  // at rest; the end time only bounds it, at kEndTimeScales of these (the retained flow may slump
  // back upstream for several of them).
  const double impact_time = 2.0 * length / v0 + 2.0 * std::sqrt(2.0 * std::max(b.height_m, h) / g);
  if (!c.settings.end_time_given) {
    c.settings.end_time_s = kEndTimeScales * impact_time;
    if (!std::isfinite(c.settings.end_time_s))
      throw InputError(
          "landslide.velocity_m_s = " + format_number(v0) + ": the MPM's default end time " +
          std::to_string(int(kEndTimeScales)) + " (2 L / v0 + 2 sqrt(2 max(H, h) / g)) = " +
          format_number(c.settings.end_time_s) + " s is not finite: give methods.mpm.end_time_s");
  }
  // The histories' default interval: 1/400 of the impact time scale, or 1/200 of a given end
  // time when that is shorter (a bound far beyond the impact keeps the impact's resolution, and
  // the test for rest, made at each output, stays as frequent).
  if (!(c.settings.output_interval_s > 0.0))
    c.settings.output_interval_s = c.settings.end_time_given
                                       ? std::min(impact_time / 400, c.settings.end_time_s / 200)
                                       : impact_time / 400;

  // Geometry: base y = 0, barrier toe x = 0, landslide front toe touching it.
  const double beta = math::degrees_to_radians(b.face_angle_deg);
  const double run_up = v0 * v0 / (2.0 * g);  // height a frictionless jet could climb
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
  check_grid_size(c, h);
  c.gravity = {0.0, -g};
  c.walls.bottom = {true, 0.0, l.base_friction, false};
  // Upstream: a smooth wall far behind the tail. Downstream and above: no-slip walls that catch
  // what overtops or splashes (a smooth wall would send a fast overtopping flow up the wall and
  // out of the grid); they are far from the barrier and do not touch what acts on it.
  c.walls.left = {true, c.lower[0] + 2.0 * dx, 0.0, false};
  c.walls.right = {true, c.upper[0] - 4.0 * dx, 0.0, false, /*no_slip=*/true};
  c.walls.top = {true, c.upper[1] - 4.0 * dx, 0.0, false, /*no_slip=*/true};

  mpm::Material m;
  m.model = mpm::Material::Model::MohrCoulomb;
  m.density = l.density_kg_m3;  // dry: the mixture's density; saturated: the grains' (below)
  if (c.settings.saturated) {
    // Saturated mixture rho_m = (1 - n) rho_S + n rho_L with water (rho_L = 1000 kg/m^3).
    CaseTwoPhase tp;
    tp.liquid.density = 1000.0;
    tp.liquid.bulk_modulus =
        in_pascal(l.material.liquid_bulk_modulus_mpa, 1e6, "liquid_bulk_modulus_mpa", "MPa");
    tp.porosity = l.material.porosity;
    tp.conductivity = l.material.hydraulic_conductivity_m_s;
    tp.drag = c.settings.semi_implicit_drag ? mpm::two_phase::Drag::SemiImplicit
                                            : mpm::two_phase::Drag::Explicit;
    const double n = tp.porosity;
    if (!(n > 0.0 && n < 1.0))
      throw InputError("landslide.material.porosity = " + format_value(n) +
                       ": must be in (0, 1) for a saturated MPM landslide");
    const double rho_s = (l.density_kg_m3 - n * tp.liquid.density) / (1.0 - n);
    if (!(rho_s > tp.liquid.density))
      throw InputError("landslide.density_kg_m3 = " + format_value(l.density_kg_m3) +
                       ": must exceed " + format_value(tp.liquid.density) +
                       " kg/m^3 (water) for a saturated MPM landslide (grain density " +
                       format_value(rho_s) + " kg/m^3 from porosity " + format_value(n) + ")");
    m.density = rho_s;
    c.two_phase = tp;
    if (!c.settings.semi_implicit_drag) {
      // The explicit drag's permeability limit alone fixes the number of steps. Beyond 1e8 steps
      // (days of run time at ~1e6 particle-updates/s) the run would look like a hang: refuse it
      // with the numbers and the remedy (docs/vv/stability.md, k = 1e-8 m/s needs 1.5e-9 s steps).
      const double dt_k = c.settings.courant * mpm::two_phase::permeability_time_step(
                                                   tp.conductivity, rho_s, n, tp.liquid.density, g);
      const double steps = c.settings.end_time_s / std::min(dt_k, c.settings.max_time_step_s);
      if (!(steps <= kMaxExplicitDragSteps))
        throw InputError(
            "methods.mpm.drag = \"explicit\": the permeability limit of "
            "landslide.material.hydraulic_conductivity_m_s = " +
            format_number(tp.conductivity) + " gives time steps of " + format_number(dt_k) +
            " s, " + format_number(std::ceil(steps)) +
            " steps for end_time_s = " + format_number(c.settings.end_time_s) +
            " s (allowed: at most 1e8): use \"drag\": \"semi-implicit\" (no "
            "permeability limit) or a shorter end_time_s");
    }
  }
  m.young_modulus = in_pascal(l.material.young_modulus_mpa, 1e6, "young_modulus_mpa", "MPa");
  m.poisson_ratio = l.material.poisson_ratio;
  m.friction_angle = math::degrees_to_radians(l.material.friction_angle_deg);
  m.dilatancy_angle = 0.0;
  m.cohesion = in_pascal(l.material.cohesion_kpa, 1e3, "cohesion_kpa", "kPa");
  m.tension_cutoff = 0.0;
  if (l.material.inertial_friction) set_inertial_friction(*l.material.inertial_friction, m);
  c.materials = {m};
  c.material_names = {"landslide"};

  mpm::BodySpec body;
  body.polygon = landslide_polygon(l, 0.0, 0.0);
  body.material = 0;
  body.velocity = {v0, 0.0};
  body.points_per_cell_direction =
      static_cast<int>(std::lround(std::sqrt(c.settings.particles_per_cell)));
  body.geostatic_k0 = 1.0 - std::sin(m.friction_angle);  // Jaky, normally consolidated
  body.surface_from_polygon = true;
  body.gravity = g;
  c.bodies = {body};
  c.landslide_initial_kinetic_energy = kinetic_energy;

  mpm::Barrier barrier;
  barrier.shape = mpm::BarrierShape(0.0, 0.0, b.height_m, b.base_width_m, b.top_width_m, beta);
  barrier.face_friction = b.face_friction;
  barrier.fixed = b.fixed;
  barrier.motion.mass = b.mass();
  barrier.motion.base_friction = b.base_friction;
  barrier.motion.gravity = g;
  // At most kMaxFaceBands bands: each is a history of the result.
  constexpr double kMaxFaceBands = 1000;
  if (c.settings.face_band_m > 0.0 && c.settings.face_band_m < b.height_m / kMaxFaceBands)
    throw InputError("methods.mpm.face_band_m = " + format_number(c.settings.face_band_m) +
                     ": must be >= barrier.height_m / " + format_number(kMaxFaceBands) + " = " +
                     format_number(b.height_m / kMaxFaceBands) + " (m)");
  barrier.face_band_height = c.settings.face_band_m;
  c.barrier = barrier;
  return c;
}

}  // namespace lsi

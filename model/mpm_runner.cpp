#include "model/mpm_runner.hpp"

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>

#include "model/impact_summary.hpp"
#include "kernels/closed_form/barrier_geometry.hpp"
#include "kernels/common/constants.hpp"
#include "kernels/common/execution_instance.hpp"
#include "model/mpm_footprint.hpp"
#include "model/progress.hpp"
#include "model/run_threads.hpp"
#include "kernels/mpm/momentum.hpp"
#include "kernels/mpm/overtopping.hpp"
#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"
#include "kernels/mpm/two_phase/face_pore_pressure.hpp"
#include "kernels/mpm/two_phase/two_phase_builder.hpp"
#include "kernels/mpm/two_phase/two_phase_solver.hpp"
#include "kernels/common/math.hpp"

namespace lsi {
namespace {

template <class Mem>
MpmSnapshot take_snapshot(const mpm::Particles<Mem>& p, double time) {
  MpmSnapshot s;
  s.time = time;
  s.count = p.count;
  const size_t n = static_cast<size_t>(p.count);
  const auto pos = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.position);
  const auto vel = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.velocity);
  const auto sig = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.stress);
  const auto eps = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.deviatoric_strain);
  const auto wp = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.plastic_work);
  const auto mass = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.mass);
  const auto vol = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.volume);
  const auto vol0 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.volume0);
  const auto mat = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.material);
  const auto ids = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.id);
  s.id.resize(n);
  s.material.resize(n);
  s.mass.resize(n);
  s.volume.resize(n);
  s.volumetric_strain.resize(n);
  s.position.resize(2 * n);
  s.velocity.resize(2 * n);
  s.stress.resize(4 * n);
  s.deviatoric_strain.resize(n);
  s.plastic_work.resize(n);
  // The solvers reorder their points (kernels/mpm/sort_points.hpp): point q is written at its id,
  // so that the snapshots list the points in the order they were created.
  for (size_t q = 0; q < n; ++q) {  // element access: correct whatever the views' layout
    const size_t i = static_cast<size_t>(ids(q));
    for (size_t k = 0; k < 2; ++k) {
      s.position[2 * i + k] = pos(q, k);
      s.velocity[2 * i + k] = vel(q, k);
    }
    for (size_t k = 0; k < 4; ++k) s.stress[4 * i + k] = sig(q, k);
    s.deviatoric_strain[i] = eps(q);
    s.plastic_work[i] = wp(q);
    s.id[i] = static_cast<std::int64_t>(i);
    s.material[i] = mat(q);
    s.mass[i] = mass(q);
    s.volume[i] = vol(q);
    s.volumetric_strain[i] = vol(q) / vol0(q) - 1.0;
  }
  return s;
}

// The barrier's safety under the MPM's loads, as the closed forms check it
// (kernels/closed_form/barrier_stability.hpp) but from the MPM's own histories: sliding,
// tan(delta_b) (W + F_down) / F_h with every face's load; overturning, the weight's restoring
// moment about the downstream toe over the upstream face's moment (from the face's load
// distribution). The resultant height of the face load at the largest moment is beside them,
// for the closed forms' assumption (half the flow's thickness).
void barrier_safety(MethodResult& r, const mpm::Barrier& b) {
  const auto& M = r.series.at("overturning_moment").values;
  const double W = b.motion.mass * lsi::gravity, mu = b.motion.base_friction;
  BarrierGeometry g;
  g.height = b.shape.height;
  g.base_width = b.shape.base_width;
  g.top_width = b.shape.top_width;
  g.face_angle = b.shape.face_angle;
  const double restoring = W * (g.base_width - g.centroid_x());
  double fs_slide = std::numeric_limits<double>::infinity(), fs_over = fs_slide;
  size_t worst = 0;
  for (size_t i = 0; i < r.time.size(); ++i) {
    if (r.force_horizontal[i] > 0.0)
      fs_slide = std::min(fs_slide, mu * (W + r.force_vertical[i]) / r.force_horizontal[i]);
    if (M[i] > 0.0 && restoring / M[i] < fs_over) {
      fs_over = restoring / M[i];
      worst = i;
    }
  }
  r.scalars.min_sliding_safety = fs_slide;
  r.scalars.min_overturning_safety = fs_over;
  r.scalars.overturning_moment_max = M.empty() ? 0.0 : M[worst];
  if (!M.empty())
    r.scalars.overturning_resultant_height = r.series.at("face_resultant_height").values[worst];
}

// The impact's scalar outputs (impact_summary.hpp): the peak force normal to the upstream face
// (the largest mean over one output interval) and its time (rise time), the peak averaged over
// the scene's window, the impact duration and the impulse delivered during it; the volumes at the
// end. The final displacement is the barrier's displacement where it has come to rest
// (has_final_displacement), NaN where the run was cut short while it still moved.
void summarize_impact(MethodResult& r, const mpm::Barrier& barrier, double window) {
  const size_t peak = std::max_element(r.force.begin(), r.force.end()) - r.force.begin();
  r.peak_force = r.force[peak];
  r.rise_time = r.time[peak];
  const ImpactDuration d = impact_duration(r.time, r.force);
  r.impact_duration = d.duration;
  r.final_displacement = has_final_displacement(r.end_state)
                             ? barrier.motion.displacement
                             : std::numeric_limits<double>::quiet_NaN();
  const WindowedPeak w = windowed_peak(r.time, r.force, window);
  r.scalars.peak_force_windowed = w.force;
  r.scalars.peak_force_windowed_time = w.time;
  r.scalars.peak_force_window = window;
  r.scalars.impulse = impulse_until(r.time, r.force, r.impact_duration);
  r.scalars.final_force = d.final_force;
  r.scalars.peak_force_horizontal =
      *std::max_element(r.force_horizontal.begin(), r.force_horizontal.end());
  r.scalars.displacement_at_end = barrier.motion.displacement;
  barrier_safety(r, barrier);
  const auto& over = r.series.at("overtopped_volume").values;
  r.scalars.overtopped_volume_m2 = over.back();
  r.scalars.overtopped_inside_barrier_m2 = r.series.at("overtopped_inside_barrier").values.back();
  r.scalars.retained_volume_m2 = r.series.at("retained_volume").values.back();
}

using Exec = Kokkos::DefaultExecutionSpace;
using Mem = Exec::memory_space;
using DrySolver = mpm::Solver<Exec>;
using SaturatedSolver = mpm::two_phase::TwoPhaseSolver<Exec>;

using AddSeries = std::function<void(const char*, const char*, const char*, double)>;

// With `transfer_dissipation` on: the kinetic energy lost in the grid transfers and the residual
// it leaves unexplained (kernels/mpm/transfer_dissipation.hpp).
template <class SolverT, class Report>
void add_transfer_dissipation(const SolverT& sv, const Report& e, const AddSeries& add) {
  if (!sv.settings().track_transfer_dissipation) return;
  add("transfer_dissipation", "J/m",
      "kinetic energy lost in the transfers between points and grid (accumulated)",
      sv.transfer_dissipation());
  add("energy_residual_unexplained", "1",
      "energy_residual with the transfer dissipation booked: (total - initial total + transfer "
      "dissipation) / the same scale",
      sv.energy_residual_unexplained(e));
}

// The energy histories of each kind of solver.
double add_energies(const DrySolver& sv, const AddSeries& add) {
  const mpm::EnergyReport e = sv.energy();
  add("kinetic_energy", "J/m", "kinetic energy of all material points", e.kinetic);
  add("elastic_energy", "J/m", "elastic strain energy", e.elastic);
  add("potential_energy", "J/m", "gravitational potential energy -m g.x", e.potential);
  add("plastic_dissipation", "J/m", "work dissipated by plastic flow (accumulated)", e.plastic);
  add("boundary_dissipation", "J/m", "work taken by the walls and the barrier (accumulated)",
      e.boundary);
  add("energy_residual", "1",
      "(total energy - initial total) / (largest kinetic + elastic + dissipated + "
      "|potential change|)",
      sv.energy_residual(e));
  add_transfer_dissipation(sv, e, add);
  return e.kinetic;
}

double add_energies(const SaturatedSolver& sv, const AddSeries& add) {
  const mpm::two_phase::TwoPhaseEnergyReport e = sv.energy();
  add("kinetic_energy", "J/m", "kinetic energy of both phases of all material points", e.kinetic());
  add("kinetic_energy_liquid", "J/m", "kinetic energy of the pore liquid", e.kinetic_liquid);
  add("elastic_energy", "J/m", "elastic strain energy of the skeleton (effective stress)",
      e.elastic);
  add("liquid_energy", "J/m", "energy stored in the compressed pore liquid", e.liquid);
  add("potential_energy", "J/m", "gravitational potential energy -m g.x", e.potential);
  add("plastic_dissipation", "J/m", "work dissipated by plastic flow (accumulated)", e.plastic);
  add("drag_dissipation", "J/m", "work dissipated by the Darcy drag (accumulated)", e.drag);
  add("viscous_dissipation", "J/m",
      "work dissipated by the artificial bulk viscosity of the mixture (accumulated)", e.viscous);
  add("boundary_dissipation", "J/m", "work taken by the walls and the barrier (accumulated)",
      e.boundary);
  add("energy_residual", "1",
      "(total energy - initial total) / (largest kinetic + stored + dissipated + |potential "
      "change|)",
      sv.energy_residual(e));
  add_transfer_dissipation(sv, e, add);
  return e.kinetic();
}

const mpm::Particles<Mem>& solid_points(const DrySolver& sv) { return sv.particles(); }
const mpm::Particles<Mem>& solid_points(const SaturatedSolver& sv) { return sv.particles().solid; }

// The pore pressure a saturated run reports (snapshots, the face): each point's cell mean by
// default (cell_mean_pore_pressure), or the points' own field. Filled on demand between steps.
class ReportedPorePressure {
 public:
  ReportedPorePressure(const SaturatedSolver& sv, bool cell_mean)
      : cell_mean_(cell_mean),
        field_(cell_mean
                   ? Kokkos::View<double*, Mem>("reported_pore_pressure", sv.particles().count)
                   : sv.particles().pore_pressure) {}
  Kokkos::View<const double*, Mem> of(const SaturatedSolver& sv) const {
    if (cell_mean_)
      mpm::two_phase::cell_mean_pore_pressure<Exec>(sv.particles(), sv.grid(), field_);
    return field_;
  }

 private:
  bool cell_mean_;
  Kokkos::View<double*, Mem> field_;
};

// Solver-specific outputs of a run: the reported pore pressure when saturated.
struct DryOutputs {
  DryOutputs(const DrySolver&, const MpmCase&) {}
};
struct SaturatedOutputs {
  SaturatedOutputs(const SaturatedSolver& sv, const MpmCase& c)
      : pressure(sv, c.settings.cell_mean_pore_pressure_output) {}
  ReportedPorePressure pressure;
};
DryOutputs outputs_for(const DrySolver& sv, const MpmCase& c) { return {sv, c}; }
SaturatedOutputs outputs_for(const SaturatedSolver& sv, const MpmCase& c) { return {sv, c}; }

MpmSnapshot snapshot_of(const DrySolver& sv, const DryOutputs&) {
  return take_snapshot(sv.particles(), sv.time());
}
MpmSnapshot snapshot_of(const SaturatedSolver& sv, const SaturatedOutputs& o) {
  MpmSnapshot s = take_snapshot(sv.particles().solid, sv.time());
  const auto p = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), o.pressure.of(sv));
  const auto ids =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), sv.particles().solid.id);
  s.pore_pressure.resize(p.extent(0));
  for (size_t q = 0; q < p.extent(0); ++q) s.pore_pressure[static_cast<size_t>(ids(q))] = p(q);
  return s;
}

// Momentum of the material (both phases when saturated), kg m/s per m.
void material_momentum(const DrySolver& sv, double p[2]) { mpm::momentum<Exec>(sv.particles(), p); }
void material_momentum(const SaturatedSolver& sv, double p[2]) {
  mpm::momentum<Exec>(sv.particles().solid, p);
  mpm::add_momentum<Exec>(sv.particles().liquid_mass, sv.particles().liquid_velocity, p);
}

// Impact outputs particular to a solver: the largest pore pressure on the face (saturated).
// What sets the dry solver's step besides the speeds: the largest expansion of a point
// (kernels/mpm/time_step.hpp). The saturated solver has it in the points' porosity.
void add_step_outputs(const DrySolver& sv, const AddSeries& add) {
  add("largest_expansion", "1",
      "largest V / V0 of a point, at least 1: the step uses the wave speed c0 sqrt of it",
      sv.max_expansion());
}
void add_step_outputs(const SaturatedSolver&, const AddSeries&) {}

void add_face_outputs(const DrySolver&, const DryOutputs&, const MpmCase&, const AddSeries&) {}
void add_face_outputs(const SaturatedSolver& sv, const SaturatedOutputs& o, const MpmCase& c,
                      const AddSeries& add) {
  add("face_pore_pressure_max", "Pa",
      c.settings.cell_mean_pore_pressure_output
          ? "largest pore pressure (cell mean) of the points within one cell in front of the "
            "upstream face"
          : "largest pore pressure of the points within one cell in front of the upstream face",
      mpm::two_phase::face_pore_pressure<Exec>(sv.particles(), o.pressure.of(sv), c.barrier->shape,
                                               sv.barrier().motion.displacement,
                                               c.settings.cell_size_m));
}

// Runs `solver` for the case: histories every output interval, impact outputs when the case
// has a barrier, snapshots, progress on a terminal, and the summary.
template <class SolverT>
void drive(const MpmCase& c, SolverT& solver, int particle_count, MpmOutcome& out) {
  MethodResult& r = out.result;
  r.method = "mpm";
  const AddSeries add = [&](const char* name, const char* units, const char* what, double v) {
    auto& sr = r.series[name];
    sr.units = units;
    sr.description = what;
    sr.values.push_back(v);
  };
  const double snap_dt = c.settings.snapshot_interval_s;
  long next_snap = 0;  // index of the next snapshot time, next_snap * snap_dt
  // Output times overshoot their targets by a step; this only absorbs the solver's rounding.
  const double snap_tol = 1e-9 * std::min(snap_dt, c.settings.output_interval_s);
  const double min_dt = solver.settings().min_time_step;
  Progress progress("mpm " + c.name, c.settings.end_time_s, c.barrier.has_value());
  const auto t0 = std::chrono::steady_clock::now();
  double io_seconds = 0.0, last_output = 0.0;
  bool barrier_left = false;
  const auto extra_outputs = outputs_for(solver, c);
  // Impact outputs: the contact forces as averages over each output interval (impulse /
  // interval: the force of one step rings with the contact of single node columns).
  // The face's band stresses of the latest output, for the snapshots.
  std::vector<double> face_pressure;
  auto impact_outputs = [&](double t, double kinetic) {
    double imp[3][2];
    solver.take_barrier_impulse(imp);
    const double span = t - last_output;
    const double inv = span > 0.0 ? 1.0 / span : 0.0;
    const auto& face = c.barrier->shape.face[mpm::BarrierShape::Upstream];
    const double fx = (imp[0][0] + imp[1][0] + imp[2][0]) * inv;
    const double fy = (imp[0][1] + imp[1][1] + imp[2][1]) * inv;
    const double fn = -(imp[0][0] * face.normal[0] + imp[0][1] * face.normal[1]) * inv;
    r.force.push_back(fn);
    r.force_horizontal.push_back(fx);
    r.force_vertical.push_back(-fy);
    const double moment = solver.take_barrier_moment_impulse() * inv;
    add("overturning_moment", "N m/m",
        "moment of the upstream face's load about the barrier's downstream toe (positive tips it "
        "downstream), from where along the face the flow pushes; mean over the output interval",
        moment);
    // Where on the face the upstream face's resultant acts: the height z at which its force
    // (F_x, F_y) gives that moment, z F_x - (z / tan(beta) - B) F_y = M (0 without a load).
    const auto& sh = c.barrier->shape;
    const double fx0 = imp[0][0] * inv, fy0 = imp[0][1] * inv;
    const double cot =
        std::fabs(sh.face_angle - 0.5 * math::pi()) < 1e-12 ? 0.0 : 1.0 / std::tan(sh.face_angle);
    const double denominator = fx0 - fy0 * cot;
    add("face_resultant_height", "m",
        "height above the base of the resultant of the upstream face's load (0 without a load)",
        denominator > 1e-9 * (std::fabs(fx0) + std::fabs(fy0)) && denominator > 0.0
            ? (moment - sh.base_width * fy0) / denominator
            : 0.0);
    // The face's normal stress in height bands (methods.mpm.face_band_m): each band's normal
    // force over its length along the face; the bands' forces add up to `force`.
    const std::vector<double> bands = solver.take_barrier_band_impulse();
    face_pressure.assign(bands.size(), 0.0);
    for (std::size_t k = 0; k < bands.size(); ++k) {
      const double band = c.barrier->face_band_height;
      const double z0 = k * band, z1 = std::min((k + 1) * band, sh.height);
      char name[48], what[160];
      std::snprintf(name, sizeof name, "face_pressure_band_%03zu", k);
      std::snprintf(what, sizeof what,
                    "mean normal stress on the upstream face between %.6g and %.6g m above the "
                    "base; mean over the output interval",
                    z0, z1);
      auto& sr = r.series[name];
      sr.units = "Pa";
      sr.description = what;
      sr.values.push_back(bands[k] * inv * std::sin(sh.face_angle) / (z1 - z0));
      face_pressure[k] = sr.values.back();
    }
    r.landslide_kinetic_energy.push_back(kinetic);
    const auto& motion = solver.barrier().motion;
    r.barrier_velocity.push_back(motion.velocity);
    r.barrier_displacement.push_back(motion.displacement);
    const mpm::OvertoppingReport o = mpm::overtopping<Exec>(
        solid_points(solver), c.barrier->shape.crest_upstream_x() + motion.displacement);
    add("overtopped_volume", "m^2", "volume of material downstream of the upstream crest corner",
        o.overtopped);
    add("retained_volume", "m^2", "volume of material upstream of the upstream crest corner",
        o.total - o.overtopped);
    const mpm::BarrierInterior in =
        mpm::barrier_interior<Exec>(solid_points(solver), c.barrier->shape, motion.displacement);
    add("barrier_interior_volume", "m^2",
        "volume of the material points whose centre lies inside the barrier (contact leak)",
        in.inside);
    add("overtopped_inside_barrier", "m^2",
        "the part of overtopped_volume whose centre lies inside the barrier (contact leak)",
        in.past_crest);
    add("barrier_friction_work", "J/m", "work dissipated by the barrier's base friction",
        motion.friction_work);
    add("barrier_kinetic_energy", "J/m", "kinetic energy of the barrier",
        0.5 * motion.mass * motion.velocity * motion.velocity);
    add_face_outputs(solver, extra_outputs, c, add);
    double p[2];
    material_momentum(solver, p);
    add("momentum_x", "kg m/s per m", "horizontal momentum of the material (both phases)", p[0]);
    last_output = t;
  };
  // The walls' normal stress in bands (methods.mpm.wall_band_m): each band's normal impulse over
  // the output interval and the band's length; a wall's bands add up to its normal reaction.
  double last_band_output = 0.0;
  auto wall_band_outputs = [&](double t) {
    const auto impulse = solver.take_wall_band_impulse();
    const double span = t - last_band_output;
    last_band_output = t;
    const auto& bands = solver.wall_bands();
    static const char* const side_names[4] = {"left", "right", "bottom", "top"};
    for (int side = 0; side < 4; ++side)
      for (std::size_t k = 0; k < impulse[side].size(); ++k) {
        const double s0 = bands.start[side] + k * bands.band;
        const double s1 = std::min(s0 + bands.band, bands.end[side]);
        char name[48], what[200];
        std::snprintf(name, sizeof name, "wall_pressure_%s_band_%03zu", side_names[side], k);
        std::snprintf(what, sizeof what,
                      "mean normal stress on the %s wall between %s %.6g and %.6g m; mean over "
                      "the output interval",
                      side_names[side], side < 2 ? "y =" : "x =", s0, s1);
        auto& sr = r.series[name];
        sr.units = "Pa";
        sr.description = what;
        sr.values.push_back(span > 0.0 ? impulse[side][k] / span / (s1 - s0) : 0.0);
      }
  };
  // What a snapshot takes from the run: the displacement since the first snapshot (t = 0), the
  // material names, the barrier where it stands.
  auto complete = [&](MpmSnapshot s) {
    const std::vector<double>& start =
        out.snapshots.empty() ? s.position : out.snapshots.front().position;
    s.displacement.resize(s.position.size());
    for (std::size_t i = 0; i < s.position.size(); ++i)
      s.displacement[i] = s.position[i] - start[i];
    s.material_names = c.material_names;
    if (c.barrier) {
      const auto& sh = c.barrier->shape;
      const double d = solver.barrier().motion.displacement;
      const auto& up = sh.face[mpm::BarrierShape::Crest].point;
      const auto& down = sh.face[mpm::BarrierShape::Downstream].point;
      s.barrier_outline = {sh.toe[0] + d,
                           sh.toe[1],
                           up[0] + d,
                           up[1],
                           down[0] + d,
                           down[1],
                           sh.toe[0] + sh.base_width + d,
                           sh.toe[1]};
      // The face's bands: their stresses at this output and their ends along the face.
      if (!face_pressure.empty()) {
        s.face_pressure = face_pressure;
        const double band = c.barrier->face_band_height;
        const double cot = std::fabs(sh.face_angle - 0.5 * math::pi()) < 1e-12
                               ? 0.0
                               : 1.0 / std::tan(sh.face_angle);
        for (std::size_t k = 0; k <= face_pressure.size(); ++k) {
          const double z = std::min(k * band, sh.height);
          s.face_band_points.push_back(sh.toe[0] + d + z * cot);
          s.face_band_points.push_back(sh.toe[1] + z);
        }
      }
    }
    return s;
  };
  const mpm::Status status = solver.run(
      c.settings.end_time_s, c.settings.output_interval_s,
      [&](const SolverT& sv) {
        const auto a = std::chrono::steady_clock::now();
        r.time.push_back(sv.time());
        const double kinetic = add_energies(sv, add);
        add("time_step", "s", "time step of the last step", sv.time_step());
        add_step_outputs(sv, add);
        add("wall_force_x", "N/m", "reaction of the walls on the material, x", -sv.wall_force()[0]);
        add("wall_force_y", "N/m", "reaction of the walls on the material, y", -sv.wall_force()[1]);
        wall_band_outputs(sv.time());
        add("front_x", "m", "largest x of a material point's centre",
            mpm::largest_coordinate<Exec>(solid_points(sv).position, solid_points(sv).count, 0));
        if (c.barrier) impact_outputs(sv.time(), kinetic);
        const double t = sv.time();
        // The solver's own test for its last output (Solver::run).
        const bool at_end =
            c.settings.end_time_s - t <= std::max(1e-12 * c.settings.end_time_s, min_dt);
        if (snap_dt > 0 &&
            (t + snap_tol >= next_snap * snap_dt || (at_end && out.snapshots.back().time < t))) {
          out.snapshots.push_back(complete(snapshot_of(sv, extra_outputs)));
          while (next_snap * snap_dt <= t + snap_tol) ++next_snap;
        }
        progress.update(t, sv.steps());
        io_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
      },
      [&](const SolverT& sv) {
        // An impact run may end once the landslide has (almost) stopped and the barrier too.
        if (!c.barrier || r.landslide_kinetic_energy.empty()) return false;
        const auto& motion = sv.barrier().motion;
        if (c.barrier->shape.toe[0] + c.barrier->shape.base_width + motion.displacement >
            c.walls.right.position - 2.0 * c.settings.cell_size_m) {
          barrier_left = true;  // it would push into the downstream wall
          return true;
        }
        return r.landslide_kinetic_energy.back() < 1e-3 * c.landslide_initial_kinetic_energy &&
               !motion.sliding();
      });
  progress.finish();
  // A run stopped because a point left the grid stops inside a step, before any output: its last
  // state goes into one more snapshot, to show where the point went (a non-finite state is not
  // written: snapshots never hold NaN).
  if (snap_dt > 0 && status == mpm::Status::LeftGrid &&
      (out.snapshots.empty() || out.snapshots.back().time < solver.time()))
    out.snapshots.push_back(complete(snapshot_of(solver, extra_outputs)));
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  RunStatistics& run = r.run.emplace();
  // A barrier pushed to the downstream end of the modelled domain is a physical outcome (far too
  // light a barrier), not an instability: the run ends there, cut short while it slides (end
  // state barrier_left_domain: no final displacement; the distance reached is displacement_at_end).
  run.finished = status == mpm::Status::Finished;
  r.status = barrier_left ? "finished: the barrier slid to the downstream end of the domain"
                          : mpm::describe(status);
  if (c.barrier) {
    // At rest: the landslide's kinetic energy below 1e-3 of its initial value and the barrier
    // not sliding (the test that ends the run early); else the run was cut short.
    const bool sliding = solver.barrier().motion.sliding();
    const bool landslide_rest =
        !r.landslide_kinetic_energy.empty() &&
        r.landslide_kinetic_energy.back() < 1e-3 * c.landslide_initial_kinetic_energy;
    r.end_state = !run.finished    ? EndState::Unstable
                  : barrier_left   ? EndState::BarrierLeftDomain
                  : sliding        ? EndState::EndTimeBarrierSliding
                  : landslide_rest ? EndState::AtRest
                                   : EndState::EndTimeLandslideMoving;
  }
  run.particles = particle_count;
  run.steps = static_cast<std::int64_t>(solver.steps());
  run.end_time = solver.time();
  run.solver_seconds = total - io_seconds;
  run.particle_updates_per_second =
      run.solver_seconds > 0 ? double(particle_count) * solver.steps() / run.solver_seconds : 0.0;
  run.saturated = c.two_phase.has_value();
  if constexpr (runs_on_host<Kokkos::DefaultExecutionSpace>)
    run.threads = instance_concurrency<Kokkos::DefaultExecutionSpace>();
  r.peak_force = r.rise_time = r.impact_duration = r.final_displacement =
      std::numeric_limits<double>::quiet_NaN();  // not an impact: not given
  // A run that stopped unstable keeps its histories up to the stop; its summary would look like
  // a result, so it is not given.
  if (c.barrier && !r.force.empty() && run.finished)
    summarize_impact(r, solver.barrier(), c.settings.peak_force_window_s);
  if (c.barrier) r.scalars.displacement_at_end = solver.barrier().motion.displacement;
  if (c.barrier && run.finished && r.series.count("face_pore_pressure_max")) {
    const auto& v = r.series.at("face_pore_pressure_max").values;
    r.scalars.face_pore_pressure_max_pa = *std::max_element(v.begin(), v.end());
  }
  if (c.barrier && r.series.count("barrier_interior_volume")) {
    const auto& v = r.series.at("barrier_interior_volume").values;
    r.scalars.barrier_interior_volume_max_m2 = *std::max_element(v.begin(), v.end());
  }
  if (r.series.count("transfer_dissipation")) {
    r.scalars.transfer_dissipation_j_per_m = r.series.at("transfer_dissipation").values.back();
    const auto& u = r.series.at("energy_residual_unexplained").values;
    r.scalars.energy_residual_unexplained_min = *std::min_element(u.begin(), u.end());
    r.scalars.energy_residual_unexplained_max = *std::max_element(u.begin(), u.end());
  }
}

}  // namespace

void ensure_kokkos() {
  if (Kokkos::is_initialized()) return;
  // Without a binding policy Kokkos warns on every start; threads that may migrate are the safe
  // default on a shared machine (set OMP_PROC_BIND=spread OMP_PLACES=threads for benchmarks).
  setenv("OMP_PROC_BIND", "false", /*overwrite=*/0);
  Kokkos::initialize();
  std::atexit([] {
    if (Kokkos::is_initialized()) Kokkos::finalize();
  });
}

namespace {
// The settings both solvers read (kernels/mpm/solver_settings.hpp), from the case's.
template <class SettingsT>
SettingsT solver_settings(const MpmCase& c) {
  SettingsT s;
  s.courant = c.settings.courant;
  s.max_time_step = c.settings.max_time_step_s;
  s.gravity[0] = c.gravity[0];
  s.gravity[1] = c.gravity[1];
  s.transfer = c.settings.apic ? mpm::Transfer::Apic : mpm::Transfer::FlipPic;
  s.flip_ratio = c.settings.flip_ratio;
  s.atomic_scatter = c.settings.atomic_scatter;
  s.track_transfer_dissipation = c.settings.transfer_dissipation;
  s.wall_band = c.settings.wall_band_m;
  return s;
}
}  // namespace

MpmOutcome run_mpm_case(const MpmCase& c) {
  check_mpm_fits(c);
  ensure_kokkos();
  MpmOutcome out;
  const double lo[2] = {c.lower[0], c.lower[1]}, hi[2] = {c.upper[0], c.upper[1]};
  const double dx = c.settings.cell_size_m;
  if (!c.two_phase) {  // dry: the single-phase path, no liquid field allocated
    mpm::Grid<Mem> grid(lo, hi, dx);
    auto particles = mpm::build_particles<Mem>(c.bodies, c.materials, lo, dx);
    auto s = solver_settings<mpm::Settings>(c);
    s.small_mass_fraction = c.settings.small_mass_fraction;
    // The solver inside: its per-thread grid copies for the threads the run takes
    // (model/run_threads.hpp).
    run_with_threads_for(particles.count, /*saturated=*/false, [&] {
      DrySolver solver(grid, particles, c.materials, c.walls, s);
      if (c.barrier) solver.attach_barrier(*c.barrier);
      drive(c, solver, particles.count, out);
    });
    return out;
  }
  namespace tp = mpm::two_phase;
  tp::TwoPhaseGrid<Mem> grid(lo, hi, dx);
  std::vector<tp::TwoPhaseBodySpec> bodies;
  for (const auto& b : c.bodies) {
    tp::TwoPhaseBodySpec t;
    static_cast<mpm::BodySpec&>(t) = b;
    t.porosity = c.two_phase->porosity;
    t.hydraulic_conductivity = c.two_phase->conductivity;
    bodies.push_back(t);
  }
  auto particles =
      tp::build_two_phase_particles<Mem>(bodies, c.materials, c.two_phase->liquid, lo, dx);
  auto s = solver_settings<tp::TwoPhaseSettings>(c);
  s.drag = c.two_phase->drag;
  s.cell_pore_pressure = c.settings.cell_pore_pressure;
  // The pore liquid does not penetrate the walls (impermeable) and slides along them freely.
  mpm::Boundaries liquid_walls = c.walls;
  for (mpm::Wall* w :
       {&liquid_walls.left, &liquid_walls.right, &liquid_walls.bottom, &liquid_walls.top}) {
    w->friction = 0.0;
    w->no_slip = false;
  }
  run_with_threads_for(particles.count, /*saturated=*/true, [&] {
    SaturatedSolver solver(grid, particles, c.materials, c.two_phase->liquid, c.walls, liquid_walls,
                           s);
    if (c.barrier) solver.attach_barrier(*c.barrier);
    drive(c, solver, particles.count, out);
  });
  return out;
}

}  // namespace lsi

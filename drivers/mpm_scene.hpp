// MPM input: the `methods.mpm` block (numerical settings, shared by every MPM scene) and the
// `mpm_case` block of a verification scene (domain, walls, materials, bodies), which replaces
// `landslide` and `barrier` for problems that are not a landslide hitting a barrier. Both are
// documented in docs/scene_schema.md.
#pragma once
#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "drivers/inertial_friction_input.hpp"
#include "kernels/mpm/barrier.hpp"
#include "kernels/mpm/boundary.hpp"
#include "kernels/mpm/constitutive/material.hpp"
#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/two_phase/two_phase_grid_update.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"

namespace lsi {

// The default window of the averaged peak force of an impact (s): the shortest window over which
// the reference study's peak force holds within a few percent between the two finest
// resolutions of its convergence study (docs/mpm.md, "Convergence of the impact outputs").
inline constexpr double kDefaultPeakForceWindow = 0.05;

struct MpmSettings {
  double cell_size_m = 0.1;
  int particles_per_cell = 4;         // a perfect square: n x n points per cell
  double courant = 0.5;
  double end_time_s = 1.0;
  double max_time_step_s = 1e300;
  double output_interval_s = 0.01;    // histories are sampled at this interval
  bool apic = true;                   // "transfer": "apic", or "flip" / "pic" (a FLIP/PIC blend)
  double flip_ratio = 0.99;           // "flip": flip_ratio in [0, 1]; "pic": 0
  bool atomic_scatter = false;        // "scatter": "duplicated" or "atomic"
  double small_mass_fraction = 0.0;   // dry solver: nodes below this x lightest point: no force
  double snapshot_interval_s = 0.0;   // particle snapshots every this many seconds; 0 = none
  bool transfer_dissipation = false;  // account the energy lost in the grid transfers
  // Impact scenes only (a landslide scene with `methods.mpm`):
  double base_friction = 0.0;         // Coulomb coefficient of the base under the flow (paper: 0)
  bool saturated = true;              // "phases": "saturated" (two-phase, the paper) or "dry"
  bool semi_implicit_drag = true;     // "drag": "semi-implicit" or "explicit" (saturated only)
  bool cell_pore_pressure = false;    // "pore_pressure": "point" or "cell" (saturated only)
  // "pore_pressure_output": the pore pressure of snapshots and of the face as its cell's mean
  // ("cell", the default: the per-point field rings from point to point) or per point ("point").
  bool cell_mean_pore_pressure_output = true;
  // The peak force is also reported as the largest mean over any window of this length (s);
  // 0 until the impact case sets its default (kDefaultPeakForceWindow).
  double peak_force_window_s = 0.0;
  bool end_time_given = true;         // false: end_time_s is the impact scene's default
};

struct MpmCase {
  std::string name;
  std::array<double, 2> lower{}, upper{};   // grid extent, m
  std::array<double, 2> gravity{0.0, -9.81};
  mpm::Boundaries walls;
  std::vector<std::string> material_names;
  std::vector<mpm::Material> materials;
  std::vector<mpm::BodySpec> bodies;
  MpmSettings settings;
  nlohmann::json source;
  // Impact scenes: the rigid barrier, and the scene's landslide (for the impact outputs).
  std::optional<mpm::Barrier> barrier;
  // Saturated (two-phase) cases: the bodies' porosity and conductivity, the liquid, the drag.
  struct TwoPhase {
    mpm::two_phase::Liquid liquid;
    double porosity = 0.5;
    double conductivity = 1e-4;   // k, m/s
    mpm::two_phase::Drag drag = mpm::two_phase::Drag::SemiImplicit;
  };
  std::optional<TwoPhase> two_phase;
  double landslide_initial_kinetic_energy = 0.0;   // J/m
};

// Parses `methods.mpm` (path names the block in messages). Throws InputError. `impact`: the block
// of a landslide scene (accepts base_friction; end_time_s optional).
MpmSettings parse_mpm_settings(const nlohmann::json& block, const std::string& path,
                               bool impact = false);
bool is_mpm_case(const nlohmann::json& scene);
// Parses a whole verification scene {"name", "mpm_case", "methods": {"mpm": {...}}}.
MpmCase parse_mpm_case(const nlohmann::json& scene);
// Switches mu(I) on in a Mohr-Coulomb material (SI units; its friction angle is the static one).
void set_inertial_friction(const InertialFrictionInput& in, mpm::Material& m);

}  // namespace lsi

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
#include "drivers/mpm_settings.hpp"
#include "kernels/mpm/barrier.hpp"
#include "kernels/mpm/boundary.hpp"
#include "kernels/mpm/constitutive/material.hpp"
#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/two_phase/two_phase_grid_update.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"

namespace lsi {

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
// of a landslide scene (accepts phases, drag, ...; end_time_s optional).
MpmSettings parse_mpm_settings(const nlohmann::json& block, const std::string& path,
                               bool impact = false);
bool is_mpm_case(const nlohmann::json& scene);
// Parses a whole verification scene {"name", "mpm_case", "methods": {"mpm": {...}}}.
MpmCase parse_mpm_case(const nlohmann::json& scene);
// Switches mu(I) on in a Mohr-Coulomb material (SI units; its friction angle is the static one).
void set_inertial_friction(const InertialFrictionInput& in, mpm::Material& m);

}  // namespace lsi

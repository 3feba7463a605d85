// An MPM case ready to run (model/mpm_runner.hpp): the grid's extent, walls, materials and
// bodies in SI units, the numerical settings, and for an impact the rigid barrier and the
// saturated mixture. Built from a verification scene (io/mpm_scene.hpp) or from a landslide
// scene (model/mpm_impact.hpp).
#pragma once
#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "kernels/mpm/barrier.hpp"
#include "kernels/mpm/boundary.hpp"
#include "kernels/mpm/constitutive/material.hpp"
#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/two_phase/two_phase_grid_update.hpp"
#include "kernels/mpm/two_phase/two_phase_particles.hpp"
#include "model/inertial_friction_input.hpp"
#include "model/mpm_settings.hpp"
#include "kernels/common/constants.hpp"

namespace lsi {

struct MpmCase {
  std::string name;
  std::array<double, 2> lower{}, upper{};  // grid extent, m
  std::array<double, 2> gravity{0.0, -lsi::gravity};
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
    double conductivity = 1e-4;  // k, m/s
    mpm::two_phase::Drag drag = mpm::two_phase::Drag::SemiImplicit;
  };
  std::optional<TwoPhase> two_phase;
  double landslide_initial_kinetic_energy = 0.0;  // J/m
};

// Switches mu(I) on in a Mohr-Coulomb material (SI units; its friction angle is the static one).
void set_inertial_friction(const InertialFrictionInput& in, mpm::Material& m);

}  // namespace lsi

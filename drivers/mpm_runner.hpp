// Runs an MPM verification case (drivers/mpm_scene.hpp) and returns its histories as the `mpm`
// method result: energies, energy residual, time step, wall reaction forces, status. Kokkos is
// started here, on first use only: closed-form work never starts it.
#pragma once
#include <string>

#include "drivers/method_result.hpp"
#include "drivers/mpm_scene.hpp"

namespace lsi {

struct MpmOutcome {
  MethodResult result;     // method "mpm"
  std::string status;      // "finished" or the reason the run stopped
  bool finished = false;
  long steps = 0;
  double wall_seconds = 0.0;         // solver loop only
  double particle_updates_per_second = 0.0;
  int particles = 0;
};

MpmOutcome run_mpm_case(const MpmCase& c);

}  // namespace lsi

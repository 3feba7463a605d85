// Runs an MPM verification case (io/mpm_scene.hpp) and returns its histories as the `mpm`
// method result: energies, energy residual, time step, wall reaction forces, status. Kokkos is
// started here, on first use only: closed-form work never starts it.
#pragma once
#include <cstdint>
#include <string>
#include <string>
#include <vector>

#include "model/method_result.hpp"
#include "model/mpm_case.hpp"

namespace lsi {

// The material points at one time, copied to the host; arrays are row-major, n = `count` rows.
struct MpmSnapshot {
  double time = 0.0;  // s, the solver time of the output it was taken at
  int count = 0;
  std::vector<std::int64_t> id;           // n, the point's index in the run's initial points
  std::vector<int> material;              // n, index into material_names
  std::vector<double> position;           // n x 2, m
  std::vector<double> displacement;       // n x 2, m, since the run's first snapshot (t = 0)
  std::vector<double> velocity;           // n x 2, m/s
  std::vector<double> stress;             // n x 4 (xx, yy, xy, zz), Pa, tension positive
  std::vector<double> mass;               // n, kg/m
  std::vector<double> volume;             // n, m^2 (current)
  std::vector<double> volumetric_strain;  // n, V / V0 - 1 (expansion positive)
  std::vector<double> deviatoric_strain;  // n, accumulated equivalent shear strain
  std::vector<double> plastic_work;       // n, J/m dissipated (accumulated)
  std::vector<double> pore_pressure;      // n, Pa, compression positive (saturated runs only)
  std::vector<std::string> material_names;
  // Impact scenes: the barrier's corners at the snapshot (upstream toe, upstream crest,
  // downstream crest, downstream toe), 4 x 2, m; empty without a barrier.
  std::vector<double> barrier_outline;
  // Impact scenes with face bands (methods.mpm.face_band_m): each band's mean normal stress over
  // the output interval that ends at the snapshot (Pa, as the histories face_pressure_band_k),
  // and the bands' ends along the upstream face where the barrier stands, from the toe up
  // ((bands + 1) x 2, m); empty otherwise.
  std::vector<double> face_pressure;
  std::vector<double> face_band_points;
};

struct MpmOutcome {
  // Method "mpm"; its status is "finished" or the reason the run stopped, its run statistics
  // are always given.
  MethodResult result;
  const RunStatistics& run() const { return *result.run; }
  bool finished() const { return result.run->finished; }
  const std::string& status() const { return result.status; }
  // Taken only with settings.snapshot_interval_s > 0: at t = 0, then at the first output time
  // that reaches each further multiple of the interval (outputs are not aligned to it, so a
  // snapshot time may lie up to one time step past the multiple), and at the end of the run.
  std::vector<MpmSnapshot> snapshots;
};

MpmOutcome run_mpm_case(const MpmCase& c);

// Starts Kokkos once (finalised at exit); what every Kokkos user in the driver calls first.
void ensure_kokkos();

}  // namespace lsi

// The scalar outputs of a design method beside its four summaries (peak force, rise time, impact
// duration, final displacement), typed, and the one table that names them in result files,
// reports and summaries. SI units, per metre of barrier width.
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lsi {

// An empty value: not given by this method for this scene (a barrier that never moves has no
// start time; the closed forms have no overtopped volume).
struct ResultScalars {
  using Value = std::optional<double>;

  // The load (every method).
  Value peak_force_horizontal;  // N/m, horizontal component of the peak
  Value impulse;                // N s/m, the force's impulse during the impact
  // The barrier's motion (closed forms with a free barrier).
  Value barrier_start_time;          // s, when it starts sliding; empty if it never does
  Value barrier_stop_time;           // s, when it stops; +inf if it never does
  Value largest_barrier_velocity;    // m/s (momentum-consistent barrier)
  Value flow_friction_deceleration;  // m/s^2, of the flow on its base (momentum-consistent)
  // The barrier's safety under the load history.
  Value min_sliding_safety;            // -, +inf for a load that cannot make it slide
  Value min_overturning_safety;        // -, +inf for a load that cannot tip it
  Value overturning_resultant_height;  // m, of the face load at the largest moment
  Value overturning_moment_max;        // N m/m, about the downstream toe (MPM)
  // The empirical model.
  Value froude_number;       // -
  Value alpha;               // -, dynamic coefficient a1 Fr^a2
  Value normal_velocity;     // m/s, the flow's velocity normal to the face
  Value peak_force_dynamic;  // N/m
  Value peak_force_static;   // N/m
  Value landslide_mass;      // kg/m
  // The two-body model.
  Value lambda;           // -, s1,max / L1,0
  Value tau;              // -, T1 / T2
  Value reduced_mass;     // kg/m
  Value max_shortening;   // m, s1,max
  Value K1;               // N s/m^2 (kg/s per metre of width)
  Value q1;               // N/m^1.5 (kg m^0.5/s^2 per metre of width)
  Value common_velocity;  // m/s
  // Literature peak-force families.
  Value hydrostatic_k;       // -
  Value hydrodynamic_alpha;  // -
  // An MPM impact.
  Value peak_force_windowed;              // N/m, the largest mean over the averaging window
  Value peak_force_windowed_time;         // s, the window's centre
  Value peak_force_window;                // s, the window
  Value final_force;                      // N/m, the force left after the impact
  Value displacement_at_end;              // m, the barrier's displacement when the run ended
  Value overtopped_volume_m2;             // m^2/m, landslide beyond the barrier's crest at the end
  Value overtopped_inside_barrier_m2;     // m^2/m, of it inside the barrier (the contact's leak)
  Value retained_volume_m2;               // m^2/m, upstream of the barrier at the end
  Value face_pore_pressure_max_pa;        // Pa, largest pore pressure on the face
  Value barrier_interior_volume_max_m2;   // m^2/m, largest landslide volume inside the barrier
  Value transfer_dissipation_j_per_m;     // J/m, kinetic energy lost in the grid transfers
  Value energy_residual_unexplained_min;  // -, of the energy balance, relative
  Value energy_residual_unexplained_max;  // -
};

// A simulated run's statistics (the MPM).
struct RunStatistics {
  std::int64_t particles = 0;
  std::int64_t steps = 0;
  double end_time = 0.0;        // s, simulated time reached
  bool finished = false;        // false: stopped unstable
  double solver_seconds = 0.0;  // s, wall time without output
  double particle_updates_per_second = 0.0;
  bool saturated = false;  // two-phase
  int threads = 0;         // host threads the kernels ran on (model/run_threads.hpp); 0: a device
};

// The error bars a grid-convergence study gives the MPM's outputs: for each output (named as in
// result files), its spread between the base and the finer resolution and whether it converged.
struct ErrorBar {
  double spread = 0.0;
  bool converged = false;
};
struct ConvergenceBars {
  int finer_cells = 0;         // cells through the thickness of the finer runs
  double finer_courant = 0.0;  // Courant number of the finer-step runs
  std::map<std::string, ErrorBar> outputs;
};

// One row of the table that names the scalars.
struct ScalarField {
  const char* name;   // in result files and summaries
  const char* units;  // "1" for a pure number
  std::optional<double> ResultScalars::*member;
  const char* description;
};
const std::vector<ScalarField>& scalar_fields();
const ScalarField* find_scalar_field(std::string_view name);

// How a scalar is stored: a real number, a count (an integer) or a flag (a boolean).
enum class ScalarKind { Real, Count, Flag };

// One scalar of a result with what a result file stores beside its value.
struct DescribedScalar {
  std::string name;
  double value = 0.0;
  std::string units;  // "1" for a pure number, a count or a flag
  std::string description;
  ScalarKind kind = ScalarKind::Real;
};

struct MethodResult;
// Every scalar a result gives beside the four summaries, by its file name, in one order: the
// ResultScalars (those given), the run statistics and the error bars (`<output>_spread`,
// `<output>_converged`, `convergence_finer_cells`, `convergence_finer_courant`). What summaries
// list.
std::vector<std::pair<std::string, double>> named_scalars(const MethodResult& r);
// Every scalar a result gives, described: the four summaries (those given, i.e. not NaN), then
// those of named_scalars in its order. What result files store, each with its units.
std::vector<DescribedScalar> described_scalars(const MethodResult& r);
// The units of a scalar by name (the four summaries, ResultScalars, run statistics); "" for a
// name it does not know.
std::string scalar_units(std::string_view name);
// Sets the scalar of that name (as named_scalars gives it); false for a name it does not know.
bool set_named_scalar(MethodResult& r, const std::string& name, double value);
// One scalar by name (the summaries, ResultScalars, run statistics); NaN where not given.
double scalar_by_name(const MethodResult& r, const std::string& name);

}  // namespace lsi

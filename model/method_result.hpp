// What one design method produces for one scene: time histories and scalar summaries, SI units,
// forces per metre of barrier width. Written to HDF5 as one group per method.
#pragma once
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "model/result_scalars.hpp"

namespace lsi {

// How a simulated run ended (the MPM; the closed forms have no end state). A final displacement
// is a result only for AtRest and EndTimeLandslideMoving (the barrier at rest at the end).
enum class EndState {
  None,                    // not a run that can end in several ways (closed forms)
  AtRest,                  // the landslide and the barrier came to rest
  EndTimeLandslideMoving,  // end time reached, the barrier at rest, the landslide still moving
  EndTimeBarrierSliding,   // end time reached with the barrier still sliding
  BarrierLeftDomain,       // the barrier slid to the downstream end of the modelled domain
  Unstable,                // the run stopped unstable (MethodResult::status says why)
};

// The token written to result files ("at_rest", ...), and back; "" for None. Throws
// std::invalid_argument for an unknown token.
const char* end_state_token(EndState s);
EndState end_state_from_token(const std::string& token);
// True where the barrier's displacement at the end is its final displacement.
inline bool has_final_displacement(EndState s) {
  return s == EndState::None || s == EndState::AtRest || s == EndState::EndTimeLandslideMoving;
}

struct MethodResult {
  std::string method;  // "empirical", "analytical", "mpm", ...
  // Time histories (all the same length as `time`).
  std::vector<double> time;                      // s
  std::vector<double> force;                     // N/m, normal to the impacted face
  std::vector<double> force_horizontal;          // N/m
  std::vector<double> force_vertical;            // N/m, positive downwards on the barrier
  std::vector<double> landslide_kinetic_energy;  // J/m
  std::vector<double> barrier_velocity;          // m/s
  std::vector<double> barrier_displacement;      // m
  // Scalars.
  double peak_force = 0.0;          // N/m (normal to the face)
  double rise_time = 0.0;           // s, T1
  double impact_duration = 0.0;     // s, T2
  double final_displacement = 0.0;  // m; +infinity if the barrier never stops
                                    // (closed forms), NaN if a run was cut
                                    // short before it stopped (end_state)
  // Runs (the MPM): how the run ended, and the solver's status ("finished" or why it stopped).
  EndState end_state = EndState::None;
  std::string status;
  // Closed forms that move a barrier: "paper" or "momentum" (scene.hpp, BarrierModel).
  std::string barrier_model;
  // Further scalars, each given by some methods (result_scalars.hpp).
  ResultScalars scalars;
  // A simulated run's statistics (the MPM); empty for the closed forms.
  std::optional<RunStatistics> run;
  // The MPM's error bars from a grid-convergence study, where one was given.
  std::optional<ConvergenceBars> convergence;
  // Further method-specific histories on the same `time` axis (e.g. the MPM's energies).
  struct Series {
    std::string units;
    std::string description;
    std::vector<double> values;
  };
  std::map<std::string, Series> series;
};

// The standard histories of a MethodResult by name, in file order, with their units: the one list
// that result files, checks and tests go through.
struct HistoryField {
  const char* name;
  std::vector<double> MethodResult::*member;
  const char* units;
  const char* description;
};
const std::vector<HistoryField>& history_fields();

// The four summaries of a MethodResult by name, in file order, with their units and meaning.
struct SummaryField {
  const char* name;
  double MethodResult::*member;
  const char* units;
  const char* description;
};
const std::vector<SummaryField>& summary_fields();

}  // namespace lsi

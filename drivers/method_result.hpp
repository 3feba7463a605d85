// What one design method produces for one scene: time histories and scalar summaries, SI units,
// forces per metre of barrier width. Written to HDF5 as one group per method.
#pragma once
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace lsi {

struct MethodResult {
  std::string method;                               // "empirical", "analytical", "mpm", ...
  // Time histories (all the same length as `time`).
  std::vector<double> time;                         // s
  std::vector<double> force;                        // N/m, normal to the impacted face
  std::vector<double> force_horizontal;             // N/m
  std::vector<double> force_vertical;               // N/m, positive downwards on the barrier
  std::vector<double> landslide_kinetic_energy;     // J/m
  std::vector<double> barrier_velocity;             // m/s
  std::vector<double> barrier_displacement;         // m
  // Scalars.
  double peak_force = 0.0;                          // N/m (normal to the face)
  double rise_time = 0.0;                           // s, T1
  double impact_duration = 0.0;                     // s, T2
  double final_displacement = 0.0;                  // m; +infinity if the barrier never stops
  // Further method-specific scalars (e.g. "froude_number", "reduced_mass_kg_per_m"), SI units.
  std::map<std::string, double> extra;
  // Further method-specific histories on the same `time` axis (e.g. the MPM's energies).
  struct Series {
    std::string units;
    std::string description;
    std::vector<double> values;
  };
  std::map<std::string, Series> series;
};

}  // namespace lsi

#include "model/result_scalars.hpp"

#include <cmath>
#include <limits>

#include "model/method_result.hpp"

namespace lsi {

const std::vector<ScalarField>& scalar_fields() {
  using S = ResultScalars;
  static const std::vector<ScalarField> fields = {
      {"peak_force_horizontal", "N/m", &S::peak_force_horizontal},
      {"impulse", "N s/m", &S::impulse},
      {"barrier_start_time", "s", &S::barrier_start_time},
      {"barrier_stop_time", "s", &S::barrier_stop_time},
      {"largest_barrier_velocity", "m/s", &S::largest_barrier_velocity},
      {"flow_friction_deceleration", "m/s^2", &S::flow_friction_deceleration},
      {"min_sliding_safety", "-", &S::min_sliding_safety},
      {"min_overturning_safety", "-", &S::min_overturning_safety},
      {"overturning_resultant_height", "m", &S::overturning_resultant_height},
      {"overturning_moment_max", "N m/m", &S::overturning_moment_max},
      {"froude_number", "-", &S::froude_number},
      {"alpha", "-", &S::alpha},
      {"normal_velocity", "m/s", &S::normal_velocity},
      {"peak_force_dynamic", "N/m", &S::peak_force_dynamic},
      {"peak_force_static", "N/m", &S::peak_force_static},
      {"landslide_mass", "kg/m", &S::landslide_mass},
      {"lambda", "-", &S::lambda},
      {"tau", "-", &S::tau},
      {"reduced_mass", "kg/m", &S::reduced_mass},
      {"max_shortening", "m", &S::max_shortening},
      {"K1", "N/m^2", &S::K1},
      {"q1", "1/s", &S::q1},
      {"common_velocity", "m/s", &S::common_velocity},
      {"hydrostatic_k", "-", &S::hydrostatic_k},
      {"hydrodynamic_alpha", "-", &S::hydrodynamic_alpha},
      {"peak_force_windowed", "N/m", &S::peak_force_windowed},
      {"peak_force_windowed_time", "s", &S::peak_force_windowed_time},
      {"peak_force_window", "s", &S::peak_force_window},
      {"final_force", "N/m", &S::final_force},
      {"displacement_at_end", "m", &S::displacement_at_end},
      {"overtopped_volume_m2", "m^2/m", &S::overtopped_volume_m2},
      {"overtopped_inside_barrier_m2", "m^2/m", &S::overtopped_inside_barrier_m2},
      {"retained_volume_m2", "m^2/m", &S::retained_volume_m2},
      {"face_pore_pressure_max_pa", "Pa", &S::face_pore_pressure_max_pa},
      {"barrier_interior_volume_max_m2", "m^2/m", &S::barrier_interior_volume_max_m2},
      {"transfer_dissipation_j_per_m", "J/m", &S::transfer_dissipation_j_per_m},
      {"energy_residual_unexplained_min", "-", &S::energy_residual_unexplained_min},
      {"energy_residual_unexplained_max", "-", &S::energy_residual_unexplained_max},
  };
  return fields;
}

const ScalarField* find_scalar_field(std::string_view name) {
  for (const ScalarField& f : scalar_fields())
    if (name == f.name) return &f;
  return nullptr;
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The run statistics by name.
struct RunField {
  const char* name;
  double (*get)(const RunStatistics&);
  void (*set)(RunStatistics&, double);
};
const RunField kRunFields[] = {
    {"particles", [](const RunStatistics& s) { return double(s.particles); },
     [](RunStatistics& s, double v) { s.particles = static_cast<std::int64_t>(v); }},
    {"steps", [](const RunStatistics& s) { return double(s.steps); },
     [](RunStatistics& s, double v) { s.steps = static_cast<std::int64_t>(v); }},
    {"end_time", [](const RunStatistics& s) { return s.end_time; },
     [](RunStatistics& s, double v) { s.end_time = v; }},
    {"finished", [](const RunStatistics& s) { return s.finished ? 1.0 : 0.0; },
     [](RunStatistics& s, double v) { s.finished = v != 0.0; }},
    {"solver_seconds", [](const RunStatistics& s) { return s.solver_seconds; },
     [](RunStatistics& s, double v) { s.solver_seconds = v; }},
    {"particle_updates_per_second",
     [](const RunStatistics& s) { return s.particle_updates_per_second; },
     [](RunStatistics& s, double v) { s.particle_updates_per_second = v; }},
    {"saturated", [](const RunStatistics& s) { return s.saturated ? 1.0 : 0.0; },
     [](RunStatistics& s, double v) { s.saturated = v != 0.0; }},
};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() > tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

std::vector<std::pair<std::string, double>> named_scalars(const MethodResult& r) {
  std::vector<std::pair<std::string, double>> out;
  for (const ScalarField& f : scalar_fields())
    if (const auto& v = r.scalars.*(f.member)) out.emplace_back(f.name, *v);
  if (r.run)
    for (const RunField& f : kRunFields) out.emplace_back(f.name, f.get(*r.run));
  if (r.convergence) {
    for (const auto& [output, bar] : r.convergence->outputs) {
      out.emplace_back(output + "_spread", bar.spread);
      out.emplace_back(output + "_converged", bar.converged ? 1.0 : 0.0);
    }
    out.emplace_back("convergence_finer_cells", r.convergence->finer_cells);
    out.emplace_back("convergence_finer_courant", r.convergence->finer_courant);
  }
  return out;
}

bool set_named_scalar(MethodResult& r, const std::string& name, double value) {
  if (const ScalarField* f = find_scalar_field(name)) {
    r.scalars.*(f->member) = value;
    return true;
  }
  for (const RunField& f : kRunFields)
    if (name == f.name) {
      if (!r.run) r.run.emplace();
      f.set(*r.run, value);
      return true;
    }
  auto bars = [&]() -> ConvergenceBars& {
    if (!r.convergence) r.convergence.emplace();
    return *r.convergence;
  };
  if (name == "convergence_finer_cells") {
    bars().finer_cells = static_cast<int>(value);
    return true;
  }
  if (name == "convergence_finer_courant") {
    bars().finer_courant = value;
    return true;
  }
  if (ends_with(name, "_spread")) {
    bars().outputs[name.substr(0, name.size() - 7)].spread = value;
    return true;
  }
  if (ends_with(name, "_converged")) {
    bars().outputs[name.substr(0, name.size() - 10)].converged = value != 0.0;
    return true;
  }
  return false;
}

double scalar_by_name(const MethodResult& r, const std::string& name) {
  if (name == "peak_force") return r.peak_force;
  if (name == "rise_time") return r.rise_time;
  if (name == "impact_duration") return r.impact_duration;
  if (name == "final_displacement") return r.final_displacement;
  if (const ScalarField* f = find_scalar_field(name))
    return (r.scalars.*(f->member)).value_or(kNaN);
  if (r.run)
    for (const RunField& f : kRunFields)
      if (name == f.name) return f.get(*r.run);
  return kNaN;
}

}  // namespace lsi

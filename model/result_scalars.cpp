#include "model/result_scalars.hpp"

#include <cmath>
#include <limits>

#include "model/method_result.hpp"

namespace lsi {

const std::vector<ScalarField>& scalar_fields() {
  using S = ResultScalars;
  static const std::vector<ScalarField> fields = {
      {"peak_force_horizontal", "N/m", &S::peak_force_horizontal,
       "horizontal component of the impact force at its peak, per metre of barrier width"},
      {"impulse", "N s/m", &S::impulse, "impulse of the impact force during the impact"},
      {"barrier_start_time", "s", &S::barrier_start_time, "time the barrier starts sliding"},
      {"barrier_stop_time", "s", &S::barrier_stop_time,
       "time the barrier stops sliding; +inf if it never stops"},
      {"largest_barrier_velocity", "m/s", &S::largest_barrier_velocity,
       "largest sliding velocity of the barrier"},
      {"flow_friction_deceleration", "m/s^2", &S::flow_friction_deceleration,
       "deceleration of the flow by the friction on its base"},
      {"min_sliding_safety", "1", &S::min_sliding_safety,
       "smallest safety factor of the barrier against sliding under the load history; +inf for "
       "a load that cannot make it slide"},
      {"min_overturning_safety", "1", &S::min_overturning_safety,
       "smallest safety factor of the barrier against overturning under the load history; +inf "
       "for a load that cannot tip it"},
      {"overturning_resultant_height", "m", &S::overturning_resultant_height,
       "height above the base of the face load's resultant at the largest overturning moment"},
      {"overturning_moment_max", "N m/m", &S::overturning_moment_max,
       "largest moment of the face load about the downstream toe"},
      {"froude_number", "1", &S::froude_number,
       "Froude number of the flow normal to the face, v_n / sqrt(g h)"},
      {"alpha", "1", &S::alpha, "dynamic coefficient of the empirical model, a1 Fr^a2"},
      {"normal_velocity", "m/s", &S::normal_velocity,
       "velocity of the flow normal to the impacted face"},
      {"peak_force_dynamic", "N/m", &S::peak_force_dynamic,
       "dynamic part of the empirical peak force"},
      {"peak_force_static", "N/m", &S::peak_force_static,
       "static part of the empirical peak force"},
      {"landslide_mass", "kg/m", &S::landslide_mass,
       "mass of the landslide per metre of barrier width"},
      {"lambda", "1", &S::lambda,
       "two-body model: largest shortening of the landslide over its length, s1,max / L1,0"},
      {"tau", "1", &S::tau, "two-body model: rise time over impact duration, T1 / T2"},
      {"reduced_mass", "kg/m", &S::reduced_mass, "two-body model: reduced mass m1 m2 / (m1 + m2)"},
      {"max_shortening", "m", &S::max_shortening,
       "two-body model: largest shortening of the landslide, s1,max"},
      {"K1", "N s/m^2", &S::K1, "two-body model: K1 = mu v1,0 / s1,max (kg/s per metre of width)"},
      {"q1", "N/m^1.5", &S::q1,
       "two-body model: q1 = 3/4 K1 v1,0 / sqrt(s1,max) (kg m^0.5/s^2 per metre of width)"},
      {"common_velocity", "m/s", &S::common_velocity,
       "two-body model: common velocity of landslide and barrier, m1 v10 / (m1 + m2)"},
      {"hydrostatic_k", "1", &S::hydrostatic_k,
       "literature model: coefficient k of the hydrostatic peak force"},
      {"hydrodynamic_alpha", "1", &S::hydrodynamic_alpha,
       "literature model: coefficient alpha of the hydrodynamic peak force"},
      {"peak_force_windowed", "N/m", &S::peak_force_windowed,
       "largest mean impact force over any window of length peak_force_window"},
      {"peak_force_windowed_time", "s", &S::peak_force_windowed_time,
       "centre of the window of peak_force_windowed"},
      {"peak_force_window", "s", &S::peak_force_window,
       "length of the averaging window of peak_force_windowed"},
      {"final_force", "N/m", &S::final_force, "impact force left on the barrier after the impact"},
      {"displacement_at_end", "m", &S::displacement_at_end,
       "displacement of the barrier when the run ended"},
      {"overtopped_volume_m2", "m^2/m", &S::overtopped_volume_m2,
       "landslide volume beyond the barrier's crest at the end"},
      {"overtopped_inside_barrier_m2", "m^2/m", &S::overtopped_inside_barrier_m2,
       "of the overtopped volume, the part inside the barrier (the contact's leak)"},
      {"retained_volume_m2", "m^2/m", &S::retained_volume_m2,
       "landslide volume upstream of the barrier at the end"},
      {"face_pore_pressure_max_pa", "Pa", &S::face_pore_pressure_max_pa,
       "largest pore pressure on the upstream face"},
      {"barrier_interior_volume_max_m2", "m^2/m", &S::barrier_interior_volume_max_m2,
       "largest landslide volume inside the barrier"},
      {"transfer_dissipation_j_per_m", "J/m", &S::transfer_dissipation_j_per_m,
       "kinetic energy lost in the grid transfers"},
      {"energy_residual_unexplained_min", "1", &S::energy_residual_unexplained_min,
       "smallest relative energy residual with the transfer dissipation booked"},
      {"energy_residual_unexplained_max", "1", &S::energy_residual_unexplained_max,
       "largest relative energy residual with the transfer dissipation booked"},
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
  const char* units;
  ScalarKind kind;
  const char* description;
  double (*get)(const RunStatistics&);
  void (*set)(RunStatistics&, double);
};
const RunField kRunFields[] = {
    {"particles", "1", ScalarKind::Count, "material points of the run",
     [](const RunStatistics& s) { return double(s.particles); },
     [](RunStatistics& s, double v) { s.particles = static_cast<std::int64_t>(v); }},
    {"steps", "1", ScalarKind::Count, "time steps of the run",
     [](const RunStatistics& s) { return double(s.steps); },
     [](RunStatistics& s, double v) { s.steps = static_cast<std::int64_t>(v); }},
    {"end_time", "s", ScalarKind::Real, "simulated time reached",
     [](const RunStatistics& s) { return s.end_time; },
     [](RunStatistics& s, double v) { s.end_time = v; }},
    {"finished", "1", ScalarKind::Flag, "true: the run finished; false: it stopped unstable",
     [](const RunStatistics& s) { return s.finished ? 1.0 : 0.0; },
     [](RunStatistics& s, double v) { s.finished = v != 0.0; }},
    {"solver_seconds", "s", ScalarKind::Real, "wall time spent in the solver, without output",
     [](const RunStatistics& s) { return s.solver_seconds; },
     [](RunStatistics& s, double v) { s.solver_seconds = v; }},
    {"particle_updates_per_second", "1/s", ScalarKind::Real,
     "material-point updates (points times steps) per second of solver time",
     [](const RunStatistics& s) { return s.particle_updates_per_second; },
     [](RunStatistics& s, double v) { s.particle_updates_per_second = v; }},
    {"saturated", "1", ScalarKind::Flag,
     "true: a saturated (two-phase) landslide; false: a dry one",
     [](const RunStatistics& s) { return s.saturated ? 1.0 : 0.0; },
     [](RunStatistics& s, double v) { s.saturated = v != 0.0; }},
    {"threads", "1", ScalarKind::Count,
     "host threads the run's kernels ran on (0: a device ran them); solver_seconds is theirs",
     [](const RunStatistics& s) { return double(s.threads); },
     [](RunStatistics& s, double v) { s.threads = static_cast<int>(v); }},
};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() > tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

std::vector<std::pair<std::string, double>> named_scalars(const MethodResult& r) {
  std::vector<std::pair<std::string, double>> out;
  for (DescribedScalar& s : described_scalars(r)) {
    bool summary = false;
    for (const SummaryField& f : summary_fields()) summary = summary || s.name == f.name;
    if (!summary) out.emplace_back(std::move(s.name), s.value);
  }
  return out;
}

std::string scalar_units(std::string_view name) {
  for (const SummaryField& f : summary_fields())
    if (name == f.name) return f.units;
  if (const ScalarField* f = find_scalar_field(name)) return f->units;
  for (const RunField& f : kRunFields)
    if (name == f.name) return f.units;
  return "";
}

std::vector<DescribedScalar> described_scalars(const MethodResult& r) {
  std::vector<DescribedScalar> out;
  for (const SummaryField& f : summary_fields())
    if (!std::isnan(r.*(f.member))) out.push_back({f.name, r.*(f.member), f.units, f.description});
  for (const ScalarField& f : scalar_fields())
    if (const auto& v = r.scalars.*(f.member)) out.push_back({f.name, *v, f.units, f.description});
  if (r.run)
    for (const RunField& f : kRunFields)
      out.push_back({f.name, f.get(*r.run), f.units, f.description, f.kind});
  if (r.convergence) {
    for (const auto& [output, bar] : r.convergence->outputs) {
      const std::string units = scalar_units(output);
      out.push_back({output + "_spread", bar.spread, units.empty() ? "1" : units,
                     "spread of " + output +
                         " between the base and the finer resolution of the grid-convergence "
                         "study"});
      out.push_back({output + "_converged", bar.converged ? 1.0 : 0.0, "1",
                     "true: " + output + " converged in the grid-convergence study",
                     ScalarKind::Flag});
    }
    out.push_back({"convergence_finer_cells", double(r.convergence->finer_cells), "1",
                   "cells through the landslide's thickness of the convergence study's finer runs",
                   ScalarKind::Count});
    out.push_back({"convergence_finer_courant", r.convergence->finer_courant, "1",
                   "Courant number of the convergence study's finer-step runs"});
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

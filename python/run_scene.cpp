#include "python/run_scene.hpp"

#include <pybind11/numpy.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "io/mpm_scene.hpp"
#include "io/scene_parser.hpp"
#include "model/closed_form_methods.hpp"
#include "model/input_error.hpp"
#include "model/method_result.hpp"
#include "model/mpm_impact.hpp"
#include "model/mpm_runner.hpp"
#include "model/scene_methods.hpp"
#include "python/kokkos_work.hpp"
#include "python/method_names.hpp"
#include "python/scene_document.hpp"
#include "sweeps/sampled_scene.hpp"

namespace py = pybind11;

namespace lsi::python {
namespace {

// The methods of a scene document, as `lsi run` runs them: a verification scene (`mpm_case`) is
// the MPM alone; a landslide scene's methods are model/scene_methods.hpp's.
SceneRun run_document(const nlohmann::json& doc, const std::vector<std::string>& only) {
  if (is_mpm_case(doc)) {
    for (const auto& m : only)
      if (m != "mpm")
        throw InputError("methods: " + m + ": a verification scene (mpm_case) runs the MPM only");
    MpmOutcome o = run_mpm_case(parse_mpm_case(doc));
    SceneRun out;
    out.results.push_back(std::move(o.result));
    out.snapshots = std::move(o.snapshots);
    return out;
  }
  return run_scene_methods(parse_scene(doc), only, "methods:");
}

// A NumPy array of the given shape that takes over `values` (row-major), without a copy.
template <class T>
py::array_t<T> take_array(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule free_when_done(owned, [](void* v) { delete static_cast<std::vector<T>*>(v); });
  return py::array_t<T>(std::move(shape), owned->data(), free_when_done);
}

// The snapshot datasets' units (io/mpm_snapshots.hpp), by name.
py::dict snapshot_units() {
  static const char* const units[][2] = {{"time", "s"},
                                         {"id", "1"},
                                         {"material", "1"},
                                         {"position", "m"},
                                         {"displacement", "m"},
                                         {"velocity", "m/s"},
                                         {"stress", "Pa"},
                                         {"mass", "kg/m"},
                                         {"volume", "m^2"},
                                         {"volumetric_strain", "1"},
                                         {"deviatoric_strain", "1"},
                                         {"plastic_work", "J/m"},
                                         {"pore_pressure", "Pa"},
                                         {"barrier_outline", "m"},
                                         {"face_pressure", "Pa"},
                                         {"face_band_points", "m"}};
  py::dict d;
  for (const auto& [name, unit] : units) d[name] = unit;
  return d;
}

// One snapshot as a dict of NumPy arrays, named as the datasets of `lsi run --out`'s
// /mpm/snapshots/NNNNNN (io/mpm_snapshots.hpp); the vectors as n x 2 (x, y: the file adds z = 0
// for XDMF), the stress n x 4 (xx, yy, xy, zz). Takes over the snapshot's arrays.
py::dict snapshot_dict(MpmSnapshot&& s) {
  const py::ssize_t n = s.count;
  py::dict d;
  d["time"] = s.time;
  d["id"] = take_array(std::move(s.id), {n});
  d["material"] = take_array(std::vector<std::int64_t>(s.material.begin(), s.material.end()), {n});
  d["position"] = take_array(std::move(s.position), {n, 2});
  d["displacement"] = take_array(std::move(s.displacement), {n, 2});
  d["velocity"] = take_array(std::move(s.velocity), {n, 2});
  d["stress"] = take_array(std::move(s.stress), {n, 4});
  d["mass"] = take_array(std::move(s.mass), {n});
  d["volume"] = take_array(std::move(s.volume), {n});
  d["volumetric_strain"] = take_array(std::move(s.volumetric_strain), {n});
  d["deviatoric_strain"] = take_array(std::move(s.deviatoric_strain), {n});
  d["plastic_work"] = take_array(std::move(s.plastic_work), {n});
  if (!s.pore_pressure.empty()) d["pore_pressure"] = take_array(std::move(s.pore_pressure), {n});
  if (!s.barrier_outline.empty())
    d["barrier_outline"] = take_array(std::move(s.barrier_outline), {4, 2});
  if (!s.face_pressure.empty()) {
    const py::ssize_t bands = static_cast<py::ssize_t>(s.face_pressure.size());
    d["face_pressure"] = take_array(std::move(s.face_pressure), {bands});
    d["face_band_points"] = take_array(std::move(s.face_band_points), {bands + 1, 2});
  }
  return d;
}

py::dict result_dict(const MethodResult& r) {
  py::dict scalars, histories, units;
  // The four summaries where the method gives them (NaN: not given), then every further scalar,
  // as the JSON summary of `lsi run` lists them (io/report.hpp, summary_json).
  const double summaries[sweeps::closed_form_output_count] = {
      r.peak_force, r.rise_time, r.impact_duration, r.final_displacement};
  for (int o = 0; o < sweeps::closed_form_output_count; ++o) {
    if (std::isnan(summaries[o])) continue;
    scalars[sweeps::closed_form_output_name[o]] = summaries[o];
    units[sweeps::closed_form_output_name[o]] = sweeps::closed_form_output_units[o];
  }
  for (const auto& [name, value] : named_scalars(r)) {
    if (scalars.contains(name)) continue;
    scalars[name.c_str()] = value;
    if (const ScalarField* f = find_scalar_field(name)) units[name.c_str()] = f->units;
  }
  for (const HistoryField& h : history_fields()) {
    const std::vector<double>& v = r.*(h.member);
    if (v.empty()) continue;
    histories[h.name] = py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
    units[h.name] = h.units;
  }
  for (const auto& [name, s] : r.series) {
    histories[name.c_str()] =
        py::array_t<double>(static_cast<py::ssize_t>(s.values.size()), s.values.data());
    units[name.c_str()] = s.units;
  }
  py::dict d;
  d["scalars"] = scalars;
  d["histories"] = histories;
  d["units"] = units;
  if (r.end_state != EndState::None) d["end_state"] = end_state_token(r.end_state);
  if (!r.status.empty()) d["status"] = r.status;
  if (!r.barrier_model.empty()) d["barrier_model"] = r.barrier_model;
  return d;
}

py::dict run(py::handle scene, py::handle methods) {
  const nlohmann::json doc = scene_document(scene);
  const std::vector<std::string> only =
      method_names(methods, {"empirical", "analytical", "literature", "mpm"});
  SceneRun run = with_kokkos([&] { return run_document(doc, only); });
  py::dict out;
  for (const MethodResult& r : run.results) out[r.method.c_str()] = result_dict(r);
  // The MPM's snapshots (methods.mpm.snapshot_interval_s), in the order they were taken.
  if (!run.snapshots.empty() && out.contains("mpm")) {
    py::dict mpm = out["mpm"];
    py::list materials;
    for (const std::string& name : run.snapshots.front().material_names) materials.append(name);
    py::list snapshots;
    for (MpmSnapshot& s : run.snapshots) snapshots.append(snapshot_dict(std::move(s)));
    mpm["snapshots"] = snapshots;
    mpm["snapshot_materials"] = materials;
    mpm["snapshot_units"] = snapshot_units();
  }
  return out;
}

}  // namespace

void add_run(py::module_& m) {
  m.def(
      "run", &run,
      "run(scene, methods=None) -> dict\n\n"
      "Runs a scene as `lsi run` does: the closed forms it selects, then the MPM where it has\n"
      "methods.mpm; a verification scene (mpm_case) runs the MPM alone.\n\n"
      "scene: a dict (the JSON of a scene file, docs/reference/scene_schema.md) or the path\n"
      "of a scene file. methods: as `lsi run --methods`: \"empirical\", \"analytical\",\n"
      "\"literature\", \"mpm\", a list of them or a comma-separated string; by default the\n"
      "scene's.\n\n"
      "Returns {method: {\"scalars\": {name: float}, \"histories\": {name: array},\n"
      "\"units\": {name: unit}, \"end_state\": str, \"status\": str, \"barrier_model\": str}},\n"
      "the methods in the order they ran. The names and units are those of the HDF5 results\n"
      "(docs/reference/results.md): histories time (s), force, force_horizontal,\n"
      "force_vertical (N/m, per metre of barrier width), landslide_kinetic_energy (J/m),\n"
      "barrier_velocity (m/s), barrier_displacement (m) and the MPM's further series; scalars\n"
      "peak_force (N/m), rise_time (s), impact_duration (s), final_displacement (m; inf for a\n"
      "barrier that never stops) and the rest, those a method does not give left out.\n"
      "end_state and status: runs (the MPM) only; barrier_model: the closed forms that move a\n"
      "barrier. An MPM run that stops unstable returns what it computed (end_state\n"
      "\"unstable\", status says why) and raises nothing.\n\n"
      "With methods.mpm.snapshot_interval_s the MPM's dict also has \"snapshots\": a list,\n"
      "one dict per snapshot in time order, as the datasets of `lsi run --out`'s\n"
      "/mpm/snapshots: time (float, s), id, material (int64, n), position, displacement,\n"
      "velocity (n x 2: x, y), stress (n x 4: xx, yy, xy, zz), mass, volume,\n"
      "volumetric_strain, deviatoric_strain, plastic_work (n), pore_pressure (saturated\n"
      "runs), barrier_outline (4 x 2, impact scenes), face_pressure and face_band_points ((bands + 1)\n"
      "x 2, impact scenes with methods.mpm.face_band_m); \"snapshot_materials\", the names\n"
      "`material` indexes; \"snapshot_units\", {name: unit}.\n\n"
      "Raises ValueError with the scene parser's message for an invalid scene\n"
      "(`landslide.thickness_m = -3: must be > 0 (m)`).",
      py::arg("scene"), py::arg("methods") = py::none());
}

}  // namespace lsi::python

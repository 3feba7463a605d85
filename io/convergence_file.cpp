#include "io/convergence_file.hpp"

#include <cmath>
#include <limits>

#include "io/json_fields.hpp"
#include "io/scene_parser.hpp"

namespace lsi {
namespace jf = json_fields;

const std::vector<std::string>& convergence_outputs() {
  static const std::vector<std::string> names = {
      "peak_force",         "peak_force_windowed",      "impulse",
      "impact_duration",    "final_displacement",       "overtopped_volume_m2",
      "retained_volume_m2", "face_pore_pressure_max_pa"};
  return names;
}

ConvergenceStudy load_convergence_study(const std::string& path) {
  const nlohmann::json doc = read_scene_document(path, "convergence study");
  ConvergenceStudy st;
  st.source = path;
  const jf::ObjectReader top(doc, "",
                             {"about", "command", "base", "finer", "relative", "floors", "cases"});
  st.command = top.optional_string("command").value_or("");
  const jf::ObjectReader base = top.object("base", {"cells", "courant"});
  const jf::ObjectReader finer = top.object("finer", {"cells", "courant"});
  st.base_cells = static_cast<int>(base.integer("cells", jf::at_least(1)));
  st.finer_cells = static_cast<int>(finer.integer("cells", jf::at_least(1)));
  st.base_courant = base.number("courant", jf::interval('(', 0, 10, ']'));
  st.finer_courant = finer.number("courant", jf::interval('(', 0, 10, ']'));
  const nlohmann::json* cases = top.find("cases");
  if (!cases || !cases->is_object()) top.fail_missing("cases", "object of cases by scene name");
  for (const auto& [name, c] : cases->items()) {
    const jf::ObjectReader r(c, "cases." + name,
                             {"landslide", "barrier", "mpm", "end_states", "solver_seconds",
                              "window", "outputs", "peak_force_windows"});
    CaseConvergence cc;
    if (!r.has("landslide") || !r.has("barrier")) r.fail_missing("landslide", "the scene's blocks");
    cc.landslide = *r.find("landslide");
    cc.barrier = *r.find("barrier");
    if (!r.has("mpm")) r.fail_missing("mpm", "the MPM settings of the base resolution");
    cc.mpm = parse_mpm_settings(*r.find("mpm"), r.path_of("mpm"), /*impact=*/true);
    const nlohmann::json* outs = r.find("outputs");
    if (!outs || !outs->is_object()) r.fail_missing("outputs", "object of outputs");
    for (const auto& [key, o] : outs->items()) {
      const jf::ObjectReader ro(
          o, r.path_of("outputs") + "." + key,
          {"value", "coarser", "finer_cells", "finer_courant", "spread", "converged"});
      // An output the study could not measure (no final displacement, ...) has null values.
      const nlohmann::json* value = ro.find("value");
      const nlohmann::json* spread = ro.find("spread");
      if (!value || !spread || value->is_null() || spread->is_null()) continue;
      OutputSpread s;
      s.value = ro.number("value", jf::any_number());
      s.spread = ro.number("spread", jf::at_least(0));
      s.converged = ro.boolean_or("converged", false);
      cc.outputs[key] = s;
    }
    st.cases[name] = std::move(cc);
  }
  return st;
}

std::string attach_convergence(const ConvergenceStudy& study, const Scene& scene,
                               MethodResult& mpm) {
  const auto it = study.cases.find(scene.name);
  if (it == study.cases.end()) return "the study has no case of this name";
  const CaseConvergence& c = it->second;
  if (c.landslide != scene.source.value("landslide", nlohmann::json()) ||
      c.barrier != scene.source.value("barrier", nlohmann::json()))
    return "the study ran another landslide or barrier under this name";
  if (!scene.methods.mpm) return "the scene has no methods.mpm";
  // The settings that shape the solution must be the study's; what is only written out may differ.
  MpmSettings here = *scene.methods.mpm;
  here.snapshot_interval_s = c.mpm.snapshot_interval_s;
  here.cell_mean_pore_pressure_output = c.mpm.cell_mean_pore_pressure_output;
  here.transfer_dissipation = c.mpm.transfer_dissipation;
  here.face_band_m = c.mpm.face_band_m;
  if (!(here == c.mpm))
    return "the study's base resolution has other MPM settings (cell size, Courant number, ...)";
  if (mpm.end_state != EndState::AtRest)
    return std::string("this run ended ") + end_state_token(mpm.end_state) +
           ", not at rest as the study's runs";
  for (const auto& [key, s] : c.outputs) {
    const double v = scalar_by_name(mpm, key);
    if (!(std::fabs(v - s.value) <= kConvergenceStaleRelative * std::fabs(s.value) + 1e-12))
      return "stale: " + key + " is " + jf::format_number(v) + " here and " +
             jf::format_number(s.value) + " in the study (rerun ci/reference_convergence.py)";
  }
  ConvergenceBars& bars = mpm.convergence.emplace();
  for (const auto& [key, s] : c.outputs) bars.outputs[key] = {s.spread, s.converged};
  bars.finer_cells = study.finer_cells;
  bars.finer_courant = study.finer_courant;
  return "";
}

}  // namespace lsi

#include "model/scene_methods.hpp"

#include <algorithm>
#include <utility>

#include "model/closed_form_methods.hpp"
#include "model/input_error.hpp"
#include "model/mpm_impact.hpp"

namespace lsi {

bool scene_runs_mpm(const Scene& scene, const std::vector<std::string>& only) {
  return only.empty() ? scene.methods.mpm.has_value()
                      : std::find(only.begin(), only.end(), "mpm") != only.end();
}

SceneRun run_scene_methods(const Scene& scene, const std::vector<std::string>& only,
                           const std::string& option) {
  SceneRun out;
  std::vector<std::string> closed;
  for (const auto& m : only)
    if (m != "mpm") closed.push_back(m);
  if (only.empty() || !closed.empty()) out.results = run_closed_form_methods(scene, closed);
  if (!scene_runs_mpm(scene, only)) return out;
  if (!scene.methods.mpm)
    throw InputError(option +
                     " mpm: the scene has no methods.mpm block (cell_size_m, ...; "
                     "docs/reference/scene_schema.md)");
  const MpmCase c = impact_case(scene);
  out.mpm_settings = c.settings;
  out.mpm_settings->end_time_given = true;  // the impact's default, resolved: the run's end time
  MpmOutcome o = run_mpm_case(c);
  out.results.push_back(std::move(o.result));
  if (!out.results.back().run->finished) out.mpm_status = out.results.back().status;
  out.snapshots = std::move(o.snapshots);
  return out;
}

}  // namespace lsi

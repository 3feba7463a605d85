// The methods of a landslide scene as `lsi run` runs them: the closed forms it selects (or
// `only` names), then the MPM if the scene has `methods.mpm` (or `only` names it). Shared by the
// command line (app/main.cpp) and the Python module (python/run_scene.cpp).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "model/method_result.hpp"
#include "model/mpm_runner.hpp"
#include "model/mpm_settings.hpp"
#include "model/scene.hpp"

namespace lsi {

struct SceneRun {
  std::vector<MethodResult> results;  // the closed forms in the scene's order, then the MPM
  // When the MPM ran: its settings as the run used them (the impact's end time resolved), the
  // reason it stopped when it did not finish (empty otherwise), and its snapshots.
  std::optional<MpmSettings> mpm_settings;
  std::string mpm_status;
  std::vector<MpmSnapshot> snapshots;
};

// Whether run_scene_methods runs the MPM: `only` names it, or names nothing and the scene has
// methods.mpm.
bool scene_runs_mpm(const Scene& scene, const std::vector<std::string>& only);

// `option` names the choice of methods in the message when `only` asks for the MPM of a scene
// without methods.mpm (InputError), e.g. "--methods" or "methods".
SceneRun run_scene_methods(const Scene& scene, const std::vector<std::string>& only,
                           const std::string& option);

}  // namespace lsi

// The scene as run: the typed scene (and the MPM's settings) written back as a scene document
// with every default filled in, for the results' root attribute `scene_resolved`. Parsing it
// again gives the same scene (parse_scene, parse_mpm_settings).
#pragma once
#include <nlohmann/json.hpp>

#include "model/mpm_case.hpp"
#include "model/mpm_settings.hpp"
#include "model/scene.hpp"

namespace lsi {

// The `methods.mpm` block of these settings (`impact`: of a landslide scene). end_time_s is left
// out where the scene leaves it to the impact's time scale (end_time_given false), as are the
// output interval when it is 0 (the same) and the keys a setting switched off does not take.
nlohmann::json mpm_settings_json(const MpmSettings& settings, bool impact);

// The landslide scene with every default filled in; `methods.mpm` from `mpm_as_run` where
// given (the settings the MPM ran with: model/mpm_impact.hpp impact_case resolves the end time
// and output interval), else from the scene's own block.
nlohmann::json resolved_scene_json(const Scene& scene, const MpmSettings* mpm_as_run = nullptr);

// A verification scene as run: the scene as read with its `methods.mpm` block resolved.
nlohmann::json resolved_mpm_case_json(const MpmCase& c);

}  // namespace lsi

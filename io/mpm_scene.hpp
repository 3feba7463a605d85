// MPM input: the `methods.mpm` block (numerical settings, shared by every MPM scene) and the
// `mpm_case` block of a verification scene (domain, walls, materials, bodies), which replaces
// `landslide` and `barrier` for problems that are not a landslide hitting a barrier, read into
// model/mpm_settings.hpp and model/mpm_case.hpp. Both are documented in docs/reference/scene_schema.md.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "model/mpm_case.hpp"
#include "model/mpm_settings.hpp"

namespace lsi {

// Parses `methods.mpm` (path names the block in messages). Throws InputError. `impact`: the block
// of a landslide scene (accepts phases, drag, ...; end_time_s optional).
MpmSettings parse_mpm_settings(const nlohmann::json& block, const std::string& path,
                               bool impact = false);
bool is_mpm_case(const nlohmann::json& scene);
// Parses a whole verification scene {"name", "mpm_case", "methods": {"mpm": {...}}}.
MpmCase parse_mpm_case(const nlohmann::json& scene);

}  // namespace lsi

// The `scene` key of a study file (`lsi sweep`) or an accuracy study (`lsi accuracy`): a scene
// file path, relative to the study file's folder, or the scene object itself.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "io/json_fields.hpp"

namespace lsi {

// The scene document `root.scene` names. Throws InputError: `scene: missing (...)`,
// `scene = "x.json": <why the file cannot be read>`, or `scene = 3: must be a scene file path or
// a scene object`. The scene itself is not validated here.
nlohmann::json read_scene_reference(const json_fields::ObjectReader& root,
                                    const std::string& base_dir);

}  // namespace lsi

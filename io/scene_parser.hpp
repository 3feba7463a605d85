// Reads scene files: JSON in, a validated Scene (model/scene.hpp) out.
#pragma once
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "model/scene.hpp"

namespace lsi {

// Parses and validates; throws InputError (one line: path, value, allowed range) on any problem:
// malformed JSON, unknown key, missing key, wrong type, non-finite number, out-of-range value,
// inconsistent barrier geometry.
Scene parse_scene(const nlohmann::json& j);
inline constexpr std::size_t kMaxInputFileBytes = std::size_t(64) << 20;
Scene load_scene(const std::string& path);
// Reads and parses a scene file as JSON (malformed JSON, missing file, more than
// kMaxInputFileBytes: InputError with the path); the top level must be an object. No schema check.
// `kind` names the file in messages ("scene", "study").
nlohmann::json read_scene_document(
    const std::string& path,
    const std::string& kind = "scene");  // also reports malformed JSON with line/column

}  // namespace lsi

#include "io/scene_reference.hpp"

#include <filesystem>

#include "model/scene.hpp"
#include "io/scene_parser.hpp"

namespace lsi {

nlohmann::json read_scene_reference(const json_fields::ObjectReader& root,
                                    const std::string& base_dir) {
  const nlohmann::json* scene = root.find("scene");
  if (!scene) root.fail_missing("scene", "a scene file path or a scene object");
  if (scene->is_object()) return *scene;
  if (!scene->is_string()) root.fail_at("scene", "must be a scene file path or a scene object");
  std::filesystem::path p(scene->get<std::string>());
  if (p.is_relative() && !base_dir.empty()) p = std::filesystem::path(base_dir) / p;
  try {
    return read_scene_document(p.string());
  } catch (const InputError& e) {
    json_fields::fail(std::string("scene = ") + json_fields::format_value(*scene) + ": " +
                      e.what());
  }
}

}  // namespace lsi

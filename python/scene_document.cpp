#include "python/scene_document.hpp"

#include <string>

#include "io/json_fields.hpp"
#include "io/scene_parser.hpp"

namespace py = pybind11;

namespace lsi::python {
namespace {

std::string shown(const std::string& path) { return path.empty() ? "(top level)" : path; }

[[noreturn]] void not_json(py::handle value, const std::string& path) {
  throw py::type_error(shown(path) + ": a " +
                       std::string(py::str(value.get_type().attr("__name__"))) +
                       " is not a JSON value (allowed: dict, list, str, bool, int, float, None)");
}

}  // namespace

nlohmann::json to_json(py::handle value, const std::string& path) {
  if (value.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  const py::module_ numpy = py::module_::import("numpy");
  if (py::isinstance(value, numpy.attr("bool_"))) return value.cast<bool>();
  if (py::isinstance<py::int_>(value) || py::isinstance(value, numpy.attr("integer"))) {
    const py::int_ i(py::reinterpret_borrow<py::object>(value));
    try {
      return i.cast<long long>();
    } catch (const py::cast_error&) {  // beyond 64 bits: a number all the same
      return py::float_(i).cast<double>();
    }
  }
  if (py::isinstance<py::float_>(value) || py::isinstance(value, numpy.attr("floating")))
    return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value)) {
    nlohmann::json object = nlohmann::json::object();
    for (const auto& [key, item] : py::reinterpret_borrow<py::dict>(value)) {
      if (!py::isinstance<py::str>(key))
        throw py::type_error(shown(path) + ": key " + std::string(py::repr(key)) +
                             ": the keys of a scene are strings");
      const std::string k = key.cast<std::string>();
      object[k] = to_json(item, json_fields::join_path(path, k));
    }
    return object;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    nlohmann::json array = nlohmann::json::array();
    std::size_t index = 0;
    for (const auto& item : value)
      array.push_back(to_json(item, shown(path) + "[" + std::to_string(index++) + "]"));
    return array;
  }
  not_json(value, path);
}

nlohmann::json scene_document(py::handle scene) {
  if (py::isinstance<py::dict>(scene)) return to_json(scene);
  const py::object path_like = py::module_::import("os").attr("PathLike");
  if (py::isinstance<py::str>(scene) || py::isinstance(scene, path_like))
    return read_scene_document(
        py::module_::import("os").attr("fsdecode")(scene).cast<std::string>());
  throw py::type_error("scene: a " + std::string(py::str(scene.get_type().attr("__name__"))) +
                       ": give a dict (the JSON of a scene file) or the path of a scene file");
}

}  // namespace lsi::python

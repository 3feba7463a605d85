// A scene as the Python module takes it: a dict (the JSON of a scene file, as json.load reads it)
// or the path of a scene file, turned into the JSON document the scene parser reads.
#pragma once
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <string>

namespace lsi::python {

// A dict, list, str, bool, int, float or None (NumPy's scalars too) as JSON. Raises TypeError
// naming the key (`landslide.shape: a set is not a JSON value`) for anything else. A float that
// is not finite stays a number, for the scene parser to refuse with its message.
nlohmann::json to_json(pybind11::handle value, const std::string& path = {});

// The scene document of `scene`: a dict (converted as to_json) or a path (str or os.PathLike,
// read as `lsi run` reads a scene file). Raises TypeError for anything else.
nlohmann::json scene_document(pybind11::handle scene);

}  // namespace lsi::python

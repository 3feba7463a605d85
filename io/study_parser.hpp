// Reads study files into a Study (model/study.hpp), and the scenes of its samples.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "model/study.hpp"

namespace lsi {

// Parses and validates; `base_dir` resolves a scene or a points file given as a relative path.
// Throws InputError naming the study key (e.g. `inputs[1].sd = -2: must be > 0`), or for a
// points file the file, row, column and value (io/study_points.hpp).
Study parse_study(const nlohmann::json& j, const std::string& base_dir);
Study load_study(const std::string& path);

// The scene of one sample: the base scene with each input's JSON pointer set to its value.
nlohmann::json sample_scene_document(const Study& study, const double* input_values);
// A parsed scene's numeric values as the closed-form sweep kernel sees them.
sweeps::SceneValues scene_values(const Scene& scene);
// The one-line reason a sample is invalid (the scene parser's message), or "" if it is valid.
std::string invalid_sample_reason(const Study& study, const double* input_values);

}  // namespace lsi

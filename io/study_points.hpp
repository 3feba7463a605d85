// The rows of a points file as the samples of a study of design "points": every value is checked
// as the scene parser checks a scene's (the ranges of sweeps/sampled_scene.hpp and the checks
// across keys), so that a file of given points either runs whole or is refused before anything
// runs.
#pragma once
#include <string>

#include "io/points_file.hpp"
#include "model/study.hpp"

namespace lsi {

// "must be > 0", "must be an integer in [0, 1000000]": a scene field's own range
// (sweeps::SceneField, sweeps/sampled_scene.hpp) as the scene parser words it.
std::string scene_field_requirement(int field);

// `study` holds the points (study.points, in the order of study.inputs); `table` is the file they
// came from, for the messages. Throws
// InputError naming the file, the row (and line), the column, the value and its allowed range
// (`points.csv: row 3 (line 4), column /landslide/velocity_m_s = -1: must be > 0`), or, for a
// value that only the scene's checks across keys refuse, the scene parser's message
// (`points.csv: row 3 (line 4): the scene with this row is invalid: barrier.top_width_m = 5:
// must be in [0, base_width_m = 4] (m)`).
void check_given_points(const Study& study, const PointsTable& table);

}  // namespace lsi

// The MPM model of a landslide scene (`landslide`, `barrier`, `methods.mpm`): the landslide
// geometry of the paper (45 deg front, body of i h x h squares, tail 3h; or a rectangle) on a
// horizontal base with its front touching the barrier's upstream toe at t = 0, moving at v0; the
// barrier a rigid trapezoid, fixed or sliding on the base. Documented in docs/reference/scene_schema.md
// ("MPM impact scenes").
#pragma once
#include "model/mpm_case.hpp"
#include "model/scene.hpp"

namespace lsi {

// Builds the MPM case of a landslide scene that has `methods.mpm`. Throws InputError.
MpmCase impact_case(const Scene& scene);

// The landslide's cross-section, front toe at (front_x, base_y), counter-clockwise.
std::vector<std::array<double, 2>> landslide_polygon(const SceneLandslide& l, double front_x,
                                                     double base_y);

}  // namespace lsi

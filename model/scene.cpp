#include "model/scene.hpp"

namespace lsi {

double SceneLandslide::equivalent_length_m() const {
  if (shape.kind == LandslideShape::Kind::Rectangle) return shape.length_m;
  // 45 deg front (h^2/2) + i squares (i h^2) + tail of length 3h (3h^2/2): area (2 + i) h^2.
  return (2.0 + shape.body_squares) * thickness_m;
}

double SceneLandslide::area_m2() const { return equivalent_length_m() * thickness_m; }

}  // namespace lsi

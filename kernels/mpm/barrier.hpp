// The rigid barrier of a scene: its shape (at zero displacement), the face friction tan(delta)
// and, unless fixed, its motion on the base. A fixed barrier runs no barrier dynamics.
#pragma once
#include <cmath>

#include "kernels/mpm/barrier_dynamics.hpp"
#include "kernels/mpm/barrier_shape.hpp"

namespace lsi::mpm {

struct Barrier {
  BarrierShape shape;
  double face_friction = 0.0;  // tan(delta), flow on the barrier's faces
  bool fixed = true;
  BarrierMotion motion;  // mass, base friction, gravity; state (displacement, velocity)
  // > 0: the upstream face's normal force is also reported in height bands of this size (m)
  // above the base (barrier_contact.hpp); the top band ends at the crest.
  double face_band_height = 0.0;
  int face_bands() const {
    return face_band_height > 0.0
               ? static_cast<int>(std::ceil(shape.height / face_band_height - 1e-9))
               : 0;
  }
};

}  // namespace lsi::mpm

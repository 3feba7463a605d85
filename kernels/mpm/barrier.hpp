// The rigid barrier of a scene: its shape (at zero displacement), the face friction tan(delta)
// and, unless fixed, its motion on the base. A fixed barrier runs no barrier dynamics.
#pragma once
#include "kernels/mpm/barrier_dynamics.hpp"
#include "kernels/mpm/barrier_shape.hpp"

namespace lsi::mpm {

struct Barrier {
  BarrierShape shape;
  double face_friction = 0.0;  // tan(delta), flow on the barrier's faces
  bool fixed = true;
  BarrierMotion motion;  // mass, base friction, gravity; state (displacement, velocity)
};

}  // namespace lsi::mpm

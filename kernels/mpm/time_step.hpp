// Time step control (the paper's eq. 24 with the particle speed): the fastest signal crosses a
// cell in dx / (c + |v|_max), c the largest P-wave speed of the materials; the step is that times
// the Courant number, recomputed every step, never larger than the user's maximum.
#pragma once
#include <algorithm>

namespace lsi::mpm {

inline double stable_time_step(double cell_size, double wave_speed, double max_speed,
                               double courant, double max_time_step) {
  return std::min(courant * cell_size / (wave_speed + max_speed), max_time_step);
}

}  // namespace lsi::mpm

// Time step control (the paper's eq. 24 with the particle speed): the fastest signal crosses a
// cell in dx / (c + |v|_max), c the largest P-wave speed of the points; the step is that times
// the Courant number, recomputed every step, never larger than the user's maximum.
//
// The P-wave speed of a point is that of its CURRENT density: the point adds V sigma grad(w) to
// its nodes, sigma growing at the modulus M whatever the point's volume V = J V0, while its mass
// rho0 V0 stays, so its stiffness-to-mass ratio, hence its squared wave speed, is J M / rho0:
//   c = c0 sqrt(J),   c0 = sqrt(M / rho0) (Material::wave_speed).
// Points that a flow tears apart expand with no stress (tension cut-off, J of 5-40 in the
// splashing overtopping flow of the reference scenes); when they are compressed again they are
// that much stiffer per unit mass. With c0 alone such runs became unstable (a period-2 oscillation
// between two expanded points behind a fixed barrier, growing x2 per step until a point left the
// grid; docs/theory/mpm.md, "Time step of expanded points"). J is taken as at least 1: a compressed point
// is softer, and ignoring that keeps the step of a run without expansion exactly as before.
#pragma once
#include <algorithm>
#include <cmath>

namespace lsi::mpm {

// wave_speed: largest P-wave speed of the materials at their initial density (m/s);
// max_expansion: largest V / V0 over the points (>= 1); max_speed: largest point speed (m/s).
inline double stable_time_step(double cell_size, double wave_speed, double max_expansion,
                               double max_speed, double courant, double max_time_step) {
  const double c = wave_speed * std::sqrt(std::max(max_expansion, 1.0));
  return std::min(courant * cell_size / (c + max_speed), max_time_step);
}

}  // namespace lsi::mpm

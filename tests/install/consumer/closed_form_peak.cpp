// The two-body model (kernels/closed_form/two_body_model.hpp) from an installed lsi: prints the
// peak force and the impulse of the pulse for the inputs on the command line.
//   usage: closed_form_peak LANDSLIDE_MASS VELOCITY EQUIVALENT_LENGTH BARRIER_MASS LAMBDA TAU
// (SI units; BARRIER_MASS `inf` for a fixed barrier).
#include <cstdio>
#include <cstdlib>

#include "kernels/closed_form/two_body_model.hpp"

int main(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr,
                 "usage: %s LANDSLIDE_MASS VELOCITY EQUIVALENT_LENGTH BARRIER_MASS LAMBDA TAU\n",
                 argv[0]);
    return 2;
  }
  double in[6];
  for (int i = 0; i < 6; ++i) in[i] = std::strtod(argv[i + 1], nullptr);
  lsi::TwoBodyCoefficients c;
  c.lambda = in[4];
  c.tau = in[5];
  const lsi::TwoBodyImpact r = lsi::two_body_impact(in[0], in[1], in[2], in[3], c);
  std::printf("peak_force %.17g\n", r.pulse.peak);
  std::printf("impulse %.17g\n", r.pulse.pulse_impulse());
  return 0;
}

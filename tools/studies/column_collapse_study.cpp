// Reruns the granular column collapse of tests/mpm/test_mpm_column_collapse.cpp with other
// settings: the resolution, sensitivity and mu(I) tables of docs/vv/verification.md. Not a test
// (nothing asserted); built beside the tests, run by hand. Serial backend (or the default host
// space), as the test's a = 3 case; `space=default` runs it on a GPU in a CUDA build.
//
//   column_collapse_study a cells_per_L0 [key=value ...]
//     L0=1 (m)  phi=30 (deg)  nu=0.3  base=tan(phi) (Coulomb mu, or no-slip)  room=1.6
//     dump=FILE  (the final points, "x y" per line in units of L0 from the wall and base)
//     k0=K       (start from the geostatic stress sigma_xx = sigma_zz = K sigma_yy, not from zero)
//     space=default  (run on Kokkos's default execution space, a GPU in a CUDA build, instead
//                     of Serial: the fine grids of docs/notes/verification.md)
//     trace=1    (the energy shares every T/16, T = sqrt(H0 / g); the deposit then differs
//                 from the test's by up to 1 %: the output times clip the time step)
//     mu_i=glass-beads  (Jop, Forterre & Pouliquen 2006: phi_s = asin(tan 20.9 deg) = 22.45,
//                        phi_2 = asin(tan 32.76 deg) = 40.05 deg, I0 = 0.279, d = 0.5 mm,
//                        rho_s = 2450 kg/m^3; sets phi to phi_s unless phi= is given after it)
// e.g. the mu(I) row of docs/notes/verification.md at 24 cells:
//   column_collapse_study 3 24 L0=0.1 mu_i=glass-beads base=0.643 room=2.2
#include <Kokkos_Core.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "support/column_collapse.hpp"
#include "study_space.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: %s a cells_per_L0 [L0=.. phi=.. nu=.. base=.. room=.. "
                 "k0=.. mu_i=glass-beads dump=FILE trace=1 space=default]\n",
                 argv[0]);
    return 2;
  }
  lsi::test::ColumnSpec spec;
  std::string dump;
  bool default_space = false;
  spec.a = std::atof(argv[1]);
  spec.cells_per_L0 = std::atoi(argv[2]);
  constexpr double kPi = 3.14159265358979323846;
  for (int i = 3; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto eq = arg.find('=');
    const std::string key = arg.substr(0, eq);
    const std::string value = eq == std::string::npos ? "" : arg.substr(eq + 1);
    if (key == "L0")
      spec.L0 = std::atof(value.c_str());
    else if (key == "phi")
      spec.friction_angle_deg = std::atof(value.c_str());
    else if (key == "nu")
      spec.poisson_ratio = std::atof(value.c_str());
    else if (key == "base" && value == "no-slip")
      spec.base = lsi::test::ColumnSpec::Base::NoSlip;
    else if (key == "base") {
      spec.base = lsi::test::ColumnSpec::Base::Coulomb;
      spec.base_friction = std::atof(value.c_str());
    } else if (key == "room")
      spec.room = std::atof(value.c_str());
    else if (key == "dump")
      dump = value;
    else if (key == "trace")
      spec.trace = value == "1";
    else if (key == "k0")
      spec.geostatic_k0 = std::atof(value.c_str());
    else if (key == "space" && value == "default")
      default_space = true;
    else if (key == "mu_i" && value == "glass-beads") {
      spec.friction_angle_deg = std::asin(std::tan(20.9 * kPi / 180)) * 180 / kPi;
      spec.limit_friction_angle_deg = std::asin(std::tan(32.76 * kPi / 180)) * 180 / kPi;
      spec.reference_inertial_number = 0.279;
      spec.grain_diameter = 0.5e-3;
      spec.grain_density = 2450;
    } else {
      std::fprintf(stderr, "unknown argument %s\n", argv[i]);
      return 2;
    }
  }
  if (!(spec.a > 0) || spec.cells_per_L0 < 2 || !(spec.L0 > 0) || !(spec.room > 1) ||
      !(spec.poisson_ratio >= 0 && spec.poisson_ratio < 0.5)) {
    std::fprintf(stderr, "need a > 0, cells_per_L0 >= 2, L0 > 0, room > 1, 0 <= nu < 0.5\n");
    return 2;
  }
  Kokkos::ScopeGuard kokkos(argc, argv);
  const lsi::test::Collapse R = default_space
                                    ? lsi::test::collapse<Kokkos::DefaultExecutionSpace>(spec)
                                    : lsi::test::collapse<lsi::test::StudySpace>(spec);
  const std::string space_name =
      default_space ? Kokkos::DefaultExecutionSpace::name() : lsi::test::StudySpace::name();
  using Base = lsi::test::ColumnSpec::Base;
  const std::string base = spec.base == Base::NoSlip    ? std::string("no slip")
                           : spec.base == Base::Coulomb ? "mu " + std::to_string(spec.base_friction)
                                                        : std::string("tan(phi)");
  std::printf("a = %g, %d cells per L0, L0 = %g m, phi = %.3f deg, base %s, mu(I) %s\n", spec.a,
              spec.cells_per_L0, spec.L0, spec.friction_angle_deg, base.c_str(),
              spec.reference_inertial_number > 0 ? "on" : "off");
  lsi::test::print(R, space_name.c_str());
  std::printf("room to the right wall: %.1f cells\n", R.right_room);
  if (!dump.empty()) {
    std::FILE* f = std::fopen(dump.c_str(), "w");
    if (!f) {
      std::fprintf(stderr, "cannot write %s\n", dump.c_str());
      return 1;
    }
    for (std::size_t q = 0; q + 1 < R.deposit.size(); q += 2)
      std::fprintf(f, "%.6f %.6f\n", R.deposit[q], R.deposit[q + 1]);
    std::fclose(f);
  }
  return R.status != lsi::mpm::Status::Finished || R.right_room < 2 ? 1 : 0;
}

// A block of the column-collapse material (Mohr-Coulomb, phi = 30 deg, psi = 0, c = 0, E of the
// a = 3 column; or the same stiffness linear elastic) dropped at v0 onto the rough base (Coulomb
// mu = tan phi) from one cell above it, stress-free as in free fall. Does it bounce? The
// restitution e is the largest upward velocity of the block's centroid after the impact over
// the downward one before it. A dense granular layer dropped flat does not bounce (e near 0); a
// continuum that compresses elastically where it cannot spread sideways does. Used in
// docs/notes/verification.md ("Tried: the continuum's impact restitution"). Not a test (nothing
// asserted); built beside the tests, run by hand, Serial backend (or the default host space).
//
//   block_drop_study mc|elastic cell_size_m width_m height_m v0_m_s [nu=0.3]
// e.g. the rows of docs/notes/verification.md:
//   block_drop_study mc 0.05 1 1 3;  block_drop_study mc 0.05 4 0.5 3
#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"
#include "study_space.hpp"

namespace {
using namespace lsi::mpm;
constexpr double kG = 9.81, kPi = 3.14159265358979323846;

template <class Exec>
int study(bool plastic, double dx, double width, double height, double v0, double nu) {
  using Mem = typename Exec::memory_space;
  Material m;
  m.model = plastic ? Material::Model::MohrCoulomb : Material::Model::LinearElastic;
  m.density = 1800;
  m.poisson_ratio = nu;
  m.young_modulus = m.density * kG * 3.0 / 0.005;  // the a = 3 column's (H0 = 3 m)
  m.friction_angle = 30.0 * kPi / 180.0;
  // Room above for a rebound at v0 (v0^2 / 2g) and beside for the spreading block.
  const double x0 = 2 * dx, y0 = 2 * dx, gap = dx, side = 2.0 * height + 1.0;
  const double lo[2] = {0, 0}, hi[2] = {x0 + 2 * side + width + 2 * dx,
                                        y0 + gap + height + v0 * v0 / (2 * kG) + 0.5 + 2 * dx};
  Grid<Mem> grid(lo, hi, dx);
  BodySpec b;
  const double xl = x0 + side, yb = y0 + gap;
  b.polygon = {{{xl, yb}}, {{xl + width, yb}}, {{xl + width, yb + height}}, {{xl, yb + height}}};
  b.velocity = {0.0, -v0};
  auto p = build_particles<Mem>({b}, {m}, lo, dx);
  Boundaries walls;
  walls.left = {true, x0, 0.0};
  walls.bottom = {true, y0, std::tan(m.friction_angle)};
  walls.right = {true, grid.upper(0) - 2 * dx, 0.0};
  Settings s;
  s.courant = 0.5;
  Solver<Exec> solver(grid, p, {m}, walls, s);
  // P-wave speed (plane strain, constrained modulus); the run covers several wave transits and
  // the time a rebound at v0 would take to rise and fall back.
  const double M = m.young_modulus * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  const double c = std::sqrt(M / m.density);
  const double t_end = 8 * height / c + 2 * v0 / kG + 0.2, out = height / c / 8;
  const EnergyReport e0 = solver.energy();
  double t = 0, v_down = 0, v_up = -1e300, t_up = 0;
  auto v = Kokkos::create_mirror_view(Kokkos::HostSpace(), p.velocity);
  while (t < t_end) {
    t += out;
    const Status status = solver.run(t, out);
    if (status != Status::Finished) {
      std::printf("stopped at t = %.4f s: %s\n", t, describe(status));
      return 1;
    }
    Kokkos::deep_copy(v, p.velocity);
    double vy = 0;  // all points carry the same mass
    for (int q = 0; q < p.count; ++q) vy += v(q, 1);
    vy /= p.count;
    v_down = std::min(v_down, vy);
    if (vy > v_up) {
      v_up = vy;
      t_up = t;
    }
  }
  const EnergyReport e = solver.energy();
  std::printf(
      "%s, nu %.2f, cell %.4g m, block %.4g x %.4g m, v0 %.3g m/s (P-wave %.1f m/s, "
      "transit %.4f s): centroid velocity most downward %.3f m/s, most upward %.3f m/s "
      "(t = %.3f s): restitution %.3f; plastic work %.3f and wall work %.3f of the "
      "initial kinetic energy; energy residual %+.4f; %ld steps\n",
      plastic ? "Mohr-Coulomb" : "elastic", nu, dx, width, height, v0, c, height / c, v_down, v_up,
      t_up, v_up / -v_down, e.plastic / e0.kinetic, e.boundary / e0.kinetic,
      solver.energy_residual(e), solver.steps());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: %s mc|elastic cell_size_m width_m height_m v0_m_s [nu=0.3]\n",
                 argv[0]);
    return 2;
  }
  const std::string model = argv[1];
  const double dx = std::atof(argv[2]), width = std::atof(argv[3]), height = std::atof(argv[4]);
  const double v0 = std::atof(argv[5]), nu = argc > 6 ? std::atof(argv[6]) : 0.3;
  if ((model != "mc" && model != "elastic") || !(dx > 0 && dx <= 0.1) ||
      !(width >= 2 * dx && width <= 10) || !(height >= 2 * dx && height <= 5) ||
      !(v0 > 0 && v0 <= 10) || !(nu >= 0 && nu < 0.5)) {
    std::fprintf(stderr,
                 "need mc|elastic, 0 < cell_size <= 0.1, 2 cells <= width <= 10, "
                 "2 cells <= height <= 5, 0 < v0 <= 10, 0 <= nu < 0.5\n");
    return 2;
  }
  Kokkos::ScopeGuard kokkos(argc, argv);
  return study<lsi::test::StudySpace>(model == "mc", dx, width, height, v0, nu);
}

// A thin sheet of the column-collapse material (Mohr-Coulomb, phi = 30 deg, psi = 0, c = 0; the
// model of tests/support/column_collapse.hpp) launched at v0 over either a rough base (Coulomb
// mu = tan phi) or a 0.3 m bed of the same material on a no-slip base, until it stops. The
// distance its centroid travels is compared with a rigid sheet's:
//   base: v0^2 / (2 g tan(phi))   (the base's Coulomb law)
//   bed:  v0^2 / (2 g sin(phi))   (a psi = 0 Mohr-Coulomb material shearing on a horizontal
//                                  plane carries tau / sigma_n = sin(phi) there: Davis 1968;
//                                  docs/theory/mpm.md, "Rate-dependent friction")
// The bed case is the a = 3 column's tail (docs/notes/verification.md, "Why the farthest point grows
// with the grid"): a sheet one or two points thick shares its grid nodes with the material under
// it, and the grid drags the two to one velocity. Not a test (nothing asserted); built beside the
// tests, run by hand, Serial backend (or the default host space).
//
//   sheet_on_bed_study base|bed cell_size_m sheet_thickness_m [v0_m_s=3]
// e.g. the table of docs/notes/verification.md:
//   sheet_on_bed_study bed 0.05 0.05;  sheet_on_bed_study bed 0.025 0.05;
//   sheet_on_bed_study bed 0.0125 0.05
#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"
#include "study_space.hpp"

namespace {
using namespace lsi::mpm;
constexpr double kG = 9.81, kPi = 3.14159265358979323846;

template <class Exec>
int study(bool on_bed, double dx, double thickness, double v0) {
  using Mem = typename Exec::memory_space;
  const double phi = 30.0 * kPi / 180.0;
  Material m;
  m.model = Material::Model::MohrCoulomb;
  m.density = 1800;
  m.poisson_ratio = 0.3;
  m.young_modulus = m.density * kG * 3.0 / 0.005;  // the a = 3 column's (H0 = 3 m)
  m.friction_angle = phi;
  const double bed = on_bed ? 0.3 : 0.0, length = 1.0;  // m
  const double x0 = 2 * dx, y0 = 2 * dx, top = y0 + bed;
  const double lo[2] = {0, 0}, hi[2] = {x0 + 4.0, top + thickness + 1.0};
  Grid<Mem> grid(lo, hi, dx);
  std::vector<BodySpec> bodies(1);
  BodySpec& sheet = bodies[0];
  sheet.polygon = {{{x0 + 0.2, top}},
                   {{x0 + 0.2 + length, top}},
                   {{x0 + 0.2 + length, top + thickness}},
                   {{x0 + 0.2, top + thickness}}};
  sheet.velocity = {v0, 0.0};
  sheet.geostatic_k0 = 0.5;
  sheet.surface_y = top + thickness;
  if (on_bed) {
    BodySpec b;
    b.polygon = {{{x0, y0}}, {{x0 + 3.9, y0}}, {{x0 + 3.9, top}}, {{x0, top}}};
    b.geostatic_k0 = 0.5;
    b.surface_y = top;
    bodies.push_back(b);
  }
  auto p = build_particles<Mem>(bodies, {m}, lo, dx);
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.position);
  std::vector<double> x_start(p.count);
  std::vector<int> in_sheet;
  for (int q = 0; q < p.count; ++q) {
    x_start[q] = x(q, 0);
    if (x(q, 1) > top) in_sheet.push_back(q);
  }
  Boundaries walls;
  walls.left = {true, x0, 0.0};
  walls.bottom =
      on_bed ? Wall{true, y0, 0.0, false, /*no_slip=*/true} : Wall{true, y0, std::tan(phi)};
  walls.right = {true, grid.upper(0) - 2 * dx, 0.0};
  Settings s;
  s.courant = 0.5;
  Solver<Exec> solver(grid, p, {m}, walls, s);
  const double mu = on_bed ? std::sin(phi) : std::tan(phi);
  const double rigid = v0 * v0 / (2 * mu * kG), t_stop = v0 / (mu * kG);
  double t = 0;
  Status status = Status::Finished;
  while (t < 3 * t_stop && status == Status::Finished) {
    t += 0.05;
    status = solver.run(t, 0.05);
  }
  Kokkos::deep_copy(x, p.position);
  auto v = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.velocity);
  double travel = 0, vmax = 0, front = -1e300, bed_shift = 0;
  for (int q : in_sheet) {
    travel += x(q, 0) - x_start[q];
    vmax = std::max(vmax, std::hypot(v(q, 0), v(q, 1)));
    front = std::max(front, x(q, 0));
  }
  travel /= in_sheet.size();
  for (int q = 0; q < p.count; ++q)
    if (x_start[q] < x0 + 3.9 && x(q, 1) < top)
      bed_shift = std::max(bed_shift, x(q, 0) - x_start[q]);
  std::printf(
      "%s, cell %.4g m, sheet %.4g m (%.1f points thick), v0 %.3g m/s: %s after %.2f s "
      "(%ld steps); sheet centroid travelled %.4f m, rigid sheet %.4f m (mu = %.3f): "
      "ratio %.3f; front %.3f m past the start's; largest bed point displacement %.3f m; "
      "largest sheet speed %.1e m/s\n",
      on_bed ? "bed" : "base", dx, thickness, thickness / (dx / 2), v0, describe(status), t,
      solver.steps(), travel, rigid, mu, travel / rigid, front - (x0 + 0.2 + length), bed_shift,
      vmax);
  return status == Status::Finished ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s base|bed cell_size_m sheet_thickness_m [v0_m_s=3]\n", argv[0]);
    return 2;
  }
  const std::string where = argv[1];
  const double dx = std::atof(argv[2]), thickness = std::atof(argv[3]);
  const double v0 = argc > 4 ? std::atof(argv[4]) : 3.0;
  if ((where != "base" && where != "bed") || !(dx > 0 && dx <= 0.1) ||
      !(thickness >= dx / 2 && thickness <= 0.5) || !(v0 > 0 && v0 <= 10)) {
    std::fprintf(stderr,
                 "need base|bed, 0 < cell_size <= 0.1, cell_size / 2 <= thickness <= 0.5, "
                 "0 < v0 <= 10\n");
    return 2;
  }
  Kokkos::ScopeGuard kokkos(argc, argv);
  return study<lsi::test::StudySpace>(where == "bed", dx, thickness, v0);
}

// The sudden stop of a saturated block at a wall, and the pressure-impulse theory it is checked
// against (Cooker & Peregrine 1995, J. Fluid Mech. 297, 193-214). Shared by
// test_mpm_pressure_impulse.cpp (the assertions) and pressure_impulse_study.cpp (the tables of
// docs/theory/two_phase.md, "The face jet").
//
// A block of liquefied saturated soil (Mohr-Coulomb skeleton with phi = c = 0: no strength, only
// the pore liquid carries load), height H on a smooth impermeable base, length L, moves at U onto
// a smooth impermeable vertical wall; no gravity. Take x from the wall into the block, y up from
// the base. If the mixture were incompressible (density rho_m), the impact would change its
// velocity at once by -grad(P) / rho_m, P the pressure impulse (the integral of the pressure over
// the impact), harmonic in the block with
//   P = 0 on the free top (y = H) and back (x = L),  dP/dy = 0 on the base,  dP/dx = -rho_m U at
//   the wall (the wall stops the normal velocity).
// Separating variables, with k_n = (n + 1/2) pi / H and A_n = 2 U (-1)^n / (k_n H) (the cosine
// series of 1 on [0, H]):
//   P(x, y) = rho_m sum_n (A_n / k_n) cos(k_n y) sinh(k_n (L - x)) / cosh(k_n L),
//   vertical velocity after the impact  v(x, y) = sum_n A_n sin(k_n y) sinh(k_n (L - x)) / cosh(k_n L),
//   wall impulse     I = integral of P(0, y) dy = 2 rho_m U sum_n tanh(k_n L) / (k_n^3 H)
//                        (-> 2 * 7 zeta(3) / pi^3 rho_m U H^2 = 0.5428 rho_m U H^2 for L >> H),
//   base impulse = the block's vertical momentum = integral of P(x, 0) dx
//                    = rho_m sum_n (A_n / k_n^2) (1 - 1 / cosh(k_n L))   (-> rho_m U H^2 / 2).
// At the wall (L >> H) the series sums to v(0, y) = (2 U / pi) ln cot(pi (1 - y/H) / 4): 0 at the
// base, 0.561 U at mid-height and a logarithmic singularity at the top corner, where the free
// surface meets the wall: the jet of a wave's flip-through. Averaged over the corner cell (size dx)
// it is about (2 U / pi) (ln(4 H / (pi dx)) + 1): 1.71 U at 8 cells per height, 2.15 U at 16,
// growing by (2 / pi) ln 2 = 0.44 U per halving of the cell, without a limit.
//
// The MPM mixture is compressible (bulk modulus K_L / n), so the impact takes a few acoustic times
// H / c and leaves the mixture ringing. Linear acoustics with the wall and base HELD (bilateral:
// no separation) oscillates about the incompressible state: the time means of the wall impulse,
// of the vertical momentum and of the velocities over many transits are the theory's. With
// unilateral walls (the impact scenes' contact) the flat block separates from the wall and the
// base at the first rarefaction and rebounds: a different, nonlinear problem.
#pragma once
#include <Kokkos_Core.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "kernels/mpm/two_phase/two_phase_builder.hpp"
#include "kernels/mpm/two_phase/two_phase_solver.hpp"

namespace lsi::test::pressure_impulse {
using namespace lsi::mpm;
using namespace lsi::mpm::two_phase;

constexpr double kPi = 3.14159265358979323846;
constexpr int kTerms = 200000;  // series terms: the x-averaged terms fall as 1 / k^2

// The block: height H, length L, speed U, mixture density rho_m = (1 - n) rho_S + n rho_L.
struct Block {
  double height = 1.0, length = 4.0;  // m
  double speed = 0.1;                 // m/s: Mach U / c = 5.5e-4, U t / H < 0.033 in the window
  double porosity = 0.5, grain_density = 2600.0, liquid_density = 1000.0;
  double liquid_bulk_modulus = 3e7;  // Pa: c = sqrt(K_L / (n rho_m)) = 183 m/s
  double mixture_density() const {
    return (1 - porosity) * grain_density + porosity * liquid_density;
  }
  double wave_speed() const {
    return std::sqrt(liquid_bulk_modulus / (porosity * mixture_density()));
  }
  double impulse_scale() const { return mixture_density() * speed * height * height; }  // N s/m
};

// cosh(k (L - x)) / cosh(k L), x in [0, L], without overflow.
inline double cosh_ratio(double k, double L, double x) {
  return std::exp(-k * x) * (1 + std::exp(-2 * k * (L - x))) / (1 + std::exp(-2 * k * L));
}

// The theory's wall impulse, N s/m.
inline double theory_wall_impulse(const Block& b) {
  double s = 0.0;
  for (int n = 0; n < kTerms; ++n) {
    const double k = (n + 0.5) * kPi / b.height;
    s += std::tanh(k * b.length) / (k * k * k * b.height);
  }
  return 2.0 * b.mixture_density() * b.speed * s;
}

// The theory's vertical momentum of the block after the impact (the base's impulse), N s/m.
inline double theory_vertical_momentum(const Block& b) {
  double s = 0.0;
  for (int n = 0; n < kTerms; ++n) {
    const double k = (n + 0.5) * kPi / b.height;
    const double A = 2 * b.speed * (n % 2 ? -1.0 : 1.0) / (k * b.height);
    s += A / (k * k) * (1 - cosh_ratio(k, b.length, b.length));  // 1 - 1 / cosh(k L)
  }
  return b.mixture_density() * s;
}

// The theory's vertical velocity averaged over x in [x0, x1] (from the wall), y in [y0, y1], m/s.
inline double theory_vertical_velocity(const Block& b, double x0, double x1, double y0, double y1) {
  const double H = b.height, L = b.length;
  double s = 0.0;
  for (int n = 0; n < kTerms; ++n) {
    const double k = (n + 0.5) * kPi / H;
    const double A = 2 * b.speed * (n % 2 ? -1.0 : 1.0) / (k * H);
    const double iy = (std::cos(k * y0) - std::cos(k * y1)) / k;  // integral of sin(k y)
    // integral of sinh(k (L - x)) / cosh(k L) over [x0, x1]
    const double ix = (cosh_ratio(k, L, x0) - cosh_ratio(k, L, x1)) / k;
    s += A * iy * ix;
  }
  return s / ((x1 - x0) * (y1 - y0));
}

// How the block meets the wall and how it is discretised.
struct Setup {
  int cells = 16;                             // per height; 2 x 2 points per cell
  Transfer transfer = Transfer::FlipPic;      // with flip_ratio 1
  bool held = true;                           // wall and base bilateral: the linear problem (above)
  bool cell_pore_pressure = true;             // TwoPhaseSettings::cell_pore_pressure
  double window_begin = 10, window_end = 60;  // the averaging window, in acoustic times H / c
};

struct Measured {
  bool finished = false;
  long steps = 0;
  double wall_impulse = 0.0;        // time mean over the window of the wall's impulse, N s/m
  double vertical_momentum = 0.0;   // time mean of the block's vertical momentum, N s/m
  double largest_wall_force = 0.0;  // largest |F_x| on the wall in the window, N/m
  // Time-mean vertical velocity of the points of the column next to the wall, per cell of height
  // (by initial position), m/s; the last entry is the corner cell.
  std::vector<double> wall_velocity;
  double corner_point_speed = 0.0;  // largest time-mean speed of a point of the corner cell, m/s
};

// The block touches the wall at t = 0. Velocities are the mixture's (mass-weighted solid and
// liquid); each point is binned by its initial position (it moves U t < 0.04 H in the window).
template <class Exec>
Measured impact(const Block& b, const Setup& setup) {
  using Mem = typename Exec::memory_space;
  const int cells = setup.cells;
  const double H = b.height, L = b.length, dx = H / cells;
  const double wall = L + 2 * dx;  // x of the wall: a grid line
  const double lo[2] = {0.0, -2 * dx}, hi[2] = {wall + 4 * dx, H + 8 * dx};
  TwoPhaseGrid<Mem> grid(lo, hi, dx);
  Material skeleton;
  skeleton.model = Material::Model::MohrCoulomb;  // phi = c = 0
  skeleton.density = b.grain_density;
  skeleton.young_modulus = 2e6;
  skeleton.poisson_ratio = 0.25;
  Liquid liquid;
  liquid.density = b.liquid_density;
  liquid.bulk_modulus = b.liquid_bulk_modulus;
  TwoPhaseBodySpec body;
  body.polygon = {{{wall - L, 0.0}}, {{wall, 0.0}}, {{wall, H}}, {{wall - L, H}}};
  body.porosity = b.porosity;
  body.hydraulic_conductivity = 1e-4;  // undrained: drag time k / (n g) = 20 us
  body.velocity = {b.speed, 0.0};
  auto pts = build_two_phase_particles<Mem>({body}, {skeleton}, liquid, lo, dx);
  Boundaries walls;  // the same for the liquid: impermeable
  walls.right = {true, wall, 0.0, setup.held};
  walls.bottom = {true, 0.0, 0.0, setup.held};
  TwoPhaseSettings s;
  s.gravity[1] = 0.0;
  s.drag = Drag::SemiImplicit;
  s.transfer = setup.transfer;
  s.flip_ratio = 1.0;
  s.cell_pore_pressure = setup.cell_pore_pressure;
  TwoPhaseSolver<Exec> solver(grid, pts, {skeleton}, liquid, walls, s);

  const double t_begin = setup.window_begin * H / b.wave_speed();
  const double t_end = setup.window_end * H / b.wave_speed();
  // Copies (create_mirror, not a view of the points' own memory on the host): the points'
  // initial positions and their masses, in the order of their ids.
  auto x0 = Kokkos::create_mirror(Kokkos::HostSpace(), pts.solid.position);
  auto ms = Kokkos::create_mirror(Kokkos::HostSpace(), pts.solid.mass);
  auto ml = Kokkos::create_mirror(Kokkos::HostSpace(), pts.liquid_mass);
  Kokkos::deep_copy(x0, pts.solid.position);
  Kokkos::deep_copy(ms, pts.solid.mass);
  Kokkos::deep_copy(ml, pts.liquid_mass);
  auto vs = Kokkos::create_mirror_view(pts.solid.velocity);
  auto vl = Kokkos::create_mirror_view(pts.liquid_velocity);
  // The solver reorders its points (kernels/mpm/sort_points.hpp): mean_v is in the order of the
  // points' ids, the velocities in the solver's order.
  auto id = Kokkos::create_mirror_view(pts.solid.id);
  std::vector<double> mean_v[2];
  for (auto& v : mean_v) v.assign(pts.count, 0.0);
  Measured m;
  double impulse = 0.0, window = 0.0;
  while (solver.time() < t_end) {
    if (solver.step() != Status::Running) return m;
    const double dt = solver.time_step();
    impulse += solver.wall_force()[0] * dt;  // the block's push on the wall
    if (solver.time() < t_begin) continue;
    window += dt;
    m.wall_impulse += dt * impulse;
    m.largest_wall_force = std::max(m.largest_wall_force, std::fabs(solver.wall_force()[0]));
    Kokkos::deep_copy(vs, pts.solid.velocity);
    Kokkos::deep_copy(vl, pts.liquid_velocity);
    Kokkos::deep_copy(id, pts.solid.id);
    for (int q = 0; q < pts.count; ++q) {
      const int i = id(q);
      for (int d = 0; d < 2; ++d)
        mean_v[d][i] += dt * (ms(i) * vs(q, d) + ml(i) * vl(q, d)) / (ms(i) + ml(i));
      m.vertical_momentum += dt * (ms(i) * vs(q, 1) + ml(i) * vl(q, 1));
    }
  }
  m.finished = true;
  m.steps = solver.steps();
  m.wall_impulse /= window;
  m.vertical_momentum /= window;
  m.wall_velocity.assign(cells, 0.0);
  std::vector<int> count(cells, 0);
  for (int q = 0; q < pts.count; ++q) {
    if (x0(q, 0) < wall - dx) continue;  // the column of points next to the wall
    const int j = std::min(cells - 1, static_cast<int>(x0(q, 1) / dx));
    const double v[2] = {mean_v[0][q] / window, mean_v[1][q] / window};
    m.wall_velocity[j] += v[1];
    count[j] += 1;
    if (j == cells - 1)
      m.corner_point_speed = std::max(m.corner_point_speed, std::hypot(v[0], v[1]));
  }
  for (int j = 0; j < cells; ++j) m.wall_velocity[j] /= count[j];
  return m;
}

}  // namespace lsi::test::pressure_impulse

// The granular column collapse of tests/mpm/test_mpm_column_collapse.cpp (its header describes
// the model, the measurements and the laws), shared with the study program
// tools/studies/column_collapse_study.cpp that reruns the variants of docs/vv/verification.md.
#pragma once
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"

namespace lsi::test {
using namespace lsi::mpm;

inline constexpr double kColumnG = 9.81;
inline constexpr double kColumnPi = 3.14159265358979323846;

// Lube et al. (2005): L_f / L0 (outside the transition 1.8 < a < 2.8).
inline double lube_runout(double a) { return 1.0 + (a < 2.3 ? 1.2 * a : 1.9 * std::cbrt(a * a)); }
// Lajeunesse et al. (2005), for the scatter: L_f / L0.
inline double lajeunesse_runout(double a) {
  return 1.0 + (a < 2.3 ? 1.8 * a : 2.3 * std::cbrt(a * a));
}

// Thickness that bounds the resolved deposit body: L0/16, one cell (two points) of the a = 3 grid,
// fixed in units of L0 so that every resolution measures the same thing (docs/vv/verification.md).
inline constexpr double kBodyThickness = 1.0 / 16;

struct Collapse {
  double a = 0, Lf = 0, Hf = 0;  // L_f / L0, H_f / L0
  double Lbody = 0;              // end of the deposit thicker than kBodyThickness L0, / L0
  double Lthin = 0;              // the same at a quarter of it (L0/64; resolved from 64 cells)
  // Mass measures of the front (all points carry the same mass): the fraction of the column
  // beyond Lube's run-out and beyond 1.2 times it, and x99 / L0, the point with 1 % beyond it.
  double beyond_law = 0, beyond_law_120 = 0, x99 = 0;
  double residual = 0, t_over_T = 0, right_room = 0;
  double kinetic_ratio = 0;                      // kinetic / released potential energy at the end
  double plastic_share = 0, boundary_share = 0;  // of the released potential energy
  bool at_rest = false;
  long steps = 0;
  int points = 0;
  double seconds = 0;
  Status status = Status::Running;
  std::vector<double> deposit;  // final (x - x0, y - y0) / L0 of every point, interleaved
};

// The column and its model; the defaults are the test's (see its header).
struct ColumnSpec {
  double a = 0.5;  // aspect ratio H0 / L0
  int cells_per_L0 = 32;
  double L0 = 1.0;  // m
  double friction_angle_deg = 30.0;
  double poisson_ratio = 0.3;
  // The base: Coulomb friction tan(friction angle) by default, a given Coulomb mu, or no slip.
  enum class Base { MaterialFriction, Coulomb, NoSlip } base = Base::MaterialFriction;
  double base_friction = 0.0;  // Coulomb mu with Base::Coulomb
  double room = 1.6;           // the right wall at x0 + room * Lube's run-out (+ 3 cells)
  // mu(I) (kernels/mpm/constitutive/inertial_friction.hpp) when reference_inertial_number > 0:
  // friction_angle_deg is then the static angle.
  double limit_friction_angle_deg = 0.0, reference_inertial_number = 0.0;
  double grain_diameter = 0.0, grain_density = 0.0;  // m, kg/m^3
  // Print the energy shares every T/16 (the run then stops at T/16 intervals, not T/4: the
  // output times clip the time step, so the deposit differs from the test's by up to 1 %).
  bool trace = false;
  // >= 0: start from the geostatic stress, sigma_xx = sigma_zz = K0 sigma_yy = -K0 rho g depth
  double geostatic_k0 = -1.0;
};

template <class Exec>
Collapse collapse(const ColumnSpec& spec) {
  using Mem = typename Exec::memory_space;
  Collapse R;
  const double a = spec.a;
  const int cells_per_L0 = spec.cells_per_L0;
  R.a = a;
  const double L0 = spec.L0, H0 = a * L0, dx = L0 / cells_per_L0, h = dx / 2;
  Material m;
  m.model = Material::Model::MohrCoulomb;
  m.density = 1800;
  m.poisson_ratio = spec.poisson_ratio;
  m.young_modulus = m.density * kColumnG * H0 / 0.005;
  m.friction_angle = spec.friction_angle_deg * kColumnPi / 180.0;
  m.limit_friction_angle = spec.limit_friction_angle_deg * kColumnPi / 180.0;
  m.reference_inertial_number = spec.reference_inertial_number;
  m.grain_diameter = spec.grain_diameter;
  m.grain_density = spec.grain_density;
  m.dilatancy_angle = 0.0;
  m.cohesion = 0.0;
  m.tension_cutoff = 0.0;
  // Walls on grid lines two cells inside the grid; room on the right for 1.6 times the run-out of
  // the law by default (more than the measured over-prediction at a = 3).
  const double x0 = 2 * dx, y0 = 2 * dx;
  const double lo[2] = {0, 0},
               hi[2] = {x0 + spec.room * lube_runout(a) * L0 + 3 * dx, y0 + H0 + 4 * dx};
  Grid<Mem> grid(lo, hi, dx);
  BodySpec body;
  body.polygon = {{{x0, y0}}, {{x0 + L0, y0}}, {{x0 + L0, y0 + H0}}, {{x0, y0 + H0}}};
  body.points_per_cell_direction = 2;
  body.geostatic_k0 = spec.geostatic_k0;
  body.surface_y = y0 + H0;
  body.gravity = kColumnG;
  auto particles = build_particles<Mem>({body}, {m}, lo, dx);
  R.points = particles.count;
  Boundaries walls;
  walls.left = {true, x0, 0.0};
  using Base = ColumnSpec::Base;
  walls.bottom = {true, y0,
                  spec.base == Base::MaterialFriction ? std::tan(m.friction_angle)
                  : spec.base == Base::Coulomb        ? spec.base_friction
                                                      : 0.0,
                  false, /*no_slip=*/spec.base == Base::NoSlip};
  const double x_right = grid.upper(0) - 2 * dx;
  walls.right = {true, x_right, 0.0};
  Settings s;
  s.courant = 0.5;
  Solver<Exec> solver(grid, particles, {m}, walls, s);

  const double T = std::sqrt(H0 / kColumnG);
  const EnergyReport e0 = solver.energy();
  const auto start = std::chrono::steady_clock::now();
  EnergyReport e = e0;
  // The run goes in chunks of T/4 (T/16 with spec.trace, which prints the energy at each), and
  // the rest check comes every T/4.
  const int per_check = spec.trace ? 4 : 1;
  const double chunk = 0.25 * T / per_check;
  double t = 0;
  for (int i = 1; i <= 40 * per_check; ++i) {
    t += chunk;
    R.status = solver.run(t, chunk);
    if (R.status != Status::Finished) return R;
    e = solver.energy();
    const double released = e0.potential - e.potential;
    if (spec.trace)
      std::printf(
          "[energy] t/T %.4f  released/initial potential %.4f  of the released: "
          "kinetic %.4f elastic %.4f plastic %.4f wall work %.4f\n",
          t / T, released / e0.potential, e.kinetic / released, e.elastic / released,
          e.plastic / released, e.boundary / released);
    if (i % per_check != 0) continue;
    R.kinetic_ratio = e.kinetic / released;
    if (t >= 2 * T && R.kinetic_ratio < 1e-3) {
      R.at_rest = true;
      break;
    }
  }
  R.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  R.t_over_T = t / T;
  R.steps = solver.steps();
  R.residual = solver.energy_residual(e);
  const double released = e0.potential - e.potential;
  R.plastic_share = e.plastic / released;
  R.boundary_share = e.boundary / released;
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), particles.position);
  double xm = -1e300, ym = -1e300;
  R.deposit.resize(2 * static_cast<std::size_t>(particles.count));
  for (int q = 0; q < particles.count; ++q) {
    xm = std::max(xm, x(q, 0));
    ym = std::max(ym, x(q, 1));
    R.deposit[2 * q] = (x(q, 0) - x0) / L0;
    R.deposit[2 * q + 1] = (x(q, 1) - y0) / L0;
  }
  R.Lf = (xm - x0 + h / 2) / L0;
  {
    const double law = lube_runout(a);
    int n_law = 0, n_120 = 0;
    std::vector<double> xs(particles.count);
    for (int q = 0; q < particles.count; ++q) {
      xs[q] = R.deposit[2 * q];
      n_law += xs[q] > law;
      n_120 += xs[q] > 1.2 * law;
    }
    R.beyond_law = static_cast<double>(n_law) / particles.count;
    R.beyond_law_120 = static_cast<double>(n_120) / particles.count;
    const std::size_t k = static_cast<std::size_t>(0.99 * particles.count);
    std::nth_element(xs.begin(), xs.begin() + k, xs.end());
    R.x99 = xs[k];
  }
  R.Hf = (ym - y0 + h / 2) / L0;
  // Deposit profile: highest point (+ h/2) in each grid column right of the left wall; the body
  // ends at the right edge of the last column at least kBodyThickness L0 thick.
  const int columns = static_cast<int>((xm - x0) / dx) + 1;
  std::vector<double> top(columns, 0.0);
  for (int q = 0; q < particles.count; ++q) {
    const int c = std::clamp(static_cast<int>((x(q, 0) - x0) / dx), 0, columns - 1);
    top[c] = std::max(top[c], x(q, 1) - y0 + h / 2);
  }
  const auto front = [&](double thickness) {
    for (int c = columns - 1; c >= 0; --c)
      if (top[c] >= thickness * L0) return (c + 1) * dx / L0;
    return 0.0;
  };
  R.Lbody = front(kBodyThickness);
  R.Lthin = front(kBodyThickness / 4);
  R.right_room = (x_right - xm) / dx;
  return R;
}

inline void print(const Collapse& R, const char* backend) {
  const double lube = lube_runout(R.a), laj = lajeunesse_runout(R.a);
  const double h_small = R.a, h_04 = std::pow(R.a, 0.4), h_13 = std::cbrt(R.a);
  std::printf(
      "[measured] %s a = %.1f (%d points, %ld steps, t = %.2f T, %.2f s, %s): "
      "L_f/L0 = %.3f vs Lube %.3f (%+.1f %%), Lajeunesse %.3f (%+.1f %%); "
      "body (>= L0/16 thick) ends at %.3f L0 (%+.1f %% Lube, %+.1f %% Lajeunesse), "
      "L0/64 thick at %.3f L0; "
      "H_f/L0 = %.3f vs a %.3f (%+.1f %%), a^0.4 %.3f (%+.1f %%), a^(1/3) %.3f (%+.1f %%); "
      "mass beyond Lube's run-out %.2f %%, beyond 1.2 times it %.2f %%, 1 %% beyond "
      "%.3f L0 (%+.1f %% Lube); "
      "energy residual %+.4f; plastic work %.3f, wall work %.3f of the released potential "
      "energy; kinetic/released %.1e\n",
      backend, R.a, R.points, R.steps, R.t_over_T, R.seconds, describe(R.status), R.Lf, lube,
      100 * (R.Lf / lube - 1), laj, 100 * (R.Lf / laj - 1), R.Lbody, 100 * (R.Lbody / lube - 1),
      100 * (R.Lbody / laj - 1), R.Lthin, R.Hf, h_small, 100 * (R.Hf / h_small - 1), h_04,
      100 * (R.Hf / h_04 - 1), h_13, 100 * (R.Hf / h_13 - 1), 100 * R.beyond_law,
      100 * R.beyond_law_120, R.x99, 100 * (R.x99 / lube - 1), R.residual, R.plastic_share,
      R.boundary_share, R.kinetic_ratio);
}

}  // namespace lsi::test

// Verification: geostatic column. A column of height h = 10 m and width 1 m stands on a smooth
// rigid base between smooth side walls, under gravity, 40 cells over the height (dx = 0.25 m,
// 2 x 2 points per cell). Smooth walls make it a one-dimensional (oedometric) problem whose
// static solution is
//   sigma_yy(y) = -rho g (h - y),   sigma_xx = sigma_zz = K0 sigma_yy,   K0 = nu / (1 - nu),
// and whose base reaction is the weight per metre, rho g h w.
//
// The solver has no damping, so the column is either started from the static stress
// (BodySpec::geostatic_k0) and must stay there, or started stress-free and time-averaged: an
// undamped linear system oscillates about its static solution, so its time mean is the static
// state. The means are taken with a Hann (raised-cosine) window over several periods of the
// fundamental mode (T1 = 4 h / c, c the constrained-modulus wave speed): its leakage of an
// oscillation of N periods falls as 1/N^3 instead of 1/N for a plain mean, so a short window
// (cheap on two shared cores) suffices.
//
// Measured: the time-averaged base stress, extrapolated linearly to the base from the points
// between 2 and 20 cells above it, against rho g h; the base reaction, Solver::wall_force()[1]
// (the force on the walls, negative: downwards), against the weight -rho g h w; K0.
//
// Boundary layer at the base (a property of the discretisation, not of this test): the wall acts
// on the nodes at or below it, but the quadratic B-spline of the first node above the wall is not
// zero there (N = 1/8 at one cell), so that free node takes 1/8 of the base traction in the weak
// form and the stresses of the points in the lowest two cell layers oscillate about the exact
// ones (2 points per node in 1D: more stress points than equations). The static discrete solution
// of the same 1D discretisation (B-spline stiffness, 2 points per cell, nodes <= wall fixed;
// solved directly, outside this test) gives a lowest-layer mean stress 16.9 % above
// rho g (h - dx/2), the next layer -4.8 %, then +1.7 %, -0.6 %, ... (decaying by ~3 per cell); the
// MPM time mean reproduces it (+17.0 %). The lowest layer is therefore reported and bounded, not
// compared at 2 %; the extrapolation from outside the layer is (1D static solution: +0.5 %).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"
#include "support/backends.hpp"

namespace {
using namespace lsi::mpm;

constexpr double kG = 9.81;

struct ColumnResult {
  double base_extrapolated = 0;  // Pa, sigma_yy extrapolated to the base (time mean)
  double slope = 0;              // Pa/m, d sigma_yy / dy of the fit (time mean)
  double lowest_layer = 0;       // Pa, mean sigma_yy of the lowest cell layer (time mean)
  double lowest_layer_xx = 0;    // Pa, mean sigma_xx of the lowest cell layer (time mean)
  double reaction = 0;           // N/m, time mean of wall_force()[1]
  double weight = 0;             // N/m, sum of particle masses times g
  double plastic = 0;            // J/m, plastic work dissipated over the run
  double elastic = 0;            // J/m, elastic energy at the end
  double h = 0, dx = 0, rho = 0, k0 = 0;
  Status status = Status::Running;
};

// Runs the column for `t_end` and averages over [t_avg, t_end] with a Hann window: the stress
// every 5 steps, the base reaction every step (weighted by the step, i.e. a time mean).
template <class Exec>
ColumnResult run_column(const Material& mat, bool geostatic_start, double t_end, double t_avg) {
  using Mem = typename Exec::memory_space;
  ColumnResult R;
  R.h = 10.0;
  R.dx = R.h / 40;
  R.rho = mat.density;
  R.k0 = mat.poisson_ratio / (1 - mat.poisson_ratio);
  const double dx = R.dx, h = R.h;
  // Walls on grid lines, two cells inside the grid (the stencil of a point next to a wall reaches
  // one node beyond it, and G2P keeps one more cell of padding).
  const double xl = 2 * dx, xr = xl + 1.0, yb = 2 * dx;
  const double lo[2] = {0, 0}, hi[2] = {xr + 2 * dx, yb + h + 3 * dx};
  Grid<Mem> grid(lo, hi, dx);
  BodySpec body;
  body.polygon = {{{xl, yb}}, {{xr, yb}}, {{xr, yb + h}}, {{xl, yb + h}}};
  if (geostatic_start) {
    body.geostatic_k0 = R.k0;
    body.surface_y = yb + h;
    body.gravity = kG;
  }
  auto particles = build_particles<Mem>({body}, {mat}, lo, dx);
  Boundaries walls;
  walls.left = {true, xl, 0.0};
  walls.right = {true, xr, 0.0};
  walls.bottom = {true, yb, 0.0};
  Settings s;
  s.courant = 0.5;
  Solver<Exec> solver(grid, particles, {mat}, walls, s);

  auto xh = Kokkos::create_mirror_view(particles.position);
  auto sh = Kokkos::create_mirror_view(particles.stress);
  auto mh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), particles.mass);
  for (int q = 0; q < particles.count; ++q) R.weight += mh(q) * kG;

  // Least-squares line through (y, sigma_yy) of the points 2 to 20 cells above the base (outside
  // the boundary layer), accumulated over the samples; the lowest layer's means.
  double Sw = 0, Sy = 0, Syy = 0, Ss = 0, Sys = 0, low_sum = 0, low_xx = 0, low_n = 0;
  double react_t = 0, react_sum = 0;
  int step = 0;
  while (solver.time() < t_end) {
    R.status = solver.step();
    if (R.status != Status::Running) return R;
    if (solver.time() <= t_avg) continue;
    const double w =
        1 - std::cos(2 * 3.14159265358979323846 * (solver.time() - t_avg) / (t_end - t_avg));
    react_sum += w * solver.wall_force()[1] * solver.time_step();
    react_t += w * solver.time_step();
    if (++step % 5) continue;
    Kokkos::deep_copy(xh, particles.position);
    Kokkos::deep_copy(sh, particles.stress);
    for (int q = 0; q < particles.count; ++q) {
      const double y = xh(q, 1) - yb;
      if (y > 2 * dx && y < 20 * dx) {
        Sw += w;
        Sy += w * y;
        Syy += w * y * y;
        Ss += w * sh(q, 1);
        Sys += w * y * sh(q, 1);
      }
      if (y < dx) {
        low_sum += w * sh(q, 1);
        low_xx += w * sh(q, 0);
        low_n += w;
      }
    }
  }
  const double slope = (Sw * Sys - Sy * Ss) / (Sw * Syy - Sy * Sy);
  R.base_extrapolated = (Ss - slope * Sy) / Sw;
  R.slope = slope;
  R.lowest_layer = low_sum / low_n;
  R.lowest_layer_xx = low_xx / low_n;
  R.reaction = react_sum / react_t;
  R.plastic = solver.energy().plastic;
  R.elastic = solver.energy().elastic;
  R.status = Status::Finished;
  return R;
}

Material soil(Material::Model model) {
  Material m;
  m.model = model;
  m.density = 2000;
  m.young_modulus = 5e7;
  m.poisson_ratio = 0.3;
  if (model == Material::Model::MohrCoulomb) {
    // K0 = 0.43 lies inside the cone: the active limit is Ka = (1 - sin phi)/(1 + sin phi) = 0.33.
    m.friction_angle = 30.0 * 3.14159265358979323846 / 180.0;
    m.dilatancy_angle = 0.0;
    m.cohesion = 0.0;
    m.tension_cutoff = 0.0;
  }
  return m;
}

void check(const ColumnResult& R, const char* label) {
  ASSERT_EQ(R.status, Status::Finished) << describe(R.status);
  const double base = R.rho * kG * R.h;                // rho g h, Pa
  const double layer = R.rho * kG * (R.h - R.dx / 2);  // at the mean depth of the lowest layer
  const double err_base = -R.base_extrapolated / base - 1;
  const double err_slope = R.slope / (R.rho * kG) - 1;
  const double err_layer = -R.lowest_layer / layer - 1;
  const double err_k0 = R.lowest_layer_xx / R.lowest_layer / R.k0 - 1;
  const double err_reaction = -R.reaction / R.weight - 1;
  std::printf(
      "[measured] %s: base sigma_yy (extrapolated) %.6g Pa vs rho g h %.6g: %+.3f %%; "
      "gradient %+.3f %%; lowest layer %+.3f %%; K0 (lowest layer) %+.3f %%; base reaction "
      "%.6g N/m vs weight %.6g: %+.3f %%\n",
      label, -R.base_extrapolated, base, 100 * err_base, 100 * err_slope, 100 * err_layer,
      100 * err_k0, -R.reaction, R.weight, 100 * err_reaction);
  // 2 % (the brief's tolerance) on the base stress extrapolated from outside the boundary layer:
  // the discrete static solution is +0.5 % off, the rest is residual oscillation.
  EXPECT_LT(std::fabs(err_base), 0.02) << label;
  // The gradient rho g of the fit: the decaying boundary-layer oscillation inside the fitting
  // window tilts it (+2.5 % in the 1D static solution): 5 %.
  EXPECT_LT(std::fabs(err_slope), 0.05) << label;
  // Lowest layer: the boundary layer described above, +16.9 % in the discrete static solution;
  // bounded at 20 % so that a regression (or a fix) of the wall treatment shows up here.
  EXPECT_LT(std::fabs(err_layer), 0.20) << label;
  // Lateral stress ratio K0 = nu/(1-nu) of the oedometric state, 2 %: sigma_xx and sigma_yy share
  // the boundary layer (it is a vertical strain error), so their ratio is unaffected.
  EXPECT_LT(std::fabs(err_k0), 0.02) << label;
  // Base reaction = weight: momentum balance of the column averaged over time, 2 %.
  EXPECT_LT(std::fabs(err_reaction), 0.02) << label;
}

template <class Exec>
class MpmGeostatic : public ::testing::Test {};
TYPED_TEST_SUITE(MpmGeostatic, lsi::test::Backends);

// Started from the geostatic stress: the state must stay (the small imbalance of the discrete
// forces at the free surface and the base excites only small oscillations).
TYPED_TEST(MpmGeostatic, ElasticColumnStaysGeostatic) {
  const Material m = soil(Material::Model::LinearElastic);
  const double T1 = 4 * 10.0 / m.wave_speed();  // fundamental period of the column, s
  check(run_column<TypeParam>(m, true, 3 * T1, T1), "elastic, geostatic start");
}

// The same with Mohr-Coulomb (phi = 30 deg, c = 0, tension cut-off 0): K0 = 0.43 > Ka = 0.33,
// so the at-rest state is elastic and must not yield anywhere.
TYPED_TEST(MpmGeostatic, MohrCoulombColumnStaysGeostatic) {
  const Material m = soil(Material::Model::MohrCoulomb);
  const double T1 = 4 * 10.0 / m.wave_speed();
  const ColumnResult R = run_column<TypeParam>(m, true, 3 * T1, T1);
  check(R, "Mohr-Coulomb, geostatic start");
  std::printf("[measured] Mohr-Coulomb column: plastic work %.3g J/m, elastic energy %.4g J/m\n",
              R.plastic, R.elastic);
  // Essentially no yielding: only the points next to the free surface, at near-zero stress,
  // touch the tension cut-off during the small oscillations. 1e-5 of the elastic energy.
  EXPECT_LE(R.plastic, 1e-5 * R.elastic);
}

// Started stress-free: the column falls onto the base and oscillates about the static state
// (the base reaction between ~0 and twice the weight, never lifting off); Hann-averaged over 6
// fundamental periods after the first. (A plain mean over 10 and 20 periods left +1.4 % and
// +1.2 % on the extrapolated base stress: the 1/N leakage of the oscillation.)
TYPED_TEST(MpmGeostatic, ElasticColumnFromZeroStressAveragesToGeostatic) {
  const Material m = soil(Material::Model::LinearElastic);
  const double T1 = 4 * 10.0 / m.wave_speed();  // fundamental period of the column, s
  check(run_column<TypeParam>(m, false, 7 * T1, T1), "elastic, zero-stress start");
}

}  // namespace

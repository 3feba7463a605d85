// Verification: a block sliding on an inclined plane with Coulomb friction. The slope is a
// horizontal bottom wall with gravity rotated by theta (boundary.hpp):
//   gravity = (g sin(theta), -g cos(theta)),   wall friction mu.
// An elastic block (rho = 2000 kg/m^3, nu = 0.3; 1.0 m x 0.4 m, 10 x 4 cells of 0.1 m, 2 x 2
// points per cell) starts at rest and stress-free with its base on the wall. A rigid block with
// mu < tan(theta) slides with constant acceleration, its centre of mass moving along the slope by
//   s(t) = 1/2 g (sin(theta) - mu cos(theta)) t^2;
// for mu >= tan(theta) it sticks.
//
// The closed form is for a rigid block; the model's block is elastic. Released stress-free, it
// rings (compression and shear under its weight, angular frequency ~ c / H), and while its base
// traction oscillates the wall's Coulomb law lets it slip a little more than a rigid block would:
// the block gains a velocity offset in the first ~50 ms (friction impulse / normal impulse 0.46
// instead of 0.5 by then) and keeps it. The offset scales as the ringing velocity, g / omega, i.e.
// as E^(-1/2): measured with mu = 0.5 and APIC, +10.1 %, +3.3 %, +1.04 %, +0.33 % on the
// displacement at E = 1e8, 1e9, 1e10, 1e11 Pa. So the friction law itself is exact in the rigid
// limit, and the tests check it there:
//   * mu = 0 and 0.2 with E = 1e8 (the offset is negligible: 0.01 % at mu = 0.2, where the net
//     acceleration is large), mu = 0.5 with E = 1e11 (a steel-stiff block): within 1 %;
//   * the E^(-1/2) law itself, over E = 1e8, 1e9, 1e10 (observed exponent within 0.5 +- 0.1).
// Sticking (mu = 0.7 > tan 30 deg = 0.577) is checked with "pic" transfer: with APIC, which
// conserves the ringing energy, the ringing block walks down the slope (a steady creep of
// 3.5 cm/s at E = 1e8, 3.3 mm/s at E = 1e10); PIC damps the ringing and the block stays put
// (docs/theory/mpm.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"
#include "support/backends.hpp"

namespace {
using namespace lsi::mpm;

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;

struct SlideResult {
  Status status = Status::Running;
  double time = 0;            // s
  double displacement = 0;    // m, centre of mass along the slope (x)
  double normal_drift = 0;    // m, centre of mass normal to the slope (y)
  double min_margin = 1e300;  // m, smallest distance of a point to the grid edge during the run
  double boundary_work = 0;   // J/m dissipated by the wall
  double energy_residual = 0;
  double mass = 0;           // kg/m
  double mean_velocity = 0;  // m/s along the slope at the end
};

template <class Exec>
SlideResult slide(double theta, double mu, double t_end, double young_modulus = 1e8,
                  Transfer transfer = Transfer::Apic) {
  using Mem = typename Exec::memory_space;
  Material m;
  m.density = 2000;
  m.young_modulus = young_modulus;
  m.poisson_ratio = 0.3;
  const double dx = 0.1;
  const double yb = 2 * dx;  // wall on a grid line, 2 cells above the origin
  const double x0 = 0.3, L = 1.0, H = 0.4;
  const double lo[2] = {0, 0}, hi[2] = {2.8, 1.0};
  Grid<Mem> grid(lo, hi, dx);
  BodySpec body;
  body.polygon = {{{x0, yb}}, {{x0 + L, yb}}, {{x0 + L, yb + H}}, {{x0, yb + H}}};
  auto particles = build_particles<Mem>({body}, {m}, lo, dx);
  Boundaries walls;
  walls.bottom = {true, yb, mu};
  Settings s;
  s.courant = 0.5;
  s.transfer = transfer;
  s.flip_ratio = 0.0;  // FlipPic only: plain PIC
  s.gravity[0] = kG * std::sin(theta);
  s.gravity[1] = -kG * std::cos(theta);
  Solver<Exec> solver(grid, particles, {m}, walls, s);

  auto xh = Kokkos::create_mirror_view(particles.position);
  auto vh = Kokkos::create_mirror_view(particles.velocity);
  auto mh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), particles.mass);
  SlideResult R;
  double cx0 = 0, cy0 = 0;
  auto centre = [&](double& cx, double& cy) {
    Kokkos::deep_copy(xh, particles.position);
    double M = 0;
    cx = cy = 0;
    for (int q = 0; q < particles.count; ++q) {
      M += mh(q);
      cx += mh(q) * xh(q, 0);
      cy += mh(q) * xh(q, 1);
      const double margin = std::min(std::min(xh(q, 0) - lo[0], hi[0] - xh(q, 0)),
                                     std::min(xh(q, 1) - lo[1], hi[1] - xh(q, 1)));
      R.min_margin = std::min(R.min_margin, margin);
    }
    cx /= M;
    cy /= M;
    R.mass = M;
  };
  centre(cx0, cy0);
  R.status = solver.run(t_end, t_end / 10, [&](const Solver<Exec>&) {
    double cx, cy;
    centre(cx, cy);  // margin check at every output
  });
  double cx, cy;
  centre(cx, cy);
  Kokkos::deep_copy(vh, particles.velocity);
  double pv = 0;
  for (int q = 0; q < particles.count; ++q) pv += mh(q) * vh(q, 0);
  R.mean_velocity = pv / R.mass;
  R.time = solver.time();
  R.displacement = cx - cx0;
  R.normal_drift = cy - cy0;
  const EnergyReport e = solver.energy();
  R.boundary_work = e.boundary;
  R.energy_residual = solver.energy_residual(e);
  return R;
}

template <class Exec>
class MpmInclinedBlock : public ::testing::Test {};
TYPED_TEST_SUITE(MpmInclinedBlock, lsi::test::Backends);

constexpr double kTheta = 30.0 * kPi / 180.0;  // tan(30 deg) = 0.577: mu = 0.5 still slides
constexpr double kEnd = 0.5;                   // s; mu = 0 travels 0.61 m, the grid allows 1.3 m

double closed_form_displacement(double mu, double t) {
  return 0.5 * kG * (std::sin(kTheta) - mu * std::cos(kTheta)) * t * t;
}

// Checks the sliding run against the closed form; `normal` also bounds the drift normal to the
// slope.
void check_sliding(const SlideResult& R, double mu, bool normal) {
  ASSERT_EQ(R.status, Status::Finished) << describe(R.status) << " mu " << mu;
  const double a = kG * (std::sin(kTheta) - mu * std::cos(kTheta));
  const double s = closed_form_displacement(mu, R.time), v = a * R.time;
  const double err = R.displacement / s - 1;
  std::printf(
      "[measured] mu %.1f: s = %.6f m vs %.6f m (%+.4f %%), v = %.5f vs %.5f m/s "
      "(%+.4f %%), normal drift %.2e m, margin %.2f m, energy residual %.1e\n",
      mu, R.displacement, s, 100 * err, R.mean_velocity, v, 100 * (R.mean_velocity / v - 1),
      R.normal_drift, R.min_margin, R.energy_residual);
  // 1 % (the brief's tolerance) on the displacement along the slope.
  EXPECT_LT(std::fabs(err), 0.01) << "mu " << mu;
  // The block's speed, 1 % likewise (it is the time integral of the same forces).
  EXPECT_LT(std::fabs(R.mean_velocity / v - 1), 0.01) << "mu " << mu;
  // It stays on the slope: the centre of mass moves normal to it only by the elastic
  // compression under its weight, rho g cos(theta) H^2 / (2 M) ~ 1e-5 m at E = 1e8 (M the
  // constrained modulus), doubled by the dynamic start: bound 1e-4 m. (Measured: 1e-5 m at
  // mu = 0; 8e-5 m for the E = 1e11 block at mu = 0.5, whose compression is negligible: the
  // friction torque makes it rock slightly on the unilateral wall.)
  if (normal) {
    EXPECT_LT(std::fabs(R.normal_drift), 1e-4) << "mu " << mu;
  }
  // The block stayed more than one cell (0.1 m) inside the grid the whole time.
  EXPECT_GT(R.min_margin, 0.1 + 1e-9) << "mu " << mu;
}

// Frictionless (exact to round-off: the wall takes only normal momentum), mu = 0.2 and, with a
// near-rigid block, mu = 0.5, all with the default APIC transfer.
TYPED_TEST(MpmInclinedBlock, SlidesWithCoulombAcceleration) {
  check_sliding(slide<TypeParam>(kTheta, 0.0, kEnd), 0.0, true);
  // mu = 0.2 at E = 1e8: the ringing also lifts the centre of mass by 0.5 mm (it rocks on the
  // unilateral wall), so the normal drift is checked on the stiff block only.
  check_sliding(slide<TypeParam>(kTheta, 0.2, kEnd), 0.2, false);
  check_sliding(slide<TypeParam>(kTheta, 0.5, kEnd, 1e11), 0.5, true);
}

// The excess displacement at mu = 0.5 is the elastic ringing of the block, which scales as
// g / omega ~ E^(-1/2): each tenfold stiffness divides it by sqrt(10). Asserted: the observed
// exponent between successive stiffnesses in [0.4, 0.6] (measured 0.49 and 0.51), and the
// excess positive (the ringing only ever helps the block slide).
TYPED_TEST(MpmInclinedBlock, ExcessSlidingVanishesAsTheBlockStiffens) {
  double excess[3];
  const double E[3] = {1e8, 1e9, 1e10};
  for (int k = 0; k < 3; ++k) {
    const SlideResult R = slide<TypeParam>(kTheta, 0.5, kEnd, E[k]);
    ASSERT_EQ(R.status, Status::Finished) << describe(R.status);
    excess[k] = R.displacement / closed_form_displacement(0.5, R.time) - 1;
    std::printf("[measured] mu 0.5, E %.0e Pa: excess displacement %+.3f %%\n", E[k],
                100 * excess[k]);
    EXPECT_GT(excess[k], 0.0);
  }
  for (int k = 0; k < 2; ++k) {
    const double exponent = std::log10(excess[k] / excess[k + 1]);
    std::printf("[measured] observed exponent of E between %.0e and %.0e: %.3f\n", E[k], E[k + 1],
                exponent);
    EXPECT_GT(exponent, 0.4);
    EXPECT_LT(exponent, 0.6);
  }
}

// mu = 0.7 > tan(30 deg) = 0.577: the static friction holds the block. Its centre of mass may
// move only by the elastic shear of the block under the slope-parallel weight: the static
// deflection of the top, rho g sin(theta) H^2 / (2 G) = 2e-5 m, at most doubled by the dynamic
// start: bound 1e-4 m, 5x that (and 0.1 % of the 0.08 m the mu = 0.5 block slides meanwhile).
// Run with plain PIC, which damps the block's ringing (see the head of this file).
TYPED_TEST(MpmInclinedBlock, SticksWhenFrictionExceedsSlope) {
  const SlideResult R = slide<TypeParam>(kTheta, 0.7, kEnd, 1e8, Transfer::FlipPic);
  ASSERT_EQ(R.status, Status::Finished) << describe(R.status);
  std::printf(
      "[measured] mu 0.7 (stick, PIC): displacement %.3e m, velocity %.3e m/s, normal "
      "drift %.2e m\n",
      R.displacement, R.mean_velocity, R.normal_drift);
  EXPECT_LT(std::fabs(R.displacement), 1e-4);
  // A creeping block would keep a steady speed (APIC: 3.5 cm/s); the elastic vibration, damped
  // by PIC, leaves far less: bound 1e-3 m/s (measured with the mass-weighted particle velocity).
  EXPECT_LT(std::fabs(R.mean_velocity), 1e-3);
  EXPECT_LT(std::fabs(R.normal_drift), 1e-4);
}

}  // namespace

// Disconnected points (kernels/mpm/stress_update.hpp): a point of a cohesionless Mohr-Coulomb
// material with no tensile strength that sits at zero stress and has grown beyond its initial
// volume V0 gets V0 back; every other point keeps V = J V0. Without this, the points that an
// overtopping flow tears apart expand without bound (an isolated APIC point exponentially) and,
// compressed again, are stiffer per unit mass by V / V0, which the time step must follow
// (time_step.hpp): 50 times smaller steps for a speck of spray.
//
// Per point (update_point_stress on host Views, one point): which states are reset and which are
// not. In the solver (every backend): an isolated APIC point in an affine expansion, which
// would grow as exp(tr(L) t), keeps its initial volume and the time step of c0.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"
#include "kernels/mpm/stress_update.hpp"
#include "support/backends.hpp"
#include "support/tolerances.hpp"

namespace {
using namespace lsi::mpm;
using HostParticles = Particles<Kokkos::HostSpace>;
using lsi::test::kTwoRoutesRel;
using lsi::test::kUnitArithmeticAbs;

// The affine field after the expansion's steps: the round-off of the transfers' sums, relative.
constexpr double kTransferSumsRel = 1e-9;

constexpr double kPi = 3.14159265358979323846;

Material granular(double cohesion = 0.0, double tension_cutoff = 0.0) {
  Material m;
  m.model = Material::Model::MohrCoulomb;
  m.density = 1800;
  m.young_modulus = 2e6;
  m.poisson_ratio = 0.25;
  m.friction_angle = 20 * kPi / 180;
  m.cohesion = cohesion;
  m.tension_cutoff = tension_cutoff;
  return m;
}

// One point of volume V0 = 0.01 m^2, stress s, current volume J0 V0; one step of the velocity
// gradient diag(a, a) over dt = 0.01 s. Returns V / V0 after the step.
double volume_ratio_after(const Material& m, double a, double J0 = 1.0, double s_yy = 0.0) {
  HostParticles p(1);
  p.volume0(0) = 0.01;
  p.volume(0) = J0 * 0.01;
  for (int k = 0; k < 4; ++k) p.stress(0, k) = 0.0;
  p.stress(0, YY) = s_yy;
  update_point_stress<true>(p, 0, PreparedMaterial(m), a, 0.0, 0.0, a, 0.01);
  return p.volume(0) / p.volume0(0);
}

TEST(DisconnectedPoints, OnlyStressFreeExpandedCohesionlessPointsGetTheirVolumeBack) {
  const double J_step = (1 + 0.01 * 10.0) * (1 + 0.01 * 10.0);  // a = 10 /s: 1.21
  // Stress-free, pulled apart: the tension cut-off returns to the apex (exact zeros): reset.
  EXPECT_EQ(volume_ratio_after(granular(), 10.0), 1.0);
  // Already expanded threefold, and pulled again: reset too.
  EXPECT_EQ(volume_ratio_after(granular(), 10.0, 3.0), 1.0);
  // Compressed: stress builds, V = J V0 (J < 1). Round-off only: 1e-14.
  const double J_c = (1 - 0.1) * (1 - 0.1);
  EXPECT_NEAR(volume_ratio_after(granular(), -10.0), J_c, kUnitArithmeticAbs);
  // An expanded point that is being compressed (J0 = 3, a < 0) carries stress after the step
  // (hypoelastic: any compression increment does), so it keeps 3 J: it was reset while it was
  // stress-free, never after.
  EXPECT_NEAR(volume_ratio_after(granular(), -10.0, 3.0), 3.0 * J_c, kUnitArithmeticAbs);
  // Under compression (sigma_yy = -50 kPa) a small expansion unloads but stays compressive:
  // not at zero stress, so V = J V0.
  EXPECT_NEAR(volume_ratio_after(granular(), 0.1, 1.0, -5e4), (1 + 1e-3) * (1 + 1e-3),
              kUnitArithmeticAbs);
  // With cohesion or tensile strength the material holds tension: its volume means something.
  EXPECT_NEAR(volume_ratio_after(granular(1e4), 10.0), J_step, kUnitArithmeticAbs);
  EXPECT_NEAR(volume_ratio_after(granular(0.0, 1e3), 10.0), J_step, kUnitArithmeticAbs);
  // Elastic material: never.
  Material elastic = granular();
  elastic.model = Material::Model::LinearElastic;
  EXPECT_NEAR(volume_ratio_after(elastic, 10.0), J_step, kUnitArithmeticAbs);
}

template <class Exec>
class MpmDisconnectedPoints : public ::testing::Test {};
TYPED_TEST_SUITE(MpmDisconnectedPoints, lsi::test::Backends);

// One point (one per cell, alone on the grid), no gravity, velocity 0 and the APIC affine field
// C = a I: the grid reconstructs the uniform expansion v = a (x - x_p) and G2P gives back the same
// C (a stress-free point exerts no force), so the point is pulled apart at tr(L) = 2a every step,
// for ever: without the reset its volume would be prod (1 + a dt)^2 ~ exp(2 a t). Cohesionless:
// reset every step, so V = V0, and the step stays exactly C dx / c0.
TYPED_TEST(MpmDisconnectedPoints, AnIsolatedExpandingApicPointKeepsItsVolumeAndTheStep) {
  using Exec = TypeParam;
  using Mem = typename Exec::memory_space;
  const double a = 2.0, dx = 0.5, t_end = 1.0;
  const Material m = granular();
  const double c0 = m.wave_speed();
  const double lo[2] = {0, 0}, hi[2] = {10, 10};
  Grid<Mem> grid(lo, hi, dx);
  BodySpec body;
  body.polygon = {{{5.0, 5.0}}, {{5.5, 5.0}}, {{5.5, 5.5}}, {{5.0, 5.5}}};
  body.points_per_cell_direction = 1;
  auto particles = build_particles<Mem>({body}, {m}, lo, dx);
  ASSERT_EQ(particles.count, 1);
  auto C = Kokkos::create_mirror_view(particles.affine);
  C(0, 0, 0) = C(0, 1, 1) = a;
  C(0, 0, 1) = C(0, 1, 0) = 0.0;
  Kokkos::deep_copy(particles.affine, C);
  Settings s;
  s.courant = 0.5;
  s.gravity[0] = s.gravity[1] = 0.0;
  Solver<Exec> solver(grid, particles, {m}, Boundaries{}, s);
  Status st = Status::Running;
  double would_be = 1.0;  // V / V0 without the reset
  while (st == Status::Running && solver.time() < t_end) {
    st = solver.step();
    would_be *= (1 + a * solver.time_step()) * (1 + a * solver.time_step());
    // The point's speed stays 0 (the affine field is centred on it) and its J at 1: the step is
    // exactly C dx / c0 (1e-12: round-off).
    ASSERT_NEAR(solver.time_step(), 0.5 * dx / c0, kTwoRoutesRel * dx / c0) << solver.steps();
  }
  ASSERT_EQ(st, Status::Running) << describe(st);
  auto V = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), particles.volume);
  auto V0 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), particles.volume0);
  Kokkos::deep_copy(C, particles.affine);
  auto sig = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), particles.stress);
  std::cout << "[ disconnect ] " << solver.steps() << " steps: V / V0 = " << V(0) / V0(0)
            << " (without the reset: " << would_be << "), C = " << C(0, 0, 0) << ", " << C(0, 1, 1)
            << "\n";
  EXPECT_EQ(V(0), V0(0));
  EXPECT_EQ(solver.max_expansion(), 1.0);
  // The expansion really went on: the affine field is intact (1e-9 relative: round-off of the
  // transfer's sums), so every step pulled the point apart by (1 + a dt)^2.
  EXPECT_NEAR(C(0, 0, 0), a, kTransferSumsRel * a);
  EXPECT_NEAR(C(0, 1, 1), a, kTransferSumsRel * a);
  EXPECT_GT(would_be, 50.0);  // exp(2 a t) = 54.6 at 1 s
  for (int k = 0; k < 4; ++k) EXPECT_EQ(sig(0, k), 0.0) << k;
}

}  // namespace

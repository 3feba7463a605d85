// Verification 3: the time-step limit in action. The explicit scheme is stable only for
// dt <= ~dx / c (Courant number <= ~1; for this bar at 16 cells run() finishes 40 periods at 1.0
// and stops with EnergyGrowth at 1.05 and above),
// so the same elastic bar as test_mpm_elastic_bar (first-mode vibration of the free-free strip
// [-L, L], nu = 0, no gravity, no walls) run at Courant 5 must be stopped by the health checks
// (energy growth at an output, non-finite values or a particle leaving the grid) within a few
// steps and never reported Finished, while at Courant 0.5 it finishes with finite fields.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"
#include "support/backends.hpp"

namespace {
using namespace lsi::mpm;

constexpr double kPi = 3.14159265358979323846;
constexpr double kL = 1.0, kRho = 1000.0, kE = 1e7, kV0 = 0.01;   // c = 100 m/s
const double kC = std::sqrt(kE / kRho);
const double kPeriod = 4.0 * kL / kC;   // first fixed-free mode of each half: 0.04 s
constexpr int kCells = 16;              // cells along L
constexpr double kDx = kL / kCells;

template <class Exec>
struct Bar {
  using Mem = typename Exec::memory_space;
  Material material;
  Grid<Mem> grid;
  Particles<Mem> particles;
  double max_speed = 0.0;   // largest initial particle speed, m/s

  Bar() {
    material.density = kRho;
    material.young_modulus = kE;
    material.poisson_ratio = 0.0;
    const double h = 2.0 * kDx;
    const double lo[2] = {-kL - 3.0 * kDx, -3.0 * kDx}, hi[2] = {kL + 3.0 * kDx, h + 3.0 * kDx};
    grid = Grid<Mem>(lo, hi, kDx);
    BodySpec body;
    body.polygon = {{{-kL, 0.0}}, {{kL, 0.0}}, {{kL, h}}, {{-kL, h}}};
    particles = build_particles<Mem>({body}, {material}, lo, kDx);
    auto x = Kokkos::create_mirror(Kokkos::HostSpace(), particles.position);   // real copies
    auto v = Kokkos::create_mirror(Kokkos::HostSpace(), particles.velocity);
    Kokkos::deep_copy(x, particles.position);
    for (int q = 0; q < particles.count; ++q) {
      v(q, 0) = kV0 * std::sin(kPi * x(q, 0) / (2.0 * kL));
      v(q, 1) = 0.0;
      max_speed = std::max(max_speed, std::abs(v(q, 0)));
    }
    Kokkos::deep_copy(particles.velocity, v);
  }

  Solver<Exec> solver(double courant) const {
    Settings s;
    s.courant = courant;
    s.gravity[0] = s.gravity[1] = 0.0;
    return Solver<Exec>(grid, particles, {material}, Boundaries{}, s);
  }
};

bool is_unstable(Status s) {
  return s == Status::NonFinite || s == Status::LeftGrid || s == Status::EnergyGrowth ||
         s == Status::TimeStepCollapse;
}

template <class Exec>
class MpmStability : public ::testing::Test {};
TYPED_TEST_SUITE(MpmStability, lsi::test::Backends);

// run() with outputs every period / 16 (about 3 steps at Courant 5): the energy check at the
// outputs stops the run.
TYPED_TEST(MpmStability, CourantFiveIsStoppedByRun) {
  using Exec = TypeParam;
  Bar<Exec> bar;
  auto solver = bar.solver(5.0);
  const double t_end = 10.0 * kPeriod;
  const long steps_to_end = static_cast<long>(std::ceil(t_end / (5.0 * kDx / kC)));   // ~128
  const Status s = solver.run(t_end, kPeriod / 16);
  std::cout << "[ stability ] Courant 5, run(): " << describe(s) << " after " << solver.steps()
            << " steps (t = " << solver.time() << " s of " << t_end << ")\n";
  EXPECT_NE(s, Status::Finished);
  EXPECT_NE(s, Status::Running);
  EXPECT_TRUE(is_unstable(s)) << describe(s);
  EXPECT_EQ(solver.status(), s);
  // The time step is the Courant number times dx / (c + |v|max): checked on the last step
  // (|v|max then is whatever the blow-up made it, so only an upper bound holds).
  EXPECT_LE(solver.time_step(), 5.0 * kDx / kC * (1 + 1e-12));
  // Bounded: measured 3 steps (the first output). 20 steps is less than a sixth of the run and
  // about 6 outputs, so a check that fires late, or not at all, fails here.
  EXPECT_LE(solver.steps(), 20);
  EXPECT_LT(solver.steps(), steps_to_end);
  const std::string message = describe(s);
  EXPECT_FALSE(message.empty());
  EXPECT_EQ(message.rfind("unstable", 0), 0u) << message;   // starts with "unstable"
}

// Manual stepping has no energy check: the per-step health checks of G2P alone (non-finite values,
// a particle leaving the grid) must stop the blow-up.
TYPED_TEST(MpmStability, CourantFiveIsStoppedByHealthChecks) {
  using Exec = TypeParam;
  Bar<Exec> bar;
  auto solver = bar.solver(5.0);
  Status s = Status::Running;
  // The first step size is exact: Courant 5 times dx / (c + |v|max) with the initial speeds.
  s = solver.step();
  EXPECT_NEAR(solver.time_step(), 5.0 * kDx / (kC + bar.max_speed), 1e-12 * kDx / kC);
  const long limit = 100;
  while (s == Status::Running && solver.steps() < limit) s = solver.step();
  std::cout << "[ stability ] Courant 5, step(): " << describe(s) << " after " << solver.steps()
            << " steps\n";
  // Measured 6 steps (LeftGrid: the unstable modes grow by orders of magnitude per step at
  // Courant 5); 100 steps (~80 % of the 128 that 10 periods take at Courant 5) bounds it widely
  // while still proving the checks fire. (Only far above the limit: at Courant 1.3 the growth is
  // ~1 % per step and step() alone runs 20 periods without tripping these checks, while run()'s
  // energy check stops it after 13 steps.)
  EXPECT_LT(solver.steps(), limit);
  EXPECT_TRUE(s == Status::NonFinite || s == Status::LeftGrid) << describe(s);
  EXPECT_EQ(std::string(describe(s)).rfind("unstable", 0), 0u) << describe(s);
}

// The same bar at Courant 0.5 runs to the end with finite fields and a bounded energy.
TYPED_TEST(MpmStability, CourantHalfFinishes) {
  using Exec = TypeParam;
  Bar<Exec> bar;
  auto solver = bar.solver(0.5);
  const double t_end = 10.0 * kPeriod;
  double worst_residual = 0.0, dt_min = 1e300, dt_max = 0.0;
  const Status s = solver.run(t_end, kPeriod / 16, [&](const Solver<Exec>& sv) {
    worst_residual = std::max(worst_residual, std::abs(sv.energy_residual(sv.energy())));
    if (sv.steps() > 0 && sv.time() < t_end * (1 - 1e-9)) {   // the last step is cut to t_end
      dt_min = std::min(dt_min, sv.time_step());
      dt_max = std::max(dt_max, sv.time_step());
    }
  });
  std::cout << "[ stability ] Courant 0.5: " << describe(s) << " after " << solver.steps()
            << " steps, largest |energy residual| " << worst_residual << "\n";
  ASSERT_EQ(s, Status::Finished) << describe(s);
  EXPECT_NEAR(solver.time(), t_end, 1e-12 * t_end);
  // The time step is the Courant number times dx / (c + |v|max), 0 < |v|max <= ~v0 (1 % for the
  // discrete transfer of the mode), at every output but the cut last step.
  EXPECT_GE(dt_min * (1 + 1e-12), 0.5 * kDx / (kC + kV0 * 1.01));
  EXPECT_LE(dt_max, 0.5 * kDx / kC * (1 + 1e-12));
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver.particles().position);
  auto v = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver.particles().velocity);
  auto st = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver.particles().stress);
  for (int q = 0; q < solver.particles().count; ++q) {
    ASSERT_TRUE(std::isfinite(x(q, 0)) && std::isfinite(x(q, 1))) << q;
    // Stable: no speed above the initial peak v0 (energy cannot grow; 5 % for the discrete
    // transfer of the mode).
    ASSERT_LE(std::abs(v(q, 0)), 1.05 * kV0) << q;
    ASSERT_LE(std::abs(v(q, 1)), 1e-9) << q;                  // stays one-dimensional (round-off)
    ASSERT_TRUE(std::isfinite(st(q, 0))) << q;
    ASSERT_LE(std::abs(st(q, 0)), 1.05 * kE * kV0 / kC) << q;   // peak stress E v0 / c = 1 kPa
  }
  // At 16 cells, Courant 0.5 the total oscillates by ~omega dt / 2 = 2.5 % (leapfrog staggering,
  // see test_mpm_elastic_bar) plus ~1 % dissipation over 10 periods; 5 % bounds both, far below
  // the unstable runs' growth (the 0.5 limit of Settings::energy_growth_limit).
  EXPECT_LT(worst_residual, 0.05);
}
}  // namespace

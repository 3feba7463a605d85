// Verification 1: free fall of an elastic block (no walls). A uniform velocity field is
// reproduced exactly by the B-spline partition of unity, the stress stays zero, and the
// trapezoidal position update integrates constant gravity exactly: v = g t, y = y0 + g t^2 / 2
// to round-off.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"
#include "support/backends.hpp"
#include "support/falling_block.hpp"

namespace {
using namespace lsi::mpm;

template <class Exec>
class MpmFreeFall : public ::testing::Test {};
TYPED_TEST_SUITE(MpmFreeFall, lsi::test::Backends);

TYPED_TEST(MpmFreeFall, VelocityAndPositionAreExact) {
  using Exec = TypeParam;
  lsi::test::FallingBlock<Exec> block;
  auto& particles = block.particles;
  auto y0 = Kokkos::create_mirror(Kokkos::HostSpace(), particles.position);  // a real copy
  Kokkos::deep_copy(y0, particles.position);
  Settings s;
  s.courant = 0.5;
  Solver<Exec> solver = block.solver(s);
  const double t_end = 1.0;
  ASSERT_EQ(solver.run(t_end, t_end), Status::Finished);
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), particles.position);
  auto v = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), particles.velocity);
  auto st = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), particles.stress);
  // The solver reorders its points (kernels/mpm/sort_points.hpp): y0 is in the order of the ids.
  auto id = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), particles.id);
  const double t = solver.time(), g = 9.81;
  EXPECT_NEAR(t, t_end, 1e-12);
  for (int q = 0; q < particles.count; ++q) {
    const int i = id(q);
    // Round-off of ~1e3 steps on O(10) values: 1e-10 absolute.
    EXPECT_NEAR(v(q, 1), -g * t, 1e-10) << q;
    EXPECT_NEAR(v(q, 0), 0.0, 1e-10) << q;
    EXPECT_NEAR(x(q, 1), y0(i, 1) - 0.5 * g * t * t, 1e-10) << q;
    EXPECT_NEAR(x(q, 0), y0(i, 0), 1e-10) << q;
    EXPECT_NEAR(st(q, 1), 0.0, 1e-6) << q;  // Pa, against stresses of order rho g h ~ 4e4
  }
  EXPECT_GT(solver.steps(), 100);
}
}  // namespace

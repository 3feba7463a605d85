// P2G's scatters (kernels/mpm/p2g.hpp) give the same grid: per-thread buffers ("duplicated", the
// host default), one buffer with atomic additions (what a GPU runs; on the host only when a
// scene asks for "scatter": "atomic") and, on Serial, the plain one (against the host's parallel
// backend's buffered scatter). The atomic path computes
// the rectangle of touched nodes in a kernel of its own, so the rectangle is checked as well.
// The atomic scatter's tiles (a GPU's default) are checked against the buffered scatter with
// every team in a tile, with none (tiles too small: the teams add into the buffer directly) and
// with a mix of both. The in-register transposes of the host's blocked P2G and G2P
// (host_transpose.hpp, where compiled in) against plain copies.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "kernels/mpm/host_transpose.hpp"
#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"
#include "support/backends.hpp"

namespace {
using namespace lsi::mpm;

template <class Exec>
class MpmP2GScatters : public ::testing::Test {};
TYPED_TEST_SUITE(MpmP2GScatters, lsi::test::Backends);

// A column that starts to collapse (nonzero velocities, APIC matrices, stresses) after 20
// steps, and the grid of the buffered scatter as the reference.
template <class Exec>
struct Collapse {
  using Mem = typename Exec::memory_space;
  Material m;
  const double lo[2] = {0, 0}, hi[2] = {3, 2}, dx = 0.05;
  Grid<Mem> grid{lo, hi, dx};
  Particles<Mem> particles;
  Settings s;
  Collapse() {
    m.model = Material::Model::MohrCoulomb;
    m.density = 1800;
    m.young_modulus = 5e6;
    m.poisson_ratio = 0.3;
    m.friction_angle = 30.0 * 3.14159265358979323846 / 180.0;
    BodySpec body;
    body.polygon = {{{0.1, 0.1}}, {{0.6, 0.1}}, {{0.6, 1.1}}, {{0.1, 1.1}}};
    body.geostatic_k0 = 0.3;
    body.surface_y = 1.1;
    body.gravity = 9.81;
    particles = build_particles<Mem>({body}, {m}, lo, dx);
    Boundaries walls;
    walls.left = {true, 0.1, 0.0};
    walls.bottom = {true, 0.1, 0.5};
    s.courant = 0.5;
    Solver<Exec> solver(grid, particles, {m}, walls, s);
    for (int i = 0; i < 20; ++i)
      if (solver.step() != Status::Running) throw std::runtime_error("the column did not run");
    P2GScatter<Exec, false> buffered(grid);
    p2g(particles, grid, buffered, s.gravity);
  }

  // The grid of `scatter` against the buffered one: the same rectangle of nodes with mass and
  // the same nodal values.
  template <class Scatter>
  void expect_same_grid(Scatter& scatter) const {
    Grid<Mem> other(lo, hi, dx);
    p2g(particles, other, scatter, s.gravity);
    const NodeBox a = grid.mass_box(), b = other.mass_box();
    EXPECT_EQ(a.i0, b.i0);
    EXPECT_EQ(a.i1, b.i1);
    EXPECT_EQ(a.j0, b.j0);
    EXPECT_EQ(a.j1, b.j1);
    EXPECT_FALSE(a.empty());
    auto m1 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), grid.mass);
    auto m2 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), other.mass);
    auto p1 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), grid.momentum);
    auto p2 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), other.momentum);
    auto f1 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), grid.force);
    auto f2 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), other.force);
    double mass_max = 0, momentum_max = 0, force_max = 0, total = 0;
    for (int n = 0; n < grid.size(); ++n) {
      mass_max = std::fmax(mass_max, m1(n));
      total += m1(n);
      for (int d = 0; d < 2; ++d) {
        momentum_max = std::fmax(momentum_max, std::fabs(p1(n, d)));
        force_max = std::fmax(force_max, std::fabs(f1(n, d)));
      }
    }
    ASSERT_GT(momentum_max, 0.0);  // the column moves
    // The scatters add the same terms in another order: round-off of a few additions, 1e-12
    // of the largest nodal value.
    int compared = 0;
    for (int n = 0; n < grid.size(); ++n) {
      EXPECT_NEAR(m1(n), m2(n), 1e-12 * mass_max) << n;
      for (int d = 0; d < 2; ++d) {
        EXPECT_NEAR(p1(n, d), p2(n, d), 1e-12 * momentum_max) << n;
        EXPECT_NEAR(f1(n, d), f2(n, d), 1e-12 * force_max) << n;
      }
      compared += m1(n) > 0.0 ? 1 : 0;
    }
    EXPECT_GT(compared, 100);
    // The partition of unity: the nodes receive exactly the points' mass.
    // (On the host: nvcc refuses a device lambda in a test body, a private member of its class.)
    const auto pm = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), particles.mass);
    double point_mass = 0.0;
    for (int q = 0; q < particles.count; ++q) point_mass += pm(q);
    EXPECT_NEAR(total, point_mass, 1e-12 * point_mass);
  }
};

TYPED_TEST(MpmP2GScatters, AtomicAndBufferedScattersGiveTheSameGrid) {
  using Exec = TypeParam;
  const Collapse<Exec> c;
  if constexpr (P2GScatter<Exec, true>::atomic) {
    P2GScatter<Exec, true> atomic(c.grid);
    atomic.tile_points = 0;
    c.expect_same_grid(atomic);
  } else {
    // Serial has one scatter (plain additions) whatever it is asked for: its grid is checked
    // against the host's parallel backend's buffered scatter on the same points instead (both
    // live in host memory).
    using Host = Kokkos::DefaultHostExecutionSpace;
    if constexpr (std::is_same_v<Host, Exec>) {
      GTEST_SKIP() << "a Serial-only build has no second host scatter to compare with";
    } else {
      P2GScatter<Host, false> buffered(c.grid);
      c.expect_same_grid(buffered);
    }
  }
}

TYPED_TEST(MpmP2GScatters, TiledAtomicScatterGivesTheSameGrid) {
  using Exec = TypeParam;
  if (!P2GScatter<Exec, true>::atomic) GTEST_SKIP() << "Serial adds without atomics or tiles";
  const Collapse<Exec> c;  // 0.5 m wide, dx 0.05: 10 cells per row
  {
    SCOPED_TRACE("every team in a tile");  // 128 points: 32 cells, 12 x 6 nodes at most
    P2GScatter<Exec, true> tiled(c.grid);
    tiled.use_tiles(128);  // any number of points (800 here)
    c.expect_same_grid(tiled);
  }
  {
    SCOPED_TRACE("no team in a tile");  // 128 points need more than 12 nodes
    P2GScatter<Exec, true> direct(c.grid);
    direct.use_tiles(128);
    direct.tile_nodes = 12;
    c.expect_same_grid(direct);
  }
  {
    // The builder fills the cells row by row, 4 points per cell, 10 cells per row: a team of
    // 12 points (3 cells) in one row touches about 6 x 4 nodes, a team over two rows 12 x 5 or
    // more. With room for 30 nodes, 8 teams in 10 tile and the others do not.
    SCOPED_TRACE("some teams in tiles");
    P2GScatter<Exec, true> mixed(c.grid);
    mixed.use_tiles(12);
    mixed.tile_nodes = 30;
    c.expect_same_grid(mixed);
  }
}

#if LSI_MPM_HOST_TRANSPOSE
TEST(HostTranspose, MovesEveryValueToItsPlace) {
  namespace hs = detail::host_simd;
  double a[8][8];
  hs::V8 r[8];
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) a[i][j] = 10 * i + j;
    r[i] = hs::load8(a[i]);
  }
  hs::transpose8(r);
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) EXPECT_EQ(r[i][j], a[j][i]) << i << " " << j;
  // Rows of 6 doubles at scattered places of a buffer, the last one at its very end.
  double buf[64];
  for (int k = 0; k < 64; ++k) buf[k] = k;
  const int at[8] = {0, 20, 6, 40, 13, 30, 50, 58};
  const double* rows[8];
  for (int p = 0; p < 8; ++p) rows[p] = buf + at[p];
  hs::V8 out[6];
  hs::gather_rows6(rows, out);
  for (int c = 0; c < 6; ++c)
    for (int p = 0; p < 8; ++p) EXPECT_EQ(out[c][p], buf[at[p] + c]) << c << " " << p;
  // add7 writes 7 values and leaves the 8th alone.
  double sum[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  hs::add7(sum, hs::V8{10, 20, 30, 40, 50, 60, 70, 80});
  const double expected[8] = {11, 22, 33, 44, 55, 66, 77, 8};
  for (int k = 0; k < 8; ++k) EXPECT_EQ(sum[k], expected[k]) << k;
}
#endif
}  // namespace

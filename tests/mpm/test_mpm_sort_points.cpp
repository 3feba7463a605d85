// Sorting the points by cell (kernels/mpm/sort_points.hpp): a run whose points start in a random
// order and are sorted every few steps takes the same steps as the run in build order that never
// sorts, point for point (matched by Particles::id), up to the round-off of sums taken in another
// order; a sort puts the points in cell order, carries every field and the id with its point, and
// leaves points that are in cell order already exactly as they are.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"
#include "kernels/mpm/sort_points.hpp"
#include "support/backends.hpp"

namespace {
using namespace lsi::mpm;

// A Mohr-Coulomb column as bench/bench_mpm.cpp's (1 m x 2 m, 2 x 2 points per cell, geostatic
// start with K0 = 0.3: it yields from the first step and its points flow), n cells across.
template <class Exec>
struct Column {
  using Mem = typename Exec::memory_space;
  Grid<Mem> grid;
  Particles<Mem> particles;
  Material material;
  Boundaries walls;

  explicit Column(int n) {
    const double L0 = 1.0, H0 = 2.0, dx = L0 / n, g = 9.81;
    material.model = Material::Model::MohrCoulomb;
    material.density = 1800;
    material.poisson_ratio = 0.3;
    material.young_modulus = material.density * g * H0 / 0.005;
    material.friction_angle = 30.0 * M_PI / 180.0;
    material.dilatancy_angle = 0.0;
    material.cohesion = 0.0;
    material.tension_cutoff = 0.0;
    const double x0 = 2 * dx, y0 = 2 * dx;
    const double lo[2] = {0, 0}, hi[2] = {x0 + 4 * L0, y0 + H0 + 3 * dx};
    grid = Grid<Mem>(lo, hi, dx);
    BodySpec body;
    body.polygon = {{{x0, y0}}, {{x0 + L0, y0}}, {{x0 + L0, y0 + H0}}, {{x0, y0 + H0}}};
    body.points_per_cell_direction = 2;
    body.geostatic_k0 = 0.3;
    body.surface_y = y0 + H0;
    body.gravity = g;
    particles = build_particles<Mem>({body}, {material}, lo, dx);
    walls.left = {true, x0, 0.0};
    walls.bottom = {true, y0, std::tan(material.friction_angle)};
    walls.right = {true, grid.upper(0) - 2 * dx, 0.0};
  }
};

// Every double field of the points on the host, in the order of their ids: [id][component].
template <class Mem>
std::vector<std::vector<double>> by_id(const Particles<Mem>& p) {
  const auto id = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.id);
  const auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.position);
  const auto v = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.velocity);
  const auto C = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.affine);
  const auto L = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.velocity_gradient);
  const auto s = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.stress);
  const auto m = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.mass);
  const auto V = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.volume);
  const auto V0 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.volume0);
  const auto W = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.plastic_work);
  const auto E = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.deviatoric_strain);
  const auto mat = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.material);
  std::vector<std::vector<double>> out(p.count);
  for (int q = 0; q < p.count; ++q) {
    std::vector<double>& r = out.at(id(q));
    EXPECT_TRUE(r.empty()) << "id " << id(q) << " twice";
    r = {x(q, 0),    x(q, 1),
         v(q, 0),    v(q, 1),
         C(q, 0, 0), C(q, 0, 1),
         C(q, 1, 0), C(q, 1, 1),
         L(q, 0, 0), L(q, 0, 1),
         L(q, 1, 0), L(q, 1, 1),
         s(q, 0),    s(q, 1),
         s(q, 2),    s(q, 3),
         m(q),       V(q),
         V0(q),      W(q),
         E(q),       static_cast<double>(mat(q))};
  }
  return out;
}

// The cell of each point (i + (nx - 1) j), in storage order.
template <class Mem>
std::vector<int> cells(const Particles<Mem>& p, const Grid<Mem>& g) {
  const auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.position);
  std::vector<int> c(p.count);
  for (int q = 0; q < p.count; ++q)
    c[q] = static_cast<int>((x(q, 0) - g.origin[0]) / g.dx) +
           (g.nx - 1) * static_cast<int>((x(q, 1) - g.origin[1]) / g.dx);
  return c;
}

template <class Exec>
void shuffle(const Particles<typename Exec::memory_space>& p, unsigned seed) {
  std::vector<int> from(p.count);
  std::iota(from.begin(), from.end(), 0);
  std::shuffle(from.begin(), from.end(), std::mt19937(seed));
  PointSorter<Exec> s;
  s.use_order(from);
  s.apply(p);
}

template <class Exec>
class MpmSortPoints : public ::testing::Test {};
TYPED_TEST_SUITE(MpmSortPoints, lsi::test::Backends);

TYPED_TEST(MpmSortPoints, ShuffledAndSortedRunTakesTheSameSteps) {
  using Exec = TypeParam;
  Column<Exec> plain(10), mixed(10);  // 800 points
  shuffle<Exec>(mixed.particles, 7);
  Settings unsorted, sorted;
  unsorted.sort_interval = 0;
  sorted.sort_interval = 7;
  Solver<Exec> a(plain.grid, plain.particles, {plain.material}, plain.walls, unsorted);
  Solver<Exec> b(mixed.grid, mixed.particles, {mixed.material}, mixed.walls, sorted);
  for (int k = 0; k < 60; ++k) {
    ASSERT_EQ(a.step(), Status::Running);
    ASSERT_EQ(b.step(), Status::Running);
  }
  // The time steps follow the largest speed, which differs by round-off.
  EXPECT_NEAR(a.time(), b.time(), 1e-12 * a.time());
  const auto fa = by_id(a.particles()), fb = by_id(b.particles());
  const size_t fields = fa.at(0).size();
  for (size_t k = 0; k < fields; ++k) {
    double scale = 0.0, diff = 0.0;
    for (size_t i = 0; i < fa.size(); ++i) {
      scale = std::max(scale, std::abs(fa[i][k]));
      diff = std::max(diff, std::abs(fa[i][k] - fb[i][k]));
    }
    // Sums in another order over 60 steps of a yielding column: round-off of a few 1e-15 of the
    // field's largest value (measured), 1e-12 leaves room; a field the sort did not move, or
    // moved with another point's values, is off by O(1).
    EXPECT_LE(diff, 1e-12 * scale) << "field " << k;
  }
  // Sorted: in cell order after the last sort (step 56) up to the few points that have crossed
  // a cell face since.
  const std::vector<int> c = cells(b.particles(), mixed.grid);
  int descents = 0;
  for (size_t q = 1; q < c.size(); ++q) descents += c[q] < c[q - 1] ? 1 : 0;
  EXPECT_LT(descents, static_cast<int>(c.size()) / 20);
}

TYPED_TEST(MpmSortPoints, SortOrdersByCellAndKeepsOrderedPointsAsTheyAre) {
  using Exec = TypeParam;
  Column<Exec> col(10);
  const auto& p = col.particles;
  const auto& g = col.grid;
  const auto before = by_id(p);
  PointSorter<Exec> sorter;
  // As built: in cell order already, nothing to do.
  EXPECT_FALSE(sorter.order(p.position, p.count, g.origin[0], g.origin[1], g.dx, g.nx, g.ny));
  shuffle<Exec>(p, 11);
  ASSERT_TRUE(sorter.order(p.position, p.count, g.origin[0], g.origin[1], g.dx, g.nx, g.ny));
  sorter.apply(p);
  const std::vector<int> c = cells(p, g);
  EXPECT_TRUE(std::is_sorted(c.begin(), c.end()));
  // Every field travelled with its point's id (exact copies).
  EXPECT_EQ(by_id(p), before);
  EXPECT_FALSE(sorter.order(p.position, p.count, g.origin[0], g.origin[1], g.dx, g.nx, g.ny));
}
}  // namespace

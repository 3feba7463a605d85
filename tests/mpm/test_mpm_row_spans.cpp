// The grid's row spans (kernels/mpm/grid.hpp, Grid::row_spans): the host's P2G records, row by
// row, a span of nodes that holds those its points touched, and the passes over the nodes (the
// P2G's gather, the grid updates, the barrier contact) visit those spans instead of the whole
// rectangle. On an L-shaped body (a long layer with a column on one end, the shape of a flow
// piled against a barrier) the column's rows are far narrower than the rectangle.
// 1. The spans hold every node with mass, and leave out most of the column's rows.
// 2. Nothing stays behind: after the points move, a grid that P2G and the grid update ran on
//    before holds exactly (bitwise, on the host) what a fresh grid holds after the same P2G and
//    update, over every node: the old nodes the points left are zeroed, nothing else changes.
//    Dry (p2g, grid_update) and saturated, both routes of the solver (two_phase_p2g_grid_update
//    in one pass; two_phase_p2g with the wall correction, then two_phase_grid_update).
// 3. The barrier contact keeps to the spans and to the barrier's columns (a barrier displaced
//    by several cells): the same nodes stopped, forces and velocities as over the whole grid.
// 4. TouchedNodes::widen_block, the blocks' spans: a block's rows at once when its stencils
//    start on neighbouring rows, point by point when they lie far apart.
// 5. NodeItems' whole rows keep to their spans (test_node_items.cpp has the rectangles).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <string>
#include <vector>

#include "kernels/mpm/barrier_contact.hpp"
#include "kernels/mpm/grid_update.hpp"
#include "kernels/mpm/p2g.hpp"
#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/two_phase/two_phase_builder.hpp"
#include "kernels/mpm/two_phase/two_phase_p2g_grid_update.hpp"
#include "support/backends.hpp"

namespace {
using namespace lsi::mpm;

template <class Exec>
class MpmRowSpans : public ::testing::Test {};
TYPED_TEST_SUITE(MpmRowSpans, lsi::test::Backends);

constexpr double kLower[2] = {0.0, 0.0}, kUpper[2] = {3.0, 2.0}, kDx = 0.05;
constexpr double kGravity[2] = {0.0, -9.81};
constexpr double kDt = 1e-4;  // s, one explicit step of a soft soil at dx 0.05

// A 2 m long, 0.2 m thick layer with a 0.3 m wide column 0.8 m tall on its left end.
const std::vector<std::array<double, 2>> kLShape = {{{0.1, 0.1}}, {{2.1, 0.1}}, {{2.1, 0.3}},
                                                    {{0.4, 0.3}}, {{0.4, 1.1}}, {{0.1, 1.1}}};

Material soil() {
  Material m;
  m.model = Material::Model::MohrCoulomb;
  m.density = 2000;
  m.young_modulus = 1e7;
  m.poisson_ratio = 0.3;
  m.friction_angle = 30.0 * 3.14159265358979323846 / 180.0;
  return m;
}

// Moves every point by (dx, dy) m.
template <class PositionView>
void shift(const PositionView& position, const int count, const double dx, const double dy) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), position);
  for (int q = 0; q < count; ++q) {
    h(q, 0) += dx;
    h(q, 1) += dy;
  }
  Kokkos::deep_copy(position, h);
}

template <class View>
std::vector<double> values(const View& v) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
  const std::size_t n = h.span();
  return std::vector<double>(h.data(), h.data() + n);
}

// Every node with mass lies in its row's span; returns the nodes the spans hold.
template <class Mem>
int expect_spans_hold_the_mass(const Grid<Mem>& g) {
  const int* spans = g.mass_rows();
  const NodeBox box = g.mass_box();
  EXPECT_NE(spans, nullptr);
  EXPECT_FALSE(box.empty());
  if (spans == nullptr || box.empty()) return 0;
  const auto mass = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), g.mass);
  int held = 0;
  for (int j = box.j0; j <= box.j1; ++j) {
    const int lo = spans[2 * j] > box.i0 ? spans[2 * j] : box.i0;
    const int hi = spans[2 * j + 1] < box.i1 ? spans[2 * j + 1] : box.i1;
    held += hi >= lo ? hi - lo + 1 : 0;
    for (int i = box.i0; i <= box.i1; ++i)
      if (mass(i + g.nx * j) > 0.0) {
        EXPECT_GE(i, lo) << "row " << j;
        EXPECT_LE(i, hi) << "row " << j;
      }
  }
  return held;
}

struct Field {
  std::string name;
  std::vector<double> reused, fresh;
};

// The host's scatters add the same terms in the same order on both grids, and the nodes left
// behind hold zeros: bitwise equal (tolerance 0). A device's atomic additions come in any order:
// round-off of a few additions there, 1e-12 of the field's largest value.
template <class Scatter>
double identity_tolerance() {
  return Scatter::atomic ? 1e-12 : 0.0;
}

void expect_identical(const std::vector<Field>& fields, const double tolerance_rel) {
  for (const Field& f : fields) {
    ASSERT_EQ(f.reused.size(), f.fresh.size()) << f.name;
    double largest = 0.0;
    for (const double v : f.fresh) largest = std::max(largest, std::fabs(v));
    int differ = 0, nonzero = 0;
    for (std::size_t k = 0; k < f.reused.size(); ++k) {
      differ += std::fabs(f.reused[k] - f.fresh[k]) > tolerance_rel * largest ? 1 : 0;
      nonzero += f.fresh[k] != 0.0 ? 1 : 0;
    }
    EXPECT_EQ(differ, 0) << f.name;
    EXPECT_GT(nonzero, 100) << f.name;
  }
}

TYPED_TEST(MpmRowSpans, DryP2GAndGridUpdateKeepToTheRowsAndLeaveNothingBehind) {
  using Exec = TypeParam;
  using Mem = typename Exec::memory_space;
  BodySpec body;
  body.polygon = kLShape;
  body.velocity = {1.0, -0.5};
  body.geostatic_k0 = 0.5;
  body.surface_y = 1.1;
  Particles<Mem> points = build_particles<Mem>({body}, {soil()}, kLower, kDx);
  const Boundaries walls;  // none
  double wall_force[2] = {0.0, 0.0};
  Grid<Mem> reused(kLower, kUpper, kDx);
  P2GScatter<Exec, false> scatter(reused);
  p2g(points, reused, scatter, kGravity);
  grid_update<Exec>(reused, walls, kDt, wall_force);
  if constexpr (!P2GScatter<Exec, false>::atomic) {
    const NodeBox box = reused.mass_box();
    const int held = expect_spans_hold_the_mass(reused);
    // The column is a seventh as wide as the layer: its rows keep the spans under half the box.
    EXPECT_LT(held, (box.i1 - box.i0 + 1) * (box.j1 - box.j0 + 1) / 2);
  } else {
    EXPECT_EQ(reused.mass_rows(), nullptr);  // the atomic scatter records none
  }

  shift(points.position, points.count, 0.7, 0.25);
  p2g(points, reused, scatter, kGravity);
  grid_update<Exec>(reused, walls, kDt, wall_force);
  Grid<Mem> fresh(kLower, kUpper, kDx);
  P2GScatter<Exec, false> fresh_scatter(fresh);
  p2g(points, fresh, fresh_scatter, kGravity);
  grid_update<Exec>(fresh, walls, kDt, wall_force);
  if constexpr (!P2GScatter<Exec, false>::atomic) expect_spans_hold_the_mass(reused);
  expect_identical({{"mass", values(reused.mass), values(fresh.mass)},
                    {"momentum", values(reused.momentum), values(fresh.momentum)},
                    {"force", values(reused.force), values(fresh.force)},
                    {"velocity", values(reused.velocity), values(fresh.velocity)},
                    {"velocity_old", values(reused.velocity_old), values(fresh.velocity_old)}},
                   identity_tolerance<P2GScatter<Exec, false>>());
}

TYPED_TEST(MpmRowSpans, SaturatedP2GAndGridUpdateKeepToTheRowsAndLeaveNothingBehind) {
  using Exec = TypeParam;
  using Mem = typename Exec::memory_space;
  using namespace lsi::mpm::two_phase;
  using Scatter = TwoPhaseScatter<Exec, false>;
  const Liquid liquid;
  TwoPhaseBodySpec body;
  body.polygon = kLShape;
  body.velocity = {1.0, -0.5};
  body.geostatic_k0 = 0.5;
  body.surface_y = 1.1;
  Boundaries walls;
  walls.bottom = {true, 0.1, 0.3};  // the walls' share of the update runs too
  const double g = 9.81;
  for (const bool one_pass : {true, false}) {
    SCOPED_TRACE(one_pass ? "P2G and grid update in one pass"
                          : "P2G with the wall correction, then the grid update");
    TwoPhaseParticles<Mem> points =
        build_two_phase_particles<Mem>({body}, {soil()}, liquid, kLower, kDx);
    const auto step = [&](TwoPhaseGrid<Mem>& grid, Scatter& s) {
      if (one_pass) {
        two_phase_p2g_grid_update<Exec>(points, grid, s, kGravity, liquid.density, g, walls, walls,
                                        kDt, Drag::SemiImplicit);
      } else {
        two_phase_p2g(points, grid, s, kGravity, liquid.density, g, &walls, &walls);
        two_phase_grid_update<Exec>(grid, walls, walls, kDt, kGravity, Drag::SemiImplicit);
      }
    };
    TwoPhaseGrid<Mem> reused(kLower, kUpper, kDx);
    Scatter scatter(reused.solid);
    step(reused, scatter);
    if constexpr (!Scatter::atomic) {
      const NodeBox box = reused.solid.mass_box();
      const int held = expect_spans_hold_the_mass(reused.solid);
      EXPECT_LT(held, (box.i1 - box.i0 + 1) * (box.j1 - box.j0 + 1) / 2);
      EXPECT_EQ(expect_spans_hold_the_mass(reused.liquid), held);
    }

    shift(points.solid.position, points.count, 0.7, 0.25);
    step(reused, scatter);
    TwoPhaseGrid<Mem> fresh(kLower, kUpper, kDx);
    Scatter fresh_scatter(fresh.solid);
    step(fresh, fresh_scatter);
    expect_identical(
        {{"solid mass", values(reused.solid.mass), values(fresh.solid.mass)},
         {"solid momentum", values(reused.solid.momentum), values(fresh.solid.momentum)},
         {"mixture force", values(reused.solid.force), values(fresh.solid.force)},
         {"solid velocity", values(reused.solid.velocity), values(fresh.solid.velocity)},
         {"solid velocity_old", values(reused.solid.velocity_old),
          values(fresh.solid.velocity_old)},
         {"liquid mass", values(reused.liquid.mass), values(fresh.liquid.mass)},
         {"liquid momentum", values(reused.liquid.momentum), values(fresh.liquid.momentum)},
         {"liquid force", values(reused.liquid.force), values(fresh.liquid.force)},
         {"liquid velocity", values(reused.liquid.velocity), values(fresh.liquid.velocity)},
         {"drag", values(reused.drag), values(fresh.drag)}},
        identity_tolerance<Scatter>());
  }
}

// A block moving at 2 m/s into a barrier (H 1 m, B 0.6 m, b 0.2 m, face 80 deg) whose toe at
// x = 0.8 m is displaced by 0.4 m (8 cells): the contact over the spans and the barrier's columns
// against the same contact over every node of a grid without spans.
TYPED_TEST(MpmRowSpans, BarrierContactKeepsToTheSpansAndTheBarriersColumns) {
  using Exec = TypeParam;
  using Mem = typename Exec::memory_space;
  const double displacement = 0.4, dt = 1e-4, friction = 0.3;
  const BarrierShape barrier(0.8, 0.1, 1.0, 0.6, 0.2, 80.0 * 3.14159265358979323846 / 180.0);
  BodySpec body;  // from x = 0.1 into the displaced barrier's upstream face (x 1.2 to 1.3)
  body.polygon = {{{0.1, 0.1}}, {{1.35, 0.1}}, {{1.35, 0.6}}, {{0.1, 0.6}}};
  body.velocity = {2.0, 0.0};
  Particles<Mem> points = build_particles<Mem>({body}, {soil()}, kLower, kDx);
  Grid<Mem> spans(kLower, kUpper, kDx), whole(kLower, kUpper, kDx);
  P2GScatter<Exec, false> scatter(spans);
  p2g(points, spans, scatter, kGravity);
  double wall_force[2] = {0.0, 0.0};
  grid_update<Exec>(spans, Boundaries{}, dt, wall_force);
  // The same nodal fields on a grid that visits every node.
  Kokkos::deep_copy(whole.mass, spans.mass);
  Kokkos::deep_copy(whole.velocity, spans.velocity);
  Kokkos::deep_copy(whole.velocity_old, spans.velocity_old);
  whole.mark_all_active();
  const BarrierContactReport a =
      barrier_contact<Exec>(spans, barrier, displacement, 0.0, friction, dt);
  const BarrierContactReport b =
      barrier_contact<Exec>(whole, barrier, displacement, 0.0, friction, dt);
  EXPECT_GT(b.nodes, 10);  // the block's front rows reach into the barrier
  EXPECT_EQ(a.nodes, b.nodes);
  // The forces are sums over the same nodes cut into other work items: round-off of a few
  // dozen additions, 1e-12 of the largest.
  const double f = std::fabs(b.total(0)) + std::fabs(b.total(1));
  EXPECT_GT(f, 0.0);
  for (int k = 0; k < 3; ++k)
    for (int d = 0; d < 2; ++d) EXPECT_NEAR(a.force[k][d], b.force[k][d], 1e-12 * f) << k << d;
  EXPECT_NEAR(a.work, b.work, 1e-12 * std::fabs(b.work));
  EXPECT_NEAR(a.upstream_moment, b.upstream_moment, 1e-12 * std::fabs(b.upstream_moment));
  // Each node's projection is the same arithmetic: the velocities equal bitwise.
  expect_identical({{"velocity", values(spans.velocity), values(whole.velocity)}}, 0.0);
}

TEST(TouchedNodes, BlocksWidenTheirRowsAtOnceOrPointByPoint) {
  using lsi::mpm::detail::TouchedNodes;
  constexpr int ny = 30;
  const auto fresh_rows = [] {
    std::vector<int> rows(2 * ny);
    for (int j = 0; j < ny; ++j) rows[2 * j] = INT_MAX, rows[2 * j + 1] = INT_MIN;
    return rows;
  };
  {
    SCOPED_TRACE("stencils starting on neighbouring rows: the block's columns on its rows");
    std::vector<int> rows = fresh_rows();
    TouchedNodes t;
    t.rows = rows.data();
    t.ny = ny;
    const int bi[4] = {5, 6, 9, 7}, bj[4] = {10, 11, 10, 12};
    t.widen_block(bi, bj, 4);
    EXPECT_EQ(t.i0, 5);
    EXPECT_EQ(t.i1, 11);
    EXPECT_EQ(t.j0, 10);
    EXPECT_EQ(t.j1, 14);
    for (int j = 0; j < ny; ++j) {
      const bool in = j >= 10 && j <= 14;
      EXPECT_EQ(rows[2 * j], in ? 5 : INT_MAX) << j;
      EXPECT_EQ(rows[2 * j + 1], in ? 11 : INT_MIN) << j;
    }
  }
  {
    SCOPED_TRACE("stencils far apart, one past the top row: point by point, clipped to the grid");
    std::vector<int> rows = fresh_rows();
    TouchedNodes t;
    t.rows = rows.data();
    t.ny = ny;
    const int bi[3] = {2, 20, 3}, bj[3] = {0, 15, 28};
    t.widen_block(bi, bj, 3);
    EXPECT_EQ(t.j1, 30);  // the rectangle is not clipped (gather_region clips it)
    for (int j = 0; j < ny; ++j) {
      int lo = INT_MAX, hi = INT_MIN;
      if (j <= 2) lo = 2, hi = 4;
      if (j >= 15 && j <= 17) lo = 20, hi = 22;
      if (j >= 28) lo = 3, hi = 5;
      EXPECT_EQ(rows[2 * j], lo) << j;
      EXPECT_EQ(rows[2 * j + 1], hi) << j;
    }
  }
}

TEST(NodeItemsRowSpans, WholeRowsKeepToTheirSpansAndSingleNodesIgnoreThem) {
  const NodeBox box{2, 9, 1, 3};
  std::vector<int> spans(2 * 4, 0);
  spans[2] = 4, spans[3] = 6;              // row 1: nodes 4..6
  spans[4] = INT_MAX, spans[5] = INT_MIN;  // row 2: none
  spans[6] = -5, spans[7] = 40;            // row 3: beyond the box both ways: the box's 2..9
  const NodeItemsOf<true> rows(box, spans.data());
  ASSERT_EQ(rows.count(), 3);
  const int expect[3][2] = {{4, 6}, {0, -1}, {2, 9}};
  int visited = 0;
  for (int t = 0; t < rows.count(); ++t)
    rows.visit(t, [&](const int j, const int i_begin, const int i_end) {
      EXPECT_EQ(j, box.j0 + t);
      if (expect[t][1] < expect[t][0]) {
        EXPECT_LT(i_end, i_begin) << "row " << j;
      } else {
        EXPECT_EQ(i_begin, expect[t][0]) << "row " << j;
        EXPECT_EQ(i_end, expect[t][1]) << "row " << j;
      }
      for (int i = i_begin; i <= i_end; ++i) ++visited;
    });
  EXPECT_EQ(visited, 3 + 8);
  // A device's single-node items visit the whole box whatever the spans.
  const NodeItemsOf<false> nodes(box, spans.data());
  EXPECT_EQ(nodes.count(), 8 * 3);
}

}  // namespace

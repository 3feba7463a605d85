// The two-phase step's kernels against each other (kernels/mpm/two_phase/): the solver runs the
// fast forms, these tests check that they compute what the plain forms compute.
// 1. P2G (two_phase_p2g.hpp): the per-thread buffers ("duplicated", the host default) and one
//    buffer with atomic additions (what a GPU runs) give the same 11 nodal fields and the same
//    rectangle of touched nodes, with the mirror-image wall correction on (its contributions go
//    to nodes beside a wall).
// 2. The fused point pass (two_phase_g2p.hpp, two_phase_g2p_update: G2P, effective stress, pore
//    pressure, next step's limits in one pass) leaves every point field, the viscous work and the
//    time-step limits as the separate kernels do (two_phase_g2p, stress_update,
//    pore_pressure_update, two_phase_time_step_limits), with Mohr-Coulomb and the bulk viscosity
//    on so that every branch of the fused pass runs.
// Both on a saturated Mohr-Coulomb column that has collapsed for 20 steps (nonzero velocities of
// both phases, APIC matrices, yielding, compressing points).
// 2b. P2G and the grid update in one pass (two_phase_p2g_grid_update.hpp, the solver's path
//    without the wall correction) give the grid fields and the report of two_phase_p2g followed
//    by two_phase_grid_update, with either drag.
// 2c. The host's grid update, a run of a row's nodes at a time, gives every node the velocities
//    of update_two_phase_node (a device's one node per work item) bit for bit, with walls.
// 3. The reported pore pressure (pore_pressure_update.hpp, cell_mean_pore_pressure): a
//    point-to-point checkerboard laid on the column's field is gone from every cell, the n V
//    weighted integral is kept, and the points' own field is left as it was.
// 4. The wave speed of the time step (two_phase_time_step.hpp, saturated_wave_speed, written with
//    three divisions) against the largest eigenvalue of the 2 x 2 wave problem computed by Eigen
//    from the stiffness and mass matrices themselves.
#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "kernels/mpm/two_phase/two_phase_builder.hpp"
#include "kernels/mpm/two_phase/two_phase_solver.hpp"
#include "support/backends.hpp"
#include "support/tolerances.hpp"

namespace {
using namespace lsi::mpm;
using namespace lsi::mpm::two_phase;
using lsi::test::kTwoRoutesRel;

// The viscous work, a sum over all points in another order in the two reductions: round-off of
// many additions, relative.
constexpr double kReorderedSumRel = 1e-9;
// Pa m^2: an absolute floor for the n V p integral's comparison, should the integral be near zero.
constexpr double kIntegralFloorAbs = 1e-9;

constexpr double kG = 9.81;

template <class Exec>
class MpmTwoPhaseKernels : public ::testing::Test {};
TYPED_TEST_SUITE(MpmTwoPhaseKernels, lsi::test::Backends);

template <class Exec>
struct CollapsingColumn {
  using Mem = typename Exec::memory_space;
  Material skeleton;
  Liquid liquid;
  Boundaries walls;
  TwoPhaseSettings settings;
  TwoPhaseGrid<Mem> grid;
  TwoPhaseParticles<Mem> particles;
  double lo[2] = {0.0, 0.0}, hi[2] = {3.0, 2.0};  // the grid, m

  CollapsingColumn() {
    skeleton.model = Material::Model::MohrCoulomb;
    skeleton.density = 2650;
    skeleton.young_modulus = 1e7;
    skeleton.poisson_ratio = 0.3;
    skeleton.friction_angle = 30.0 * 3.14159265358979323846 / 180.0;
    liquid.bulk_modulus = 3e7;
    const double dx = 0.05;
    walls.left = {true, 0.1, 0.0};
    walls.bottom = {true, 0.1, 0.0};
    grid = TwoPhaseGrid<Mem>(lo, hi, dx);
    TwoPhaseBodySpec body;
    body.polygon = {{{0.1, 0.1}}, {{0.6, 0.1}}, {{0.6, 1.1}}, {{0.1, 1.1}}};
    body.porosity = 0.4;
    body.hydraulic_conductivity = 1e-4;
    body.geostatic_k0 = 0.3;
    body.surface_y = 1.1;
    body.gravity = kG;
    particles = build_two_phase_particles<Mem>({body}, {skeleton}, liquid, lo, dx);
    settings.courant = 0.5;
    settings.drag = Drag::SemiImplicit;
    settings.wall_correction = true;
    settings.bulk_viscosity_linear = 0.06;
    settings.bulk_viscosity_quadratic = 1.5;
  }
};

// A deep copy of every point field.
template <class Mem>
TwoPhaseParticles<Mem> copy_of(const TwoPhaseParticles<Mem>& a) {
  TwoPhaseParticles<Mem> b(a.count);
  const auto& s = a.solid;
  auto& t = b.solid;
  Kokkos::deep_copy(t.position, s.position);
  Kokkos::deep_copy(t.velocity, s.velocity);
  Kokkos::deep_copy(t.affine, s.affine);
  Kokkos::deep_copy(t.velocity_gradient, s.velocity_gradient);
  Kokkos::deep_copy(t.stress, s.stress);
  Kokkos::deep_copy(t.mass, s.mass);
  Kokkos::deep_copy(t.volume, s.volume);
  Kokkos::deep_copy(t.volume0, s.volume0);
  Kokkos::deep_copy(t.plastic_work, s.plastic_work);
  Kokkos::deep_copy(t.deviatoric_strain, s.deviatoric_strain);
  Kokkos::deep_copy(t.material, s.material);
  Kokkos::deep_copy(b.liquid_velocity, a.liquid_velocity);
  Kokkos::deep_copy(b.liquid_affine, a.liquid_affine);
  Kokkos::deep_copy(b.liquid_divergence, a.liquid_divergence);
  Kokkos::deep_copy(b.liquid_mass, a.liquid_mass);
  Kokkos::deep_copy(b.porosity, a.porosity);
  Kokkos::deep_copy(b.pore_pressure, a.pore_pressure);
  Kokkos::deep_copy(b.conductivity, a.conductivity);
  Kokkos::deep_copy(b.traction, a.traction);
  Kokkos::deep_copy(b.volumetric_rate, a.volumetric_rate);
  Kokkos::deep_copy(b.viscous_pressure, a.viscous_pressure);
  return b;
}

// Every value of View a and b, flattened, on the host.
template <class View>
std::vector<double> values(const View& v) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
  std::vector<double> out(h.data(), h.data() + h.span());
  return out;
}

// max |a - b| / max |a| (0 when a is all zeros and b equals it).
double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double scale = 0.0, diff = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    scale = std::max(scale, std::fabs(a[i]));
    diff = std::max(diff, std::fabs(a[i] - b[i]));
  }
  return scale > 0.0 ? diff / scale : diff;
}

// A node field computed two ways.
struct GridField {
  std::string name;
  std::vector<double> first, second;
};

// Every field has content (the column moves) and its two values agree within kTwoRoutesRel of
// its largest value (the callers say why that tolerance).
void expect_same_grid_fields(const std::vector<GridField>& fields) {
  for (const GridField& f : fields) {
    double largest = 0.0;
    for (double v : f.first) largest = std::max(largest, std::fabs(v));
    EXPECT_GT(largest, 0.0) << f.name;
    EXPECT_LT(relative_difference(f.first, f.second), kTwoRoutesRel) << f.name;
  }
}

TYPED_TEST(MpmTwoPhaseKernels, AtomicAndBufferedP2GGiveTheSameGrid) {
  using Exec = TypeParam;
  using Mem = typename Exec::memory_space;
  CollapsingColumn<Exec> c;
  TwoPhaseSolver<Exec> solver(c.grid, c.particles, {c.skeleton}, c.liquid, c.walls, c.settings);
  for (int i = 0; i < 20; ++i) ASSERT_EQ(solver.step(), Status::Running);
  // A surface load on every point (the column has none), a few newtons per metre of thickness
  // like the points' weight, so that its lanes of the mixture force are compared too.
  auto traction = Kokkos::create_mirror_view(c.particles.traction);
  for (int q = 0; q < c.particles.count; ++q) {
    traction(q, 0) = 3.0 * (q % 7) - 9.0;
    traction(q, 1) = -2.0 * (q % 5);
  }
  Kokkos::deep_copy(c.particles.traction, traction);

  TwoPhaseGrid<Mem> buffered_grid(c.lo, c.hi, c.grid.dx());
  TwoPhaseScatter<Exec, false> buffered(buffered_grid.solid);
  const double* g = c.settings.gravity;
  two_phase_p2g(c.particles, buffered_grid, buffered, g, c.liquid.density, kG, &c.walls, &c.walls);
  // The atomic scatter without tiles, with tiles of 128 points (a GPU's default), and with tiles
  // of 12 points and room for 30 nodes: the teams within a row of cells tile, those over two
  // rows do not (test_mpm_p2g_scatters.cpp). With the wall correction: the mirror images'
  // contributions go into the tiles too.
  struct Tiling {
    int points, nodes;
  };
  for (const Tiling tiling : {Tiling{0, 0}, Tiling{128, 0}, Tiling{12, 30}}) {
    SCOPED_TRACE("tiles of " + std::to_string(tiling.points) + " points");
    if (tiling.points > 0 && !TwoPhaseScatter<Exec, true>::atomic) continue;  // Serial: none
    TwoPhaseGrid<Mem> atomic_grid(c.lo, c.hi, c.grid.dx());
    TwoPhaseScatter<Exec, true> atomic(atomic_grid.solid);
    atomic.use_tiles(tiling.points);  // at any number of points (800 here)
    if (tiling.nodes > 0) atomic.tile_nodes = tiling.nodes;
    two_phase_p2g(c.particles, atomic_grid, atomic, g, c.liquid.density, kG, &c.walls, &c.walls);

    for (const auto* grid : {&buffered_grid.liquid, &atomic_grid.solid, &atomic_grid.liquid}) {
      const NodeBox a = buffered_grid.solid.mass_box(), b = grid->mass_box();
      EXPECT_EQ(a.i0, b.i0);
      EXPECT_EQ(a.i1, b.i1);
      EXPECT_EQ(a.j0, b.j0);
      EXPECT_EQ(a.j1, b.j1);
      EXPECT_FALSE(a.empty());
    }
    // The same terms added in another order: round-off of a few additions, 1e-12 of the
    // largest nodal value.
    expect_same_grid_fields(
        {{"solid mass", values(buffered_grid.solid.mass), values(atomic_grid.solid.mass)},
         {"solid momentum", values(buffered_grid.solid.momentum),
          values(atomic_grid.solid.momentum)},
         {"mixture force", values(buffered_grid.solid.force), values(atomic_grid.solid.force)},
         {"liquid mass", values(buffered_grid.liquid.mass), values(atomic_grid.liquid.mass)},
         {"liquid momentum", values(buffered_grid.liquid.momentum),
          values(atomic_grid.liquid.momentum)},
         {"liquid force", values(buffered_grid.liquid.force), values(atomic_grid.liquid.force)},
         {"drag", values(buffered_grid.drag), values(atomic_grid.drag)}});
  }
}

TYPED_TEST(MpmTwoPhaseKernels, P2GAndGridUpdateInOnePassMatchTheTwoKernels) {
  using Exec = TypeParam;
  using Mem = typename Exec::memory_space;
  CollapsingColumn<Exec> c;
  TwoPhaseSolver<Exec> solver(c.grid, c.particles, {c.skeleton}, c.liquid, c.walls, c.settings);
  for (int i = 0; i < 20; ++i) ASSERT_EQ(solver.step(), Status::Running);
  const double* g = c.settings.gravity;
  const double dt = 1e-4;
  for (const Drag drag : {Drag::SemiImplicit, Drag::Explicit}) {
    SCOPED_TRACE(drag == Drag::SemiImplicit ? "semi-implicit drag" : "explicit drag");
    // Two kernels: P2G without the wall correction (the one pass is for steps without it), then
    // the grid update.
    TwoPhaseGrid<Mem> two(c.lo, c.hi, c.grid.dx()), one(c.lo, c.hi, c.grid.dx());
    TwoPhaseScatter<Exec, false> two_scatter(two.solid), one_scatter(one.solid);
    two_phase_p2g(c.particles, two, two_scatter, g, c.liquid.density, kG, nullptr, nullptr);
    const GridUpdateReport a = two_phase_grid_update<Exec>(two, c.walls, c.walls, dt, g, drag);
    const GridUpdateReport b = two_phase_p2g_grid_update<Exec>(
        c.particles, one, one_scatter, g, c.liquid.density, kG, c.walls, c.walls, dt, drag);
    // The same sums and per-node arithmetic; a * b + c contracted into fused multiply-adds may
    // differ between the two inlining contexts: 1e-12 of the largest nodal value.
    expect_same_grid_fields(
        {{"solid mass", values(two.solid.mass), values(one.solid.mass)},
         {"solid momentum", values(two.solid.momentum), values(one.solid.momentum)},
         {"mixture force", values(two.solid.force), values(one.solid.force)},
         {"solid velocity", values(two.solid.velocity), values(one.solid.velocity)},
         {"solid velocity_old", values(two.solid.velocity_old), values(one.solid.velocity_old)},
         {"liquid mass", values(two.liquid.mass), values(one.liquid.mass)},
         {"liquid momentum", values(two.liquid.momentum), values(one.liquid.momentum)},
         {"liquid force", values(two.liquid.force), values(one.liquid.force)},
         {"liquid velocity", values(two.liquid.velocity), values(one.liquid.velocity)},
         {"liquid velocity_old", values(two.liquid.velocity_old), values(one.liquid.velocity_old)},
         {"drag", values(two.drag), values(one.drag)}});
    // The reductions: the column stands on the bottom wall (a force and a wall dissipation) and
    // its liquid seeps (drag dissipation, seepage work).
    const std::vector<double> reports_two = {a.wall_dissipation, a.drag_dissipation,
                                             a.seepage_gravity_work, a.wall_force[0],
                                             a.wall_force[1]},
                              reports_one = {b.wall_dissipation, b.drag_dissipation,
                                             b.seepage_gravity_work, b.wall_force[0],
                                             b.wall_force[1]};
    EXPECT_GT(std::fabs(a.wall_force[1]), 0.0);
    EXPECT_GT(std::fabs(a.drag_dissipation), 0.0);
    for (std::size_t k = 0; k < reports_two.size(); ++k)
      EXPECT_NEAR(reports_one[k], reports_two[k], kTwoRoutesRel * std::fabs(reports_two[k]))
          << "report value " << k;
  }
}

TYPED_TEST(MpmTwoPhaseKernels, FusedPointPassMatchesTheSeparateKernels) {
  using Exec = TypeParam;
  using Mem = typename Exec::memory_space;
  CollapsingColumn<Exec> c;
  TwoPhaseSolver<Exec> solver(c.grid, c.particles, {c.skeleton}, c.liquid, c.walls, c.settings);
  for (int i = 0; i < 20; ++i) ASSERT_EQ(solver.step(), Status::Running);
  // The grid as the solver left it (the last step's P2G and grid update): both paths read it.
  const double dt = solver.time_step();
  TwoPhaseParticles<Mem> separate = copy_of(c.particles), fused = copy_of(c.particles);

  Kokkos::View<PreparedMaterial*, Mem> table("materials", 1);
  auto host = Kokkos::create_mirror_view(table);
  host(0) = PreparedMaterial(c.skeleton);
  Kokkos::deep_copy(table, host);
  const Kokkos::View<const PreparedMaterial*, Mem> materials = table;
  const BulkViscosity viscosity{c.settings.bulk_viscosity_linear,
                                c.settings.bulk_viscosity_quadratic};
  const double dx = c.grid.dx();

  const TwoPhaseG2PReport a = two_phase_g2p<Exec>(separate, c.grid, dt, &c.walls, &c.walls);
  stress_update<Exec, true>(separate.solid, materials, dt);
  const double viscous_a =
      pore_pressure_update<Exec>(separate, c.grid, c.liquid, dt, materials, viscosity);
  const TimeStepLimits limits_a = two_phase_time_step_limits<Exec>(
      separate, materials, c.liquid, kG, viscosity.linear, viscosity.quadratic, dx);

  TwoPhasePointWork work;
  work.plastic = true;
  work.pore_pressure = true;
  work.constants = {c.liquid.density, c.liquid.bulk_modulus, kG,
                    viscosity.linear, viscosity.quadratic,   dx};
  const TwoPhaseG2PReport b =
      two_phase_g2p_update<Exec>(fused, c.grid, dt, materials, work, &c.walls, &c.walls);

  // The same operations on each point in the same order; only the compiler's contraction of
  // a * b + c into fused multiply-adds may differ between the two inlining contexts: 1e-12 of
  // each field's largest value (a wrong sign or a missing term shows as O(1)).
  struct Field {
    std::string name;
    std::vector<double> separate, fused;
  };
  const auto& s = separate.solid;
  const auto& f = fused.solid;
  const std::vector<Field> fields = {
      {"position", values(s.position), values(f.position)},
      {"solid velocity", values(s.velocity), values(f.velocity)},
      {"solid affine", values(s.affine), values(f.affine)},
      {"effective stress", values(s.stress), values(f.stress)},
      {"volume", values(s.volume), values(f.volume)},
      {"plastic work", values(s.plastic_work), values(f.plastic_work)},
      {"deviatoric strain", values(s.deviatoric_strain), values(f.deviatoric_strain)},
      {"liquid velocity", values(separate.liquid_velocity), values(fused.liquid_velocity)},
      {"liquid affine", values(separate.liquid_affine), values(fused.liquid_affine)},
      {"porosity", values(separate.porosity), values(fused.porosity)},
      {"pore pressure", values(separate.pore_pressure), values(fused.pore_pressure)},
      {"volumetric rate", values(separate.volumetric_rate), values(fused.volumetric_rate)},
      {"viscous pressure", values(separate.viscous_pressure), values(fused.viscous_pressure)}};
  for (const Field& field : fields)
    EXPECT_LT(relative_difference(field.separate, field.fused), kTwoRoutesRel) << field.name;
  // The velocity gradient and the liquid divergence, which the fields above depend on, stay in
  // the fused pass's registers: their point fields are left as they were.
  EXPECT_EQ(values(f.velocity_gradient), values(c.particles.solid.velocity_gradient));
  EXPECT_EQ(values(fused.liquid_divergence), values(c.particles.liquid_divergence));
  // The column yields and compresses somewhere: the plastic and viscous branches ran.
  double plastic = 0.0, viscous_pressure = 0.0;
  for (double v : fields[5].fused) plastic = std::max(plastic, v);
  for (double v : fields[12].fused) viscous_pressure = std::max(viscous_pressure, v);
  EXPECT_GT(plastic, 0.0);
  EXPECT_GT(viscous_pressure, 0.0);

  EXPECT_EQ(a.health.non_finite, b.health.non_finite);
  EXPECT_EQ(a.health.outside, b.health.outside);
  EXPECT_NEAR(a.health.max_speed, b.health.max_speed, kTwoRoutesRel * a.health.max_speed);
  EXPECT_NEAR(a.load_work, b.load_work, kTwoRoutesRel * std::fabs(a.load_work) + 1e-300);
  // The viscous work is a sum over the points: their order differs between the two reductions.
  EXPECT_NEAR(viscous_a, b.viscous_work, kReorderedSumRel * std::fabs(viscous_a));
  EXPECT_NE(viscous_a, 0.0);
  EXPECT_NEAR(limits_a.wave_speed, b.limits.wave_speed, kTwoRoutesRel * limits_a.wave_speed);
  EXPECT_NEAR(limits_a.permeability_dt, b.limits.permeability_dt,
              kTwoRoutesRel * limits_a.permeability_dt);
}

TYPED_TEST(MpmTwoPhaseKernels, CellMeanPorePressureRemovesTheCheckerboard) {
  using Exec = TypeParam;
  using Mem = typename Exec::memory_space;
  CollapsingColumn<Exec> c;
  // A smooth field (hydrostatic in y) plus +-50 kPa alternating from point to point: 2 x 2 points
  // per cell, numbered along rows, so each cell holds two of each sign.
  auto p_host = Kokkos::create_mirror_view(c.particles.pore_pressure);
  const auto x_host =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.particles.solid.position);
  const auto n_host =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.particles.porosity);
  const auto v_host =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.particles.solid.volume);
  const double dx = c.grid.dx();
  for (int q = 0; q < c.particles.count; ++q) {
    // The point's column and row on the half-cell lattice (the column has not moved yet).
    const long k = std::lround((x_host(q, 0) - c.lo[0]) / dx * 2 - 0.5) +
                   std::lround((x_host(q, 1) - c.lo[1]) / dx * 2 - 0.5);
    p_host(q) = 1e4 * (1.1 - x_host(q, 1)) + (k % 2 == 0 ? 5e4 : -5e4);
  }
  Kokkos::deep_copy(c.particles.pore_pressure, p_host);
  Kokkos::View<double*, Mem> mean("mean", c.particles.count);
  cell_mean_pore_pressure<Exec>(c.particles, c.grid, mean);
  const auto m_host = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), mean);
  const auto p_after =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), c.particles.pore_pressure);
  double integral_before = 0.0, integral_after = 0.0, worst = 0.0;
  for (int q = 0; q < c.particles.count; ++q) {
    EXPECT_EQ(p_after(q), p_host(q)) << "the points' own field must not change, point " << q;
    integral_before += n_host(q) * v_host(q) * p_host(q);
    integral_after += n_host(q) * v_host(q) * m_host(q);
    // In a cell the points' weights are equal, so the checkerboard cancels: what is left is the
    // smooth field's mean over the cell, within its variation across one cell (1e4 Pa/m x dx).
    worst = std::max(worst, std::fabs(m_host(q) - 1e4 * (1.1 - x_host(q, 1))));
  }
  EXPECT_LT(worst, 1e4 * dx);  // the checkerboard's 5e4 Pa would be far above this
  // A projection: the n V weighted integral is kept, to round-off of the sums.
  EXPECT_NEAR(integral_after, integral_before,
              kTwoRoutesRel * std::fabs(integral_before) + kIntegralFloorAbs);
}

TEST(TwoPhaseGridUpdate, ARunOfNodesAtATimeGivesEachNodeItsOwnUpdate) {
  // The host's grid update takes a row's nodes a run at a time (update_two_phase_node_run: the
  // velocities in a loop over the run's nodes, the walls and the reductions after it); a device
  // takes one node per work item (update_two_phase_node). Rows of 41 nodes (two runs and a
  // shorter one) whose sums mix empty, dry and wet nodes, with walls at both ends and below
  // (Coulomb, bilateral, no-slip; the liquid's left wall open), against update_two_phase_node
  // called node by node. The explicit drag takes one node at a time on the host as well: its
  // half checks the update across the rows' work items. What each node's update computes is
  // checked by the drag and consolidation tests of test_mpm_two_phase.cpp.
  using Exec = Kokkos::DefaultHostExecutionSpace;
  using Mem = Exec::memory_space;
  const double lo[2] = {0.0, 0.0}, hi[2] = {2.0, 0.5}, dt = 2e-4, g[2] = {1.5, -9.5};
  TwoPhaseGrid<Mem> run(lo, hi, 0.05), one(lo, hi, 0.05);
  ASSERT_EQ(run.solid.nx, 41);
  Boundaries walls, liquid_walls;
  walls.left = {true, 0.1, 0.3};
  walls.right = {true, 1.9, 0.0, true};
  walls.bottom = {true, 0.1, 0.5};
  walls.top = {true, 0.45, 0.0, false, true};
  liquid_walls = walls;
  liquid_walls.left.active = false;
  unsigned state = 12345u;  // a fixed pseudo-random sequence in [-1, 1)
  auto next = [&state]() {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) * (2.0 / 16777216.0) - 1.0;
  };
  for (TwoPhaseGrid<Mem>* grid : {&run, &one}) {
    state = 12345u;
    for (int n = 0; n < run.size(); ++n) {
      const bool empty = n % 7 == 3, dry = n % 5 == 1;
      grid->solid.mass(n) = empty ? 0.0 : 2.0 + next();
      grid->liquid.mass(n) = empty || dry ? 0.0 : 1.0 + 0.5 * next();
      grid->drag(n) = 3e3 * (1.5 + next());
      for (int d = 0; d < 2; ++d) {
        grid->solid.momentum(n, d) = 4.0 * next();
        grid->liquid.momentum(n, d) = dry ? 0.0 : 2.0 * next();
        grid->solid.force(n, d) = 5e3 * next();
        grid->liquid.force(n, d) = dry ? 0.0 : 2e3 * next();
      }
    }
  }
  for (const Drag drag : {Drag::SemiImplicit, Drag::Explicit}) {
    SCOPED_TRACE(drag == Drag::SemiImplicit ? "semi-implicit drag" : "explicit drag");
    const GridUpdateReport a = two_phase_grid_update<Exec>(run, walls, liquid_walls, dt, g, drag);
    TwoPhaseUpdateSums b{0.0, 0.0, 0.0, 0.0, 0.0};
    const auto& S = one.solid;
    const auto& L = one.liquid;
    for (int j = 0; j < S.ny; ++j)
      for (int ii = 0; ii < S.nx; ++ii) {
        const int i = ii + S.nx * j;
        const TwoPhaseNodeSums n{S.mass(i),
                                 L.mass(i),
                                 {S.momentum(i, 0), S.momentum(i, 1)},
                                 {L.momentum(i, 0), L.momentum(i, 1)},
                                 {S.force(i, 0), S.force(i, 1)},
                                 {L.force(i, 0), L.force(i, 1)},
                                 one.drag(i)};
        if (drag == Drag::SemiImplicit)
          update_two_phase_node<true>(S, L, i, ii, j, n, walls, liquid_walls, S.origin[0],
                                      S.origin[1], S.dx, 1e-9 * S.dx, dt, g[0], g[1], b);
        else
          update_two_phase_node<false>(S, L, i, ii, j, n, walls, liquid_walls, S.origin[0],
                                       S.origin[1], S.dx, 1e-9 * S.dx, dt, g[0], g[1], b);
      }
    // Each node's velocities: the same operations on the same values, exact divisions.
    int differ = 0;
    for (int i = 0; i < run.size(); ++i)
      for (int d = 0; d < 2; ++d)
        differ += run.solid.velocity(i, d) != S.velocity(i, d) ||
                  run.solid.velocity_old(i, d) != S.velocity_old(i, d) ||
                  run.liquid.velocity(i, d) != L.velocity(i, d) ||
                  run.liquid.velocity_old(i, d) != L.velocity_old(i, d);
    EXPECT_EQ(differ, 0);
    // The reductions: every wall acts, and the nodes' shares are added per thread and then
    // joined (the threads cut the rows): a few roundings of sums of about 400 values.
    const std::vector<double> got = {a.wall_dissipation, a.drag_dissipation, a.seepage_gravity_work,
                                     a.wall_force[0], a.wall_force[1]},
                              want = {b.wall_lost, b.drag_lost, b.seep, b.rx, b.ry};
    for (std::size_t k = 0; k < got.size(); ++k) {
      EXPECT_GT(std::fabs(want[k]), 0.0) << "report value " << k;
      EXPECT_NEAR(got[k], want[k], kTwoRoutesRel * std::fabs(want[k])) << "report value " << k;
    }
  }
}

TEST(SaturatedWaveSpeed, IsTheFastestWaveOfTheTwoPhases) {
  // Per unit volume: masses m_S = (1-n) rho_S, m_L = n rho_L; stiffness (sigma' = M eps_S,
  // p = -(K_L/n)((1-n) eps_S + n eps_L)) K = [[M + (1-n)^2 K_L/n, (1-n) K_L], [(1-n) K_L, n K_L]].
  // The undrained speed sqrt((M + K_L/n) / rho_m) is a Rayleigh quotient of the same problem, so
  // the speed is the largest root; the soft and stiff ends of the stability matrix included.
  const double rho_S = 2650.0, rho_L = 1000.0;
  int cases = 0;
  for (double M : {1e5, 1e7, 1.35e9})
    for (double K_L : {2e6, 3e7, 2.2e9})
      for (double n : {0.05, 0.2, 0.4, 0.6, 0.95}) {
        const double mS = (1 - n) * rho_S, mL = n * rho_L;
        Eigen::Matrix2d K;
        K << M + (1 - n) * (1 - n) * K_L / n, (1 - n) * K_L, (1 - n) * K_L, n * K_L;
        const Eigen::Vector2d inv_sqrt_m(1 / std::sqrt(mS), 1 / std::sqrt(mL));
        // symmetric form m^-1/2 K m^-1/2: the same eigenvalues c^2, computed stably
        const Eigen::Matrix2d A = inv_sqrt_m.asDiagonal() * K * inv_sqrt_m.asDiagonal();
        const double c_max =
            std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(A).eigenvalues().maxCoeff());
        // Both are a few roundings of the same numbers: 1e-12 relative.
        EXPECT_NEAR(saturated_wave_speed(M, rho_S, n, rho_L, K_L), c_max, kTwoRoutesRel * c_max)
            << "M " << M << " K_L " << K_L << " n " << n;
        ++cases;
      }
  EXPECT_EQ(cases, 45);
  // The example of the file comment: M = 1e7 Pa, K_L = 2.2e9 Pa, n = 0.4: c_f = 1857 m/s.
  EXPECT_NEAR(saturated_wave_speed(1e7, rho_S, 0.4, rho_L, 2.2e9), 1857.0, 0.5);
}

}  // namespace

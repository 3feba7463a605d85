// Verification of the rigid barrier (kernels/mpm/barrier_*.hpp):
//  * its motion on the base under a known load (barrier_dynamics.hpp) against the closed forms:
//    a constant push, a push then free deceleration to rest, sticking below the friction
//    threshold (including the extra base friction of a downward load), and a triangular pulse on
//    an inclined face against the exact piecewise-linear response of the analytical model
//    (kernels/closed_form/rigid_block_response.hpp);
//  * the contact of an elastic block with a fixed barrier (barrier_contact.hpp) against
//    one-dimensional wave theory and momentum conservation;
//  * a free, frictionless barrier hit by the block: momentum of block + barrier conserved;
//  * the volume of points inside the barrier (overtopping.hpp, the contact-leak diagnostic);
//  * the moment of the contact forces about the downstream toe (barrier_contact.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "kernels/closed_form/rigid_block_response.hpp"
#include "kernels/mpm/barrier_coupling.hpp"
#include "kernels/mpm/overtopping.hpp"
#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"
#include "support/backends.hpp"

namespace {
using namespace lsi::mpm;

constexpr double kG = 9.81;
constexpr double kPi = 3.14159265358979323846;

BarrierMotion block(double mass, double mu) {
  BarrierMotion b;
  b.mass = mass;
  b.base_friction = mu;
  b.gravity = kG;
  return b;
}

// Constant push F > mu M g: x = (F - mu M g) t^2 / (2 M). The update is exact for a constant
// force (mean velocity of the step), so only round-off remains: 1e-12 relative.
TEST(BarrierMotion, ConstantPushGivesUniformAcceleration) {
  BarrierMotion b = block(5000.0, 0.5);
  const double F = 40000.0, dt = 1e-3;
  const int n = 1500;
  for (int i = 0; i < n; ++i) b.advance(F, 0.0, dt);
  const double t = n * dt, a = (F - 0.5 * 5000.0 * kG) / 5000.0;
  EXPECT_NEAR(b.displacement / (0.5 * a * t * t), 1.0, 1e-12);
  EXPECT_NEAR(b.velocity / (a * t), 1.0, 1e-12);
  // Friction work: tan(delta_b) M g times the distance slid.
  EXPECT_NEAR(b.friction_work / (0.5 * 5000.0 * kG * b.displacement), 1.0, 1e-12);
}

// Push F for T, then nothing: it decelerates at mu g and stops at
//   x = a T^2 / 2 + (a T)^2 / (2 mu g),  a = (F - mu M g) / M,
// within the step where v reaches zero (located exactly). 1e-12 relative (round-off).
TEST(BarrierMotion, PushThenStopsWhereTheClosedFormSays) {
  BarrierMotion b = block(8000.0, 0.4);
  const double F = 60000.0, dt = 1e-3, T = 0.5;
  int i = 0;
  for (; i < 500; ++i) b.advance(F, 0.0, dt);
  for (; i < 3000; ++i) b.advance(0.0, 0.0, dt);
  const double a = (F - 0.4 * 8000.0 * kG) / 8000.0;
  const double x = 0.5 * a * T * T + (a * T) * (a * T) / (2 * 0.4 * kG);
  EXPECT_EQ(b.velocity, 0.0);
  EXPECT_NEAR(b.displacement / x, 1.0, 1e-12);
}

// Below the threshold nothing moves, exactly; a downward load on the barrier (F_y < 0) raises
// the base's normal force, so a push above mu M g but below mu (M g - F_y) sticks too.
TEST(BarrierMotion, SticksBelowTheFrictionThreshold) {
  BarrierMotion b = block(5000.0, 0.5);
  const double limit = 0.5 * 5000.0 * kG;
  for (int i = 0; i < 1000; ++i) b.advance(0.999 * limit, 0.0, 1e-3);
  EXPECT_EQ(b.displacement, 0.0);
  EXPECT_EQ(b.velocity, 0.0);
  for (int i = 0; i < 1000; ++i) b.advance(1.5 * limit, -0.6 * 5000.0 * kG, 1e-3);
  EXPECT_EQ(b.displacement, 0.0);
  // and slides once the same push has no downward load to help the base.
  b.advance(1.5 * limit, 0.0, 1e-3);
  EXPECT_GT(b.displacement, 0.0);
}

// Triangular normal pulse on a face inclined at beta = 70 deg (peak 60 kN/m at T1 = 0.1 s, end
// T2 = 0.6 s), resolved as the flow's force on the barrier, (N sin(beta), -N cos(beta)), and
// sampled at mid-step: the final displacement against the exact response of the analytical
// model's sliding block (drive sin(beta) - mu cos(beta)). Mid-step sampling is second order in
// dt: at dt = T2 / 60 000 the error is ~1e-9; asserted 1e-6 relative (the brief's bound).
TEST(BarrierMotion, TriangularPulseMatchesTheExactRigidBlockResponse) {
  const double M = 6000.0, mu = 0.45, beta = 70.0 * kPi / 180.0, P = 60000.0, T1 = 0.1, T2 = 0.6;
  auto N = [&](double t) {
    if (t <= 0.0 || t >= T2) return 0.0;
    return t < T1 ? P * t / T1 : P * (T2 - t) / (T2 - T1);
  };
  BarrierMotion b = block(M, mu);
  const int steps = 120000;  // to 2 T2: the block has stopped
  const double dt = 2 * T2 / steps;
  for (int i = 0; i < steps; ++i) {
    const double n = N((i + 0.5) * dt);
    b.advance(n * std::sin(beta), -n * std::cos(beta), dt);
  }
  lsi::SlidingBlock sb;
  sb.mass = M;
  sb.base_friction = mu;
  sb.drive = std::sin(beta) - mu * std::cos(beta);
  const double t[4] = {0.0, T1, T2, 2 * T2}, f[4] = {0.0, P, 0.0, 0.0};
  const lsi::RigidBlockSummary exact = lsi::rigid_block_response(t, f, 4, sb);
  std::printf("[measured] pulse: barrier %.9f m, exact %.9f m\n", b.displacement,
              exact.final_displacement);
  ASSERT_GT(exact.final_displacement, 0.01);  // the pulse does move it
  EXPECT_NEAR(b.displacement / exact.final_displacement, 1.0, 1e-6);
  EXPECT_EQ(b.velocity, 0.0);
}

// An elastic block (nu = 0, so plane strain is one-dimensional along x: constrained modulus
// = E) of length L and height h moves at v0 onto a fixed vertical barrier face, without gravity.
// One-dimensional wave theory (a bar hitting a rigid wall): the contact lasts 2 L / c,
// c = sqrt(E / rho), with the constant force rho c v0 h, and the bar leaves at -v0: impulse
// 2 M v0.
struct ImpactRun {
  double impulse = 0;           // N s/m on the barrier (x), time integral of the contact force
  double momentum_change = 0;   // kg m/s per m, block before - after (x)
  double rebound = 0;           // final velocity / -v0
  double duration = 0;          // s, time with a contact force
  double plateau = 0;           // N/m, median contact force while in contact
  double barrier_momentum = 0;  // free barrier: M_b V at the end
  double block_mass = 0;
};

template <class Exec>
ImpactRun impact(bool free_barrier, double barrier_mass = 0.0, double dx = 0.05) {
  using Mem = typename Exec::memory_space;
  Material m;
  m.density = 2000;
  m.young_modulus = 1e7;
  m.poisson_ratio = 0.0;
  const double L = 1.0, h = 0.4, v0 = 2.0;
  const double lo[2] = {0, 0}, hi[2] = {4.0, 1.0};
  Grid<Mem> grid(lo, hi, dx);
  BodySpec body;
  const double x0 = 0.5, y0 = 0.3;  // the block's front touches the face at t = 0
  body.polygon = {{{x0, y0}}, {{x0 + L, y0}}, {{x0 + L, y0 + h}}, {{x0, y0 + h}}};
  auto particles = build_particles<Mem>({body}, {m}, lo, dx);
  {
    auto v = Kokkos::create_mirror_view(particles.velocity);
    for (int q = 0; q < particles.count; ++q) {
      v(q, 0) = v0;
      v(q, 1) = 0.0;
    }
    Kokkos::deep_copy(particles.velocity, v);
  }
  Settings s;
  s.courant = 0.5;
  s.gravity[0] = s.gravity[1] = 0.0;
  Solver<Exec> solver(grid, particles, {m}, Boundaries{}, s);
  Barrier b;
  // Vertical face at x = 1.5 (on a grid line), 0.8 m high from y = 0.1: covers the block.
  b.shape = BarrierShape(x0 + L, 0.1, 0.8, 0.6, 0.6, 0.5 * kPi);
  b.face_friction = 0.0;
  b.fixed = !free_barrier;
  b.motion.mass = barrier_mass;
  b.motion.base_friction = 0.0;
  b.motion.gravity = 0.0;
  solver.attach_barrier(b);
  auto mass = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), particles.mass);
  auto vel = Kokkos::create_mirror_view(particles.velocity);
  auto momentum = [&] {
    Kokkos::deep_copy(vel, particles.velocity);
    double p = 0;
    for (int q = 0; q < particles.count; ++q) p += mass(q) * vel(q, 0);
    return p;
  };
  ImpactRun r;
  for (int q = 0; q < particles.count; ++q) r.block_mass += mass(q);
  const double p0 = momentum();
  const double c = std::sqrt(m.young_modulus / m.density);
  const double t_end = 2 * L / c + 0.1;  // contact, and a margin
  std::vector<double> forces;
  while (solver.time() < t_end) {
    EXPECT_EQ(solver.step(), Status::Running);
    const double fx = solver.barrier_contact_report().total(0);
    r.impulse += fx * solver.time_step();
    if (fx > 0) {
      r.duration += solver.time_step();
      forces.push_back(fx);
    }
  }
  const double p1 = momentum();
  r.momentum_change = p0 - p1;
  r.rebound = -(p1 / r.block_mass) / v0;
  std::sort(forces.begin(), forces.end());
  r.plateau = forces.empty() ? 0 : forces[forces.size() / 2];
  r.barrier_momentum = barrier_mass * solver.barrier().motion.velocity;
  return r;
}

template <class Exec>
class MpmBarrier : public ::testing::Test {};
TYPED_TEST_SUITE(MpmBarrier, lsi::test::Backends);

// Grid contact is inelastic at the scale of a cell (the nodes the barrier stops carry mass from
// material up to 1.5 cells away), so the rebound falls short of v0 by an amount that shrinks
// with the cell size: measured rebound 0.910, 0.946, 0.965, 0.977 and contact duration +14, +8,
// +3.7, +1.2 % at dx = 0.1, 0.05, 0.025, 0.0125 m. The test runs dx = 0.05 and 0.025 m.
TYPED_TEST(MpmBarrier, ElasticBlockOnFixedBarrierReturnsItsMomentumChange) {
  const double rho = 2000, E = 1e7, v0 = 2.0, h = 0.4, L = 1.0;
  const double c = std::sqrt(E / rho);
  const ImpactRun coarse = impact<TypeParam>(false, 0.0, 0.05);
  const ImpactRun r = impact<TypeParam>(false, 0.0, 0.025);
  for (const ImpactRun* q : {&coarse, &r}) {
    std::printf(
        "[measured] impulse %.2f N s/m, momentum change %.2f, 2 M v0 %.2f, rebound "
        "%.4f, contact %.4f s (2L/c %.4f s), plateau force %.0f N/m (rho c v0 h %.0f)\n",
        q->impulse, q->momentum_change, 2 * q->block_mass * v0, q->rebound, q->duration, 2 * L / c,
        q->plateau, rho * c * v0 * h);
    // The impulse the barrier receives is the block's momentum change: the contact is the only
    // horizontal force, so they agree to round-off (the brief's bound is 2 %).
    EXPECT_NEAR(q->impulse / q->momentum_change, 1.0, 1e-9);
  }
  // Against the wave solution at dx = 0.025 m: impulse 2 M v0 within 2 % (measured -1.7 %),
  // contact duration 2 L / c within 5 % (measured +3.7 %; the contact opens and closes one node
  // column at a time), plateau force rho c v0 h within 5 % (the median force in contact; it
  // rings about the plateau).
  EXPECT_NEAR(r.impulse / (2 * r.block_mass * v0), 1.0, 0.02);
  EXPECT_NEAR(r.duration / (2 * L / c), 1.0, 0.05);
  EXPECT_NEAR(r.plateau / (rho * c * v0 * h), 1.0, 0.05);
  // The loss converges away: halving the cell shrinks the rebound deficit to 0.65 of its value
  // (measured); asserted below 0.8.
  EXPECT_LT((1 - r.rebound) / (1 - coarse.rebound), 0.8);
}

// A free, frictionless barrier (mass = the block's) on a frictionless base, no gravity: the
// only horizontal forces are the contact's, so the block's momentum lost is the barrier's gained,
// to round-off.
TYPED_TEST(MpmBarrier, FreeBarrierConservesMomentum) {
  const double block_mass = 2000 * 1.0 * 0.4;
  const ImpactRun r = impact<TypeParam>(true, block_mass);
  std::printf("[measured] free barrier: block lost %.4f, barrier gained %.4f kg m/s per m\n",
              r.momentum_change, r.barrier_momentum);
  EXPECT_GT(r.barrier_momentum, 0.3 * block_mass * 2.0);  // it did push the barrier
  EXPECT_NEAR(r.barrier_momentum / r.momentum_change, 1.0, 1e-9);
}

// Three grid nodes on the upstream face of a trapezoid (H 4, B 3, b 1 m, face 80 deg, toe at
// x = 1 m, displaced 0.25 m) moving into it at known velocities, one more moving away: the contact
// stops the normal components, and the moment about the downstream toe is the sum of
// (y - y_toe) f_x - (x - x_toe,down) f_y over the stopped nodes' forces, with the forces the
// projection gives (computed here by hand): to round-off.
TYPED_TEST(MpmBarrier, UpstreamFaceMomentIsTheSumOverTheNodesForces) {
  using Mem = typename TypeParam::memory_space;
  const double beta = 80.0 * kPi / 180.0, dx = 0.25, dt = 1e-3, shift = 0.25;
  const BarrierShape shape(1.0, 0.0, 4.0, 3.0, 1.0, beta);
  const double lo[2] = {0.0, 0.0}, hi[2] = {6.0, 6.0};
  Grid<Mem> grid(lo, hi, dx);
  grid.mark_all_active();
  const double n[2] = {-std::sin(beta), std::cos(beta)};  // the face's outward normal
  struct Node {
    int i, j;
    double m, vx, vy;
  };
  // Nodes on the face's line (x = toe + shift + y / tan(beta)), rounded to the grid: at y = 1, 2,
  // 3 m the face is at x = 1.426, 1.603, 1.779; the nodes at 1.5, 1.75 and 2.0 lie inside.
  const Node nodes[] = {{6, 4, 3.0, 2.0, 0.0},
                        {7, 8, 2.0, 3.0, -0.5},
                        {8, 12, 1.0, 1.0, 0.2},
                        {6, 5, 5.0, -2.0, 0.0}};  // the last moves away: no contact
  auto m_h = Kokkos::create_mirror_view(grid.mass);
  auto v_h = Kokkos::create_mirror_view(grid.velocity);
  Kokkos::deep_copy(m_h, 0.0);
  Kokkos::deep_copy(v_h, 0.0);
  double want = 0.0;
  const double x_down = 1.0 + 3.0;  // the downstream toe, in the barrier's frame
  for (const Node& q : nodes) {
    const int k = q.i + grid.nx * q.j;
    m_h(k) = q.m;
    v_h(k, 0) = q.vx;
    v_h(k, 1) = q.vy;
    const double vn = q.vx * n[0] + q.vy * n[1];
    if (vn >= 0.0) continue;
    // Smooth face (friction 0): the normal velocity is removed; the force on the barrier is
    // -m dv / dt = m vn n / dt.
    const double fx = q.m * vn * n[0] / dt, fy = q.m * vn * n[1] / dt;
    const double x = q.i * dx - shift, y = q.j * dx;
    want += y * fx - (x - x_down) * fy;
  }
  Kokkos::deep_copy(grid.mass, m_h);
  Kokkos::deep_copy(grid.velocity, v_h);
  Kokkos::deep_copy(grid.velocity_old, v_h);
  const BarrierContactReport r = barrier_contact<TypeParam>(grid, shape, shift, 0.0, 0.0, dt);
  EXPECT_EQ(r.nodes, 3);
  EXPECT_GT(want, 0.0);  // pushed downstream above the base: it tips the barrier
  EXPECT_NEAR(r.upstream_moment, want, 1e-12 * std::fabs(want));
}

// Three face nodes 1, 2 and 3 m above the toe of the barrier of the test above, here standing
// at y = 0.25 m on a grid whose first node row is at y = -0.5 m (rows 7, 11, 15), with face bands
// of 1 m, in two steps of the same node velocities (different time steps): the contact adds each
// node's normal impulse on the barrier, m |v_n|, into its row, step after step; taking the bands
// shares each row's impulse among the bands its tributary height [y - dx/2, y + dx/2] overlaps,
// half below and half above each band edge 1, 2, 3 m above the toe (computed here by hand), and
// leaves the rows at zero. To round-off.
TYPED_TEST(MpmBarrier, FaceRowImpulsesGoToTheBandsTheirHeightOverlaps) {
  using Mem = typename TypeParam::memory_space;
  const double beta = 80.0 * kPi / 180.0, dx = 0.25, shift = 0.25;
  const double dt[2] = {1e-3, 2.5e-3};
  Barrier b;
  b.shape = BarrierShape(1.0, 0.25, 4.0, 3.0, 1.0, beta);
  b.face_band_height = 1.0;
  ASSERT_EQ(b.face_bands(), 4);
  const double lo[2] = {0.0, -0.5}, hi[2] = {6.0, 6.0};
  Grid<Mem> grid(lo, hi, dx);
  grid.mark_all_active();
  const double n[2] = {-std::sin(beta), std::cos(beta)};
  struct Node {
    int i, j;
    double m, vx, vy;
  };
  const Node nodes[] = {{6, 7, 3.0, 2.0, 0.0}, {7, 11, 2.0, 3.0, -0.5}, {8, 15, 1.0, 1.0, 0.2}};
  auto m_h = Kokkos::create_mirror_view(grid.mass);
  auto v_h = Kokkos::create_mirror(grid.velocity);  // its own memory: the contact changes v
  Kokkos::deep_copy(m_h, 0.0);
  Kokkos::deep_copy(v_h, 0.0);
  double p[3];  // each node's normal impulse on the barrier in a step, N s/m
  for (int k = 0; k < 3; ++k) {
    const Node& q = nodes[k];
    m_h(q.i + grid.nx * q.j) = q.m;
    v_h(q.i + grid.nx * q.j, 0) = q.vx;
    v_h(q.i + grid.nx * q.j, 1) = q.vy;
    p[k] = -q.m * (q.vx * n[0] + q.vy * n[1]);
    ASSERT_GT(p[k], 0.0);
  }
  Kokkos::deep_copy(grid.mass, m_h);
  BarrierCoupling<Mem> coupling;
  coupling.attach(b);
  for (int step = 0; step < 2; ++step) {
    Kokkos::deep_copy(grid.velocity, v_h);
    Kokkos::deep_copy(grid.velocity_old, v_h);
    coupling.begin_step(grid);
    ASSERT_EQ(coupling.row_impulse().extent(0), static_cast<std::size_t>(grid.ny));
    const BarrierContactReport r = barrier_contact<TypeParam>(grid, b.shape, shift, 0.0, 0.0,
                                                              dt[step], coupling.row_impulse());
    ASSERT_EQ(r.nodes, 3) << "step " << step;
    coupling.apply(r, dt[step]);
    auto rows = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), coupling.row_impulse());
    for (int j = 0; j < grid.ny; ++j) {
      const double want = (step + 1) * (j == 7 ? p[0] : j == 11 ? p[1] : j == 15 ? p[2] : 0.0);
      EXPECT_NEAR(rows(j), want, 1e-12 * p[0]) << "row " << j << ", step " << step;
    }
  }
  const std::vector<double> bands = coupling.take_band_impulse();
  ASSERT_EQ(bands.size(), 4u);
  const double want[4] = {0.5 * p[0], 0.5 * (p[0] + p[1]), 0.5 * (p[1] + p[2]), 0.5 * p[2]};
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(bands[k], 2.0 * want[k], 1e-12 * p[0]) << k;
  auto rows = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), coupling.row_impulse());
  for (int j = 0; j < grid.ny; ++j) EXPECT_EQ(rows(j), 0.0) << "row " << j << " after the take";
  const std::vector<double> again = coupling.take_band_impulse();
  for (int k = 0; k < 4; ++k) EXPECT_EQ(again[k], 0.0) << k;
}

// Points placed around a trapezoid (H 4, B 2, b 1 m, face 80 deg, toe at x = 1 m), at rest and
// displaced 0.5 m downstream: those whose centre is inside count with their initial volume; those
// upstream of the face, above the crest, beyond the back face or on the base do not; of those
// inside, the ones downstream of the upstream crest corner (x > toe + run) are also the part of
// the overtopped volume that leaked in. Each point has its own V0 (a power of 2), so the sum says
// exactly which counted: exact equality.
TYPED_TEST(MpmBarrier, InteriorVolumeCountsThePointsInsideTheDisplacedBarrier) {
  using Mem = typename TypeParam::memory_space;
  const double beta = 80.0 * kPi / 180.0, run = 4.0 / std::tan(beta);  // the face's run, 0.705 m
  const BarrierShape shape(1.0, 0.0, 4.0, 2.0, 1.0, beta);
  const double shift = 0.5, toe = 1.0 + shift;  // the displaced toe
  // Face x at y = 2: toe + run / 2; back face x at y: toe + 2 - y (2 - 1.705) / 4.
  struct P {
    double x, y;
    bool inside_displaced, inside_at_rest;
  };
  const P pts[] = {
      {toe + 1.0, 2.0, true, true},              // mid-barrier
      {toe + run / 2 + 0.01, 2.0, true, true},   // 1 cm behind the displaced face
      {toe + run / 2 - 0.01, 2.0, false, true},  // 1 cm in front of it
      {toe + run + 0.4, 3.99, true, true},       // 1 cm below the crest
      {toe + run + 0.4, 4.01, false, false},     // 1 cm above it
      {toe + 1.9, 0.05, true, false},            // near the displaced heel, inside
      {toe + 2.01, 0.05, false, false},          // beyond the heel
      {toe + 1.0, 0.0, false, false},            // on the base: the base wall's
      {1.0 + run / 2 + 0.2, 2.0, false, true},   // behind the face at rest, in front once displaced
  };
  const int n = sizeof(pts) / sizeof(pts[0]);
  Particles<Mem> p(n);
  auto pos = Kokkos::create_mirror_view(p.position);
  auto v0 = Kokkos::create_mirror_view(p.volume0);
  double displaced = 0.0, at_rest = 0.0, displaced_past = 0.0, at_rest_past = 0.0;
  for (int q = 0; q < n; ++q) {
    pos(q, 0) = pts[q].x;
    pos(q, 1) = pts[q].y;
    v0(q) = std::ldexp(1.0, -q);
    if (pts[q].inside_displaced) displaced += v0(q);
    if (pts[q].inside_at_rest) at_rest += v0(q);
    if (pts[q].inside_displaced && pts[q].x > toe + run) displaced_past += v0(q);
    if (pts[q].inside_at_rest && pts[q].x > 1.0 + run) at_rest_past += v0(q);
  }
  Kokkos::deep_copy(p.position, pos);
  Kokkos::deep_copy(p.volume0, v0);
  const BarrierInterior moved = barrier_interior<TypeParam>(p, shape, shift);
  const BarrierInterior still = barrier_interior<TypeParam>(p, shape, 0.0);
  EXPECT_EQ(moved.inside, displaced);
  EXPECT_EQ(still.inside, at_rest);
  EXPECT_EQ(moved.past_crest, displaced_past);
  EXPECT_EQ(still.past_crest, at_rest_past);
  // Both cases have points inside on either side of the crest corner (not all or nothing).
  EXPECT_GT(moved.past_crest, 0.0);
  EXPECT_LT(moved.past_crest, moved.inside);
  EXPECT_GT(still.past_crest, 0.0);
  EXPECT_LT(still.past_crest, still.inside);
}

}  // namespace

// Verification 2: free vibration of an elastic bar in its first mode (fixed-free), and the energy
// balance of the elastic scheme over ten periods.
//
// Problem. A bar of length L, fixed at x = 0 and free at x = L, starts stress-free with the
// first-mode velocity v(x, 0) = v0 sin(pi x / (2 L)). With nu = 0 the plane-strain model has
// lambda = 0 and G = E / 2, so sigma_xx = 2 G eps_xx = E eps_xx and sigma_yy = sigma_zz = 0: the
// strip is a 1D bar with wave speed c = sqrt(E / rho) (also the P-wave speed the time step uses,
// sqrt((K + 4G/3) / rho) = sqrt(E / rho) at nu = 0). The exact solution is
//   v(x, t) = v0 sin(pi x / (2 L)) cos(omega t),   omega = pi c / (2 L),
// and its centre-of-mass velocity v_cm(t) = (2 v0 / pi) cos(omega t).
//
// The fixed end is imposed by symmetry, not by a wall: the solver's walls (boundary.hpp) are
// unilateral, they stop a node moving into the wall but let it leave freely, so they cannot hold
// the tension half of the cycle (with a no-slip left wall at x = 0 the bar detaches and v_cm is
// off by ~200 %). The mode above, extended to the free-free bar [-L, L], is antisymmetric about
// x = 0 (v(-x) = -v(x)), so x = 0 stays fixed exactly and the half x > 0 is the fixed-free bar;
// v_cm is the mass-weighted mean velocity of the particles that start at x > 0. The strip is two
// cells high with free top and bottom: with nu = 0 and fields independent of y, the tensor-product
// B-spline transfers keep the motion exactly one-dimensional.
//
// Time centring. The step is USL with the stress updated after G2P from the new grid velocity:
// for a linear elastic body this is the leapfrog (symplectic Euler) scheme, whose particle
// velocity after step n+1 approximates v at t_{n+1} - dt/2 while the stress is at t_{n+1}. Read
// at the nominal time, v_cm carries a first-order phase error omega dt / 2 (1.2 % at 32 cells,
// Courant 0.5); read at t - dt/2 it converges at second order. Both are printed; the accuracy
// assertions use the centred reading, which is the solver's actual accuracy. For the same reason
// kinetic (t - dt/2) + elastic (t) energy oscillates by ~omega dt / 2 within a period; at
// quarter periods (kinetic energy extremal) that offset vanishes to first order, so the drift is
// measured there.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <vector>

#include "kernels/mpm/particle_builder.hpp"
#include "kernels/mpm/solver.hpp"
#include "support/backends.hpp"

namespace {
using namespace lsi::mpm;

constexpr double kPi = 3.14159265358979323846;
constexpr double kL = 1.0, kRho = 1000.0, kE = 1e7;  // c = 100 m/s, period 4 L / c = 0.04 s
constexpr double kV0 = 0.01;                         // peak strain v0 / c = 1e-4: linear regime
const double kC = std::sqrt(kE / kRho);
const double kOmega = kPi * kC / (2.0 * kL);
const double kPeriod = 2.0 * kPi / kOmega;
const double kVcmAmplitude = 2.0 * kV0 / kPi;

struct Sample {
  double t, dt, vcm, energy;
};

struct BarRun {
  std::vector<Sample> samples;  // one per output, the first at t = 0
  Status status = Status::Running;
  long steps = 0;
  double seconds = 0.0;
};

// The free-free bar [-L, L] (cells: cells along L, i.e. the fixed-free half), 2 x 2 points per
// cell, first-mode velocity, no gravity, no walls; outputs every period / outputs_per_period.
template <class Exec>
BarRun run_bar(int cells, double flip_ratio, double courant, double periods,
               int outputs_per_period) {
  using Mem = typename Exec::memory_space;
  const auto start = std::chrono::steady_clock::now();
  Material m;
  m.density = kRho;
  m.young_modulus = kE;
  m.poisson_ratio = 0.0;
  const double dx = kL / cells, h = 2.0 * dx;
  // Three cells of padding: G2P flags particles within one cell of the grid edge.
  const double lo[2] = {-kL - 3.0 * dx, -3.0 * dx}, hi[2] = {kL + 3.0 * dx, h + 3.0 * dx};
  Grid<Mem> grid(lo, hi, dx);
  BodySpec body;
  body.polygon = {{{-kL, 0.0}}, {{kL, 0.0}}, {{kL, h}}, {{-kL, h}}};
  auto particles = build_particles<Mem>({body}, {m}, lo, dx);
  auto x = Kokkos::create_mirror(Kokkos::HostSpace(), particles.position);  // real copies
  auto v = Kokkos::create_mirror(Kokkos::HostSpace(), particles.velocity);
  auto mass = Kokkos::create_mirror(Kokkos::HostSpace(), particles.mass);
  Kokkos::deep_copy(x, particles.position);
  Kokkos::deep_copy(mass, particles.mass);
  std::vector<char> right(particles.count);
  double right_mass = 0.0;
  for (int q = 0; q < particles.count; ++q) {
    v(q, 0) = kV0 * std::sin(kPi * x(q, 0) / (2.0 * kL));
    v(q, 1) = 0.0;
    right[q] = x(q, 0) > 0.0;
    if (right[q]) right_mass += mass(q);
  }
  Kokkos::deep_copy(particles.velocity, v);
  Settings s;
  s.courant = courant;
  s.transfer = flip_ratio > 0.0 ? Transfer::FlipPic : Transfer::Apic;  // 0: APIC
  s.flip_ratio = flip_ratio;
  s.gravity[0] = s.gravity[1] = 0.0;
  Solver<Exec> solver(grid, particles, {m}, Boundaries{}, s);
  BarRun run;
  auto vh = Kokkos::create_mirror(Kokkos::HostSpace(), particles.velocity);
  run.status =
      solver.run(periods * kPeriod, kPeriod / outputs_per_period, [&](const Solver<Exec>& sv) {
        Kokkos::deep_copy(vh, sv.particles().velocity);
        double mv = 0.0;
        for (int q = 0; q < sv.particles().count; ++q)
          if (right[q]) mv += mass(q) * vh(q, 0);
        run.samples.push_back({sv.time(), sv.time_step(), mv / right_mass, sv.energy().total()});
      });
  run.steps = solver.steps();
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

// max |v_cm - exact| / (2 v0 / pi) over the samples, the exact value taken at t - shift * dt.
double vcm_error(const BarRun& run, double shift) {
  double err = 0.0;
  for (const Sample& s : run.samples) {
    const double exact = kVcmAmplitude * std::cos(kOmega * (s.t - shift * s.dt));
    err = std::max(err, std::abs(s.vcm - exact) / kVcmAmplitude);
  }
  return err;
}

template <class Exec>
class MpmElasticBar : public ::testing::Test {};
TYPED_TEST_SUITE(MpmElasticBar, lsi::test::Backends);

TYPED_TEST(MpmElasticBar, FirstModeCentreOfMassVelocityConverges) {
  using Exec = TypeParam;
  const int cells[3] = {8, 16, 32};
  double centred[3], nominal[3];
  for (int k = 0; k < 3; ++k) {
    const BarRun run = run_bar<Exec>(cells[k], 0.0, 0.5, 1.0, 64);  // APIC, one period
    ASSERT_EQ(run.status, Status::Finished) << describe(run.status);
    ASSERT_GE(run.samples.size(), 64u);
    centred[k] = vcm_error(run, 0.5);
    nominal[k] = vcm_error(run, 0.0);
    std::cout << "[ bar ] " << cells[k] << " cells, APIC, Courant 0.5: v_cm error " << centred[k]
              << " (at t - dt/2), " << nominal[k] << " (at t); " << run.steps << " steps, "
              << run.seconds << " s\n";
  }
  const double order_centred[2] = {std::log2(centred[0] / centred[1]),
                                   std::log2(centred[1] / centred[2])};
  const double order_nominal[2] = {std::log2(nominal[0] / nominal[1]),
                                   std::log2(nominal[1] / nominal[2])};
  std::cout << "[ bar ] observed order at t - dt/2: " << order_centred[0] << ", "
            << order_centred[1] << "; at t: " << order_nominal[0] << ", " << order_nominal[1]
            << "\n";
  // 1 % at 32 cells (the acceptance threshold; measured 0.17 %, so a regression of the transfers
  // or of the stress update shows long before it is reached).
  EXPECT_LT(centred[2], 0.01);
  // Quadratic B-splines without cell crossing (peak displacement 6e-5 m << dx) and leapfrog in
  // time are second order; measured 2.0 on both pairs. 1.8 leaves room for the pre-asymptotic
  // 8-cell result and is well above the required first order.
  EXPECT_GE(order_centred[0], 1.8);
  EXPECT_GE(order_centred[1], 1.8);
  // Read at the nominal time the error is dominated by the half-step offset omega dt / 2, which
  // is proportional to dx at fixed Courant: first order (measured 1.26 and 1.15, tending to 1
  // from above as the second-order part fades). 0.9 guards against anything worse than first.
  EXPECT_GE(order_nominal[0], 0.9);
  EXPECT_GE(order_nominal[1], 0.9);
}

// Energy drift over ten periods, APIC (the default and the scheme the tests use) against the
// FLIP/PIC blend 0.99: APIC loses 0.2 % over ten periods, the blend about 1.7 % (its 1 % PIC part
// filters the velocity every step), so APIC is the transfer that meets the 1 % budget.
TYPED_TEST(MpmElasticBar, EnergyIsConservedOverTenPeriods) {
  using Exec = TypeParam;
  const int cells = 32, per_period = 16;
  double drift[2] = {0.0, 0.0}, oscillation[2] = {0.0, 0.0}, final_drift[2] = {0.0, 0.0};
  const double flip[2] = {0.0, 0.99};
  for (int k = 0; k < 2; ++k) {
    const BarRun run = run_bar<Exec>(cells, flip[k], 0.5, 10.0, per_period);
    ASSERT_EQ(run.status, Status::Finished) << describe(run.status);
    ASSERT_EQ(run.samples.size(), 10u * per_period + 1u);  // one sample per output interval
    const double e0 = run.samples.front().energy;
    for (size_t i = 0; i < run.samples.size(); ++i) {
      const double rel = (run.samples[i].energy - e0) / e0;
      oscillation[k] = std::max(oscillation[k], std::abs(rel));
      if (i % (per_period / 4) == 0) drift[k] = std::max(drift[k], std::abs(rel));  // t = k T / 4
    }
    final_drift[k] = (run.samples.back().energy - e0) / e0;
    std::cout << "[ bar ] " << cells << " cells, flip_ratio " << flip[k]
              << ", Courant 0.5, 10 periods: energy drift " << drift[k] << " (max at quarter "
              << "periods), " << final_drift[k] << " (at 10 T), " << oscillation[k]
              << " (max over all samples); " << run.steps << " steps, " << run.seconds << " s\n";
  }
  // The acceptance threshold, 1 %, on the APIC drift at quarter periods (measured 0.23 %).
  EXPECT_LT(drift[0], 0.01);
  EXPECT_LE(final_drift[0], 0.0);  // the transfers dissipate; they must never create energy
  // Within a period the total also carries the leapfrog offset ~ omega dt / 2 = 1.2 % (see the
  // header); it is bounded, not a drift. 2 % bounds it with room for the 0.2 % drift on top.
  EXPECT_LT(oscillation[0], 0.02);
  // The justification of the choice: the blend dissipates more than APIC (measured 1.7 % vs
  // 0.2 %), a margin of almost an order of magnitude, so the comparison is not marginal.
  EXPECT_GT(std::abs(final_drift[1]), 2.0 * std::abs(final_drift[0]));
}
}  // namespace

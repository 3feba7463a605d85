// Verification (against experiments): collapse of a two-dimensional granular column.
//
// A column L0 wide and H0 = a L0 high, held by a smooth wall on its left (the symmetry plane of a
// column released on both sides; the quasi-2D experiments use a box with a gate), is released on
// a rough horizontal base and spreads until it stops. The law: Lube, Huppert, Sparks & Freundt,
// "Collapses of two-dimensional granular columns", Phys. Rev. E 72, 041301 (2005), as quoted by
// Lagree, Staron & Popinet, J. Fluid Mech. 686:378 (2011), eqs. 3.1-3.2:
//   (L_f - L0) / L0 = 1.2 a          for a <~ 1.8
//   (L_f - L0) / L0 = 1.9 a^(2/3)    for a >~ 2.8
// and for the final height H_f / L0 = a for small a: a short column collapses by the avalanche of
// its flank along a Coulomb failure plane and its top stays where it was (H_f = H0). The height
// of tall columns is quoted with different exponents (a^0.4 attributed to Lube et al., not
// confirmed from the paper; a^(1/3) for Lajeunesse, Monnier & Homsy, Phys. Fluids 17, 103302
// (2005), as quoted by K. Kumar, PhD thesis, Cambridge 2015, ch. 2), so it is printed, not
// asserted. Scatter between experiments: Lajeunesse et al. fit 1.8 a and 2.3 a^(2/3) in a similar
// channel, a run-out 50 % above Lube's at small a and 21 % above at a = 3 (the secondary sources
// disagree on which fit belongs to which experiment: docs/verification.md); Balmforth & Kerswell,
// J. Fluid Mech. 538:399 (2005, abstract), find (L_f - L0)/L0 ~ a^(0.65 +- 0.05) in narrow and
// a^(0.9 +- 0.1) in wide channels with a prefactor that depends on the material.
//
// Model: Mohr-Coulomb, phi = 30 deg, psi = 0, c = 0, tension cut-off 0, nu = 0.3, rho = 1800,
// E = rho g H0 / 0.005 (0.5 % elastic strain under the column's weight, stiff enough not to matter,
// soft enough for a cheap time step), base friction tan(phi), 2 x 2 points per cell, Courant 0.5,
// APIC. L_f and H_f: the farthest / highest point plus half a point spacing; L_body: the end of
// the deposit where it is at least L0/16 thick (highest point per grid column). At rest: kinetic
// energy below 1e-3 of the potential energy released, checked every T/4, T = sqrt(H0 / g).
//
// a = 0.5 (32 cells across L0) is asserted: run-out within 20 % of Lube et al., H_f = H0 within
// 3 %. That is agreement at this resolution: the farthest point moves out as the grid is refined
// (+6.6 % at 32, +17 % at 64, +25 % at 96 cells per L0) while the numerical dissipation falls,
// and converges at +34 % from 256 cells (run on a GPU). Converged, the farthest point lies 34 to
// 51 % beyond Lube at a = 0.5, 1 and 3, at the end of a film whose mass shrinks with the cell;
// the front of the mass (1 % of it beyond) lies within 20 % at a = 0.5 and 1 at every
// resolution tried (16 to 512 cells), +4 and +14 % on the finest. Which of the two the law's
// run-out is, is left to the owner (docs/verification.md, "The finest grids, on a GPU").
// a = 3 (16 cells across L0) is run and reported against the law but its run-out is NOT
// asserted against it. The farthest point over-predicts it, +28 % at 16, +38 % at 24, +44 % at 32,
// +49 % at 64 cells per L0, where it has converged (+48 % at 48); it belongs to a thin tail, about
// 1.2 % of the column (mostly points of its outer face), that coarse grids hold back. The body
// of the deposit converges: its end where it is L0/16 thick lies at 5.81, 5.75, 5.63 L0 (+17, +16,
// +14 % over Lube, within 3 % of Lajeunesse et al.), but that number depends on the thickness
// chosen (L0/25: +24 to +32 %; L0/12.5: +7 to +10 %; 1 % of the mass beyond 6.1-6.2 L0, +23 to
// +26 %, from 24 to 64 cells, +18 % at 192) and the experiments' front criterion is not known
// to us, so it is printed and regression-checked, not claimed as a verification. The same
// over-prediction of tall-column run-outs by MPM with Mohr-Coulomb, against DEM, is reported by
// Kumar (PhD thesis, Cambridge 2015, ch. 4) for a > ~1.7. The a = 3 case asserts what the solver
// must still do there: finish, keep the energy balance, and stay within regression bands
// (docs/verification.md, which also lists the sensitivity to friction, base friction, transfer
// scheme, stiffness and time step).
//
// Both cases check the energy balance, Solver::energy_residual, in [-0.2, +0.05]: a negative value
// is numerical dissipation, kinetic energy lost by the discretisation (grid transfers, impact on
// the base) that neither the plastic nor the wall work accounts for. It shrinks as the grid is
// refined (a = 0.5: -10.0, -6.9, -5.3, -3.6 % at 16, 24, 32, 48 cells per L0; a = 3: -2.3, -1.7,
// -1.4 % at 16, 24, 32), as numerical dissipation should; up to 20 % is tolerated. A positive
// residual is energy created by the scheme: more than 5 % would mean an instability or an
// accounting error.
//
// Backends: a = 0.5 on every backend, a = 3 on Serial only (on the default host space if Serial
// is not compiled in): same kernels, and this small problem (3 072 points) gains nothing from
// threads. Measured on the 2 shared cores of the development machine (ctest, OMP_NUM_THREADS=2,
// OMP_WAIT_POLICY=passive as registered in CMakeLists.txt): Serial a = 0.5 1.2 s, Serial a = 3
// 5-6 s, OpenMP a = 0.5 1.3-2.2 s; OpenMP a = 3 would add 3-5 s idle, 8 s with a competing process,
// 210 s with a whole `ctest -j2` running beside it (every step is ~13 fork-join regions).
#include <gtest/gtest.h>

#include <cmath>
#include <type_traits>

#include "support/backends.hpp"
#include "support/column_collapse.hpp"

namespace {
using namespace lsi::test;

void check_common(const Collapse& R) {
  ASSERT_EQ(R.status, Status::Finished) << describe(R.status);
  EXPECT_TRUE(R.at_rest) << "still moving at t = " << R.t_over_T << " T";
  // See the header: numerical dissipation up to 20 %, no more than 5 % energy created.
  EXPECT_GT(R.residual, -0.2);
  EXPECT_LT(R.residual, 0.05);
  // The deposit must not have reached the right wall (it would cut the run-out short).
  EXPECT_GT(R.right_room, 2.0);
}

template <class Exec>
const char* backend_name() {
#ifdef KOKKOS_ENABLE_SERIAL
  if constexpr (std::is_same_v<Exec, Kokkos::Serial>) return "Serial";
#endif
  return Exec::name();
}

template <class Exec>
class MpmColumnCollapse : public ::testing::Test {};
TYPED_TEST_SUITE(MpmColumnCollapse, lsi::test::Backends);

// a = 0.5: flank avalanche, truncated-cone deposit.
TYPED_TEST(MpmColumnCollapse, ShortColumnRunOutAndHeight) {
  const Collapse R = collapse<TypeParam>({.a = 0.5, .cells_per_L0 = 32});
  print(R, backend_name<TypeParam>());
  check_common(R);
  // Run-out within 20 % of Lube et al. (2005); measured +6.6 %. The experiments scatter more
  // than that (Lajeunesse et al.: +50 %), so 20 % is a statement about this model, not the data.
  EXPECT_LT(std::fabs(R.Lf / lube_runout(R.a) - 1), 0.2);
  // The top of the column is not reached by the failure plane: H_f = H0, less the elastic
  // shortening (0.25 % on average) and the half-spacing of the measurement; 3 %.
  EXPECT_LT(std::fabs(R.Hf / R.a - 1), 0.03);
}

// a = 3: free fall of the upper column, conical deposit. One backend only (see the header).
#ifdef KOKKOS_ENABLE_SERIAL
using TallColumnSpace = Kokkos::Serial;
#else
using TallColumnSpace = Kokkos::DefaultHostExecutionSpace;
#endif
TYPED_TEST(MpmColumnCollapse, TallColumnFinishesAndReportsRunOut) {
  using Exec = TypeParam;
  if (!std::is_same_v<Exec, TallColumnSpace>)
    GTEST_SKIP() << "a = 3 runs on " << backend_name<TallColumnSpace>() << " only (run time)";
  const Collapse R = collapse<Exec>({.a = 3.0, .cells_per_L0 = 16});
  print(R, backend_name<Exec>());
  check_common(R);
  // Not a verification against Lube et al. (see the header): the rate-independent continuum
  // over-predicts the run-out of tall columns. Regression band at 16 cells per L0, measured
  // L_f/L0 = 6.34, +28 % over Lube and +10 % over Lajeunesse et al.: longer than Lube's law, and
  // less than 1.5 times it.
  const double ratio = R.Lf / lube_runout(R.a);
  EXPECT_GT(ratio, 1.0);
  EXPECT_LT(ratio, 1.5);
  // The deposit body (at least L0/16 thick) converges with the grid (5.81, 5.75, 5.63 L0 at 16,
  // 24, 32 cells): measured 5.81 L0, +17 % over Lube. Regression band: between Lube's law and
  // 1.3 times it (a kernel change that moves it outside should be looked at, not the band).
  EXPECT_GT(R.Lbody / lube_runout(R.a), 1.0);
  EXPECT_LT(R.Lbody / lube_runout(R.a), 1.3);
  // The tail beyond the body is thin: the body reaches at least 85 % of the farthest point.
  EXPECT_GT(R.Lbody / R.Lf, 0.85);
  // Far below the initial height: the whole column took part in the collapse.
  EXPECT_LT(R.Hf, 0.6 * R.a);
}
}  // namespace

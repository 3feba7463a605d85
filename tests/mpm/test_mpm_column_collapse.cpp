// Verification (against experiments): collapse of a two-dimensional granular column.
//
// A column L0 wide and H0 = a L0 high, held by a smooth wall on its left (the symmetry plane of a
// column released on both sides), is released on a rough horizontal base and spreads until it
// stops. The law: Lube, Huppert, Sparks & Freundt, "Collapses of two-dimensional granular
// columns", Phys. Rev. E 72, 041301 (2005), as quoted by Lagree, Staron & Popinet, J. Fluid Mech.
// 686:378 (2011), eqs. 3.1-3.2:
//   (L_f - L0) / L0 = 1.2 a          for a <~ 1.8
//   (L_f - L0) / L0 = 1.9 a^(2/3)    for a >~ 2.8
// and H_f = H0 for small a (the flank avalanches along a Coulomb failure plane, the top stays).
//
// The run-out of the continuum is measured at the front of the deposit's mass: x99, the position
// with 1 % of the material points beyond it. A rate-independent continuum has no grain size, so
// a film of any thickness keeps flowing beyond the grains' front (where a granular layer thinner
// than a few grains stops); the film's mass shrinks with the cell while its farthest point does
// not, so the farthest point is not the experiments' run-out (docs/vv/verification.md).
//
// Model: Mohr-Coulomb, phi = 30 deg, psi = 0, c = 0, tension cut-off 0, nu = 0.3, rho = 1800,
// E = rho g H0 / 0.005 (0.5 % elastic strain under the column's weight), base friction tan(phi),
// 2 x 2 points per cell, Courant 0.5, APIC; at rest when the kinetic energy is below 1e-3 of the
// potential energy released (tests/support/column_collapse.hpp).
//
// Asserted: a = 0.5 and a = 1 (32 cells across L0), x99 within 20 % of Lube et al.; H_f = H0 at
// a = 0.5. a = 3 (16 cells) is run and checked for what the solver must do (finish, balance its
// energy, stay in a regression band); its mass front lies further out than the law at every
// resolution tried, decreasing with the cell (docs/notes/verification.md, "The finest grids"), so it is
// not asserted against the law.
//
// Every case checks the energy balance, Solver::energy_residual, in [-0.2, +0.05]: a negative
// value is numerical dissipation (grid transfers, the impact on the base) that neither the plastic
// nor the wall work accounts for, and shrinks as the grid is refined; a positive one is energy
// created by the scheme, and more than 5 % would mean an instability or an accounting error.
//
// Backends: a = 0.5 and a = 1 on every backend, a = 3 on Serial only (on the default host space
// if Serial is not compiled in): the same kernels, and this small problem gains nothing from
// threads.
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
  // The mass front within 20 % of Lube et al. (2005). The experiments scatter more than that
  // (Lajeunesse et al. fit a run-out 50 % above Lube's at small a), so 20 % is a statement about
  // this model against one law, not about the data.
  EXPECT_LT(std::fabs(R.x99 / lube_runout(R.a) - 1), 0.2);
  // The top of the column is not reached by the failure plane: H_f = H0, less the elastic
  // shortening (0.25 % on average) and the half-spacing of the measurement; 3 %.
  EXPECT_LT(std::fabs(R.Hf / R.a - 1), 0.03);
}

// a = 1: the failure plane reaches the top; still the linear regime of the law.
TYPED_TEST(MpmColumnCollapse, SquareColumnRunOut) {
  const Collapse R = collapse<TypeParam>({.a = 1.0, .cells_per_L0 = 32});
  print(R, backend_name<TypeParam>());
  check_common(R);
  // As for a = 0.5: the mass front within 20 % of Lube et al.
  EXPECT_LT(std::fabs(R.x99 / lube_runout(R.a) - 1), 0.2);
  // The whole column took part: lower than it was, by more than the elastic shortening.
  EXPECT_LT(R.Hf, 0.97 * R.a);
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
  // Not a verification against Lube et al. (see the header). Regression bands at 16 cells per
  // L0: the farthest point beyond Lube's law and within 1.5 times it; the mass front beyond the
  // law and within 1.3 times it; the body (at least L0/16 thick) reaching 85 % of the farthest
  // point (the tail beyond it is thin). A kernel change that moves a value outside its band
  // should be looked at, not the band.
  const double lube = lube_runout(R.a);
  EXPECT_GT(R.Lf / lube, 1.0);
  EXPECT_LT(R.Lf / lube, 1.5);
  EXPECT_GT(R.x99 / lube, 1.0);
  EXPECT_LT(R.x99 / lube, 1.3);
  EXPECT_GT(R.Lbody / lube, 1.0);
  EXPECT_LT(R.Lbody / lube, 1.3);
  EXPECT_GT(R.Lbody / R.Lf, 0.85);
  // Far below the initial height: the whole column took part in the collapse.
  EXPECT_LT(R.Hf, 0.6 * R.a);
}
}  // namespace

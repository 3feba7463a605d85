// Verification of the saturated impact against the pressure-impulse theory (Cooker & Peregrine
// 1995): a liquefied saturated block stopped by a wall (the problem, the theory and the MPM set-up
// are in pressure_impulse.hpp). Held walls (the linear problem): the time means over 10-60
// acoustic times must be the theory's away from the singular corner, and the corner must move
// faster than the flow and faster at a finer grid, as the singularity says. This is what shows
// that the fast sheet along the barrier face of the saturated impacts (docs/theory/two_phase.md, "The
// face jet") is the flip-through jet of a liquefied flow, not an artefact.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "pressure_impulse.hpp"
#include "support/backends.hpp"

namespace {
using namespace lsi::test::pressure_impulse;

template <class T>
class MpmPressureImpulse : public ::testing::Test {};
TYPED_TEST_SUITE(MpmPressureImpulse, lsi::test::Backends);

TYPED_TEST(MpmPressureImpulse, TimeMeansAreTheIncompressibleImpulse) {
  const Block b;
  const double I = theory_wall_impulse(b), Py = theory_vertical_momentum(b);
  const double scale = b.impulse_scale(), U = b.speed;
  Setup coarse, fine, point;
  coarse.cells = 8;
  fine.cells = 16;
  point.cells = 16;
  point.cell_pore_pressure = false;
  const Measured m8 = impact<TypeParam>(b, coarse), m16 = impact<TypeParam>(b, fine);
  const Measured p16 = impact<TypeParam>(b, point);
  ASSERT_TRUE(m8.finished && m16.finished && p16.finished);
  for (const auto& [name, m] :
       {std::pair{"8 cells", &m8}, {"16 cells", &m16}, {"16 cells, point pressure", &p16}})
    std::printf(
        "[measured] %s: %ld steps, wall impulse %.4f rho_m U H^2 (theory %.4f), vertical "
        "momentum %.4f (theory %.4f), corner cell %.3f U, corner point %.3f U\n",
        name, m->steps, m->wall_impulse / scale, I / scale, m->vertical_momentum / scale,
        Py / scale, m->wall_velocity.back() / U, m->corner_point_speed / U);
  // 1. The wall impulse converges to the theory's, about first order in the cell (measured
  //    +13.7 % at 8 cells, +6.7 % at 16, +4.5 % at 32: the pressure of the wall's cell is spread
  //    over the B-spline's support). 10 % at 16 cells, and at least a 0.7 error ratio per halving.
  EXPECT_NEAR(m16.wall_impulse, I, 0.10 * I);
  EXPECT_LT(std::fabs(m16.wall_impulse - I), 0.7 * std::fabs(m8.wall_impulse - I));
  // 2. The vertical momentum (the base's impulse, over the whole block): measured +2.3 % at 16.
  EXPECT_NEAR(m16.vertical_momentum, Py, 0.05 * Py);
  // 3. The vertical velocity at the wall, cell by cell, in the lower 60 % of the height (the
  //    corner's singularity is smoothed over about three cells above): measured within 0.057 U at
  //    16 cells. 0.08 U, a fifth of the mean there; the time mean of the ringing is part of it.
  const double dx = b.height / fine.cells;
  for (int j = 0; (j + 1) * dx <= 0.6 * b.height; ++j)
    EXPECT_NEAR(m16.wall_velocity[j], theory_vertical_velocity(b, 0, dx, j * dx, (j + 1) * dx),
                0.08 * U)
        << "cell " << j;
  // 4. The corner: faster than the flow, and faster on the finer grid (theory: +0.44 U per halving
  //    of the cell average, no limit). Measured corner cell 1.11 U at 8 cells, 1.32 U at 16: with
  //    held walls the MPM's corner is below the theory's cell average (1.71, 2.15 U) but grows
  //    without converging; 0.1 U is half the measured growth.
  EXPECT_GT(m8.wall_velocity.back(), U);
  EXPECT_GT(m16.wall_velocity.back(), m8.wall_velocity.back() + 0.1 * U);
  // 5. Pore pressure per point locks next to the wall (the nearly incompressible mixture and
  //    the B-splines): its wall column barely rises and the wall impulse is too large (measured
  //    +31 % at 16 cells against +6.7 % with the cell-mean pressure; docs/notes/two_phase.md).
  EXPECT_GT(std::fabs(p16.wall_impulse - I), 2 * std::fabs(m16.wall_impulse - I));
}

// The contact of the impact scenes: unilateral wall and base, APIC, pore pressure per point. The
// flat block leaves the wall and the base at the first rarefaction (a compressible rebound, not
// the incompressible theory: wall impulse 0.81 rho_m U H^2 instead of 0.54), but the corner's
// velocity is set in the compression, before it leaves, and is then kept: it must be the theory's
// corner-cell average, at each resolution.
TYPED_TEST(MpmPressureImpulse, FreeCornerMovesAtTheTheorysCornerSpeed) {
  const Block b;
  const double U = b.speed;
  for (int cells : {8, 16}) {
    Setup st;
    st.cells = cells;
    st.held = false;
    st.transfer = Transfer::Apic;
    st.cell_pore_pressure = false;
    const Measured m = impact<TypeParam>(b, st);
    ASSERT_TRUE(m.finished);
    const double dx = b.height / cells;
    const double theory = theory_vertical_velocity(b, 0, dx, b.height - dx, b.height);
    std::printf(
        "[measured] unilateral, %d cells: wall impulse %.4f rho_m U H^2, largest wall force "
        "in the window %.3g rho_m c U H, corner cell %.3f U (theory %.3f U)\n",
        cells, m.wall_impulse / b.impulse_scale(),
        m.largest_wall_force / (b.mixture_density() * b.wave_speed() * U * b.height),
        m.wall_velocity.back() / U, theory / U);
    // The block has left the wall before the window: its force there is under 5 % of the
    // water-hammer force rho_m c U H (measured 1.3 % and 0.3 %).
    EXPECT_LT(m.largest_wall_force, 0.05 * b.mixture_density() * b.wave_speed() * U * b.height);
    // Measured -4.1 % (8 cells) and -3.1 % (16): 10 %, the theory's cell average being an
    // estimate of what a B-spline grid resolves of a singularity.
    EXPECT_NEAR(m.wall_velocity.back(), theory, 0.10 * theory) << cells << " cells";
  }
}

}  // namespace

// The transfer-dissipation account (kernels/mpm/transfer_dissipation.hpp) where its answer is
// known: a uniform velocity field goes to the grid and back without loss, so a free-falling
// block loses nothing in the transfers, with APIC and with PIC; and it costs nothing when off.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/mpm/solver.hpp"
#include "support/backends.hpp"
#include "support/falling_block.hpp"

namespace {
using namespace lsi::mpm;

template <class Exec>
class MpmTransferDissipation : public ::testing::Test {};
TYPED_TEST_SUITE(MpmTransferDissipation, lsi::test::Backends);

template <class Exec>
Solver<Exec> falling_block(Transfer transfer, bool track) {
  Settings s;
  s.transfer = transfer;
  s.flip_ratio = 0.0;  // plain PIC when FlipPic
  s.track_transfer_dissipation = track;
  return lsi::test::FallingBlock<Exec>().solver(s);
}

TYPED_TEST(MpmTransferDissipation, UniformMotionLosesNothingInTheTransfers) {
  using Exec = TypeParam;
  for (Transfer t : {Transfer::Apic, Transfer::FlipPic}) {
    Solver<Exec> solver = falling_block<Exec>(t, true);
    ASSERT_EQ(solver.run(1.0, 1.0), Status::Finished);
    const EnergyReport e = solver.energy();
    // Every point moves at g t: the B-splines' partition of unity carries the uniform field to
    // the grid and back exactly, so only round-off is left: of 1e3 steps of sums of ~1e3 terms,
    // ~1e-13 of the kinetic energy; 1e-10 bounds it.
    EXPECT_GT(e.kinetic, 1e4);
    EXPECT_LT(std::fabs(solver.transfer_dissipation()), 1e-10 * e.kinetic)
        << (t == Transfer::Apic ? "APIC" : "PIC");
    // With nothing lost, the residual is the unexplained one (both ~round-off).
    EXPECT_NEAR(solver.energy_residual_unexplained(e), solver.energy_residual(e), 1e-10);
  }
}

TYPED_TEST(MpmTransferDissipation, OffByDefaultAndThenZero) {
  using Exec = TypeParam;
  Solver<Exec> solver = falling_block<Exec>(Transfer::Apic, Settings{}.track_transfer_dissipation);
  EXPECT_FALSE(solver.settings().track_transfer_dissipation);
  ASSERT_EQ(solver.run(0.1, 0.1), Status::Finished);
  EXPECT_EQ(solver.transfer_dissipation(), 0.0);
}

}  // namespace

// The scalar outputs of a simulated impact from its force history (model/impact_summary.hpp):
// the peak averaged over a window, the impulse, the impact duration. The force samples are means
// over the interval ending at each output time, so the force is piecewise constant and every
// answer here is exact up to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "model/impact_summary.hpp"
#include "support/tolerances.hpp"

namespace {
using lsi::impact_duration;
using lsi::impulse_until;
using lsi::windowed_peak;
using lsi::test::kRoundOffAbs;

// The brute-force scan against windowed_peak: the scan's start is a sum of 0.0005 s steps, and
// each mean is a difference of two impulses divided by a short window (cancellation).
constexpr double kBruteForceScanRel = 1e-9;

// Outputs every 0.1 s; force[i] is the mean over (t[i-1], t[i]] (force[0] belongs to no interval).
const std::vector<double> kTime = {0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
const std::vector<double> kForce = {0, 0, 10, 20, 100, 20, 10, 0, 0, 0, 0};

TEST(ImpactSummary, WindowedPeakOfAPiecewiseConstantForce) {
  // One interval: the largest sample, centred on its interval (0.3, 0.4].
  const auto one = windowed_peak(kTime, kForce, 0.1);
  EXPECT_NEAR(one.force, 100.0, kRoundOffAbs);
  EXPECT_NEAR(one.time, 0.35, kRoundOffAbs);
  // Three intervals: (20 + 100 + 20) / 3 centred on the peak; any shift of the window loses.
  const auto three = windowed_peak(kTime, kForce, 0.3);
  EXPECT_NEAR(three.force, 140.0 / 3.0, kRoundOffAbs);
  EXPECT_NEAR(three.time, 0.35, kRoundOffAbs);
  // A window of 1.5 intervals must hang over the peak's neighbours by half an interval on one
  // side: (100 x 0.1 + 20 x 0.05) / 0.15, a window that starts between two output times.
  EXPECT_NEAR(windowed_peak(kTime, kForce, 0.15).force, 11.0 / 0.15, kRoundOffAbs);
  // At least the whole history: the mean over it.
  EXPECT_NEAR(windowed_peak(kTime, kForce, 5.0).force, 16.0, kRoundOffAbs);
  // Shorter than every interval: the largest sample.
  EXPECT_NEAR(windowed_peak(kTime, kForce, 0.01).force, 100.0, kRoundOffAbs);
}

// Uneven intervals and random forces against a brute-force scan of the window's start on a fine
// grid (the maximum lies where the window's start or end is an output time, which the fine grid
// contains): the two agree to round-off.
TEST(ImpactSummary, WindowedPeakAgreesWithABruteForceScan) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> step(0.005, 0.03), value(-50.0, 400.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> t = {0.0}, f = {0.0};
    for (int i = 0; i < 60; ++i) {
      t.push_back(t.back() + std::round(step(rng) * 1000) / 1000);  // on a 1 ms lattice
      f.push_back(value(rng));
    }
    for (double w : {0.017, 0.05, 0.123}) {
      const auto got = windowed_peak(t, f, w);
      double best = -1e300;
      for (double s = 0.0; s + w <= t.back() + kRoundOffAbs; s += 0.0005)  // the lattice's halves
        best = std::max(best, (impulse_until(t, f, s + w) - impulse_until(t, f, s)) / w);
      EXPECT_NEAR(got.force, best, kBruteForceScanRel * std::fabs(best))
          << "trial " << trial << " w " << w;
    }
  }
}

TEST(ImpactSummary, ImpulseIsTheIntegralOfThePiecewiseConstantForce) {
  EXPECT_NEAR(impulse_until(kTime, kForce, 1.0), 16.0, kRoundOffAbs);  // 160 N/m x 0.1 s
  EXPECT_NEAR(impulse_until(kTime, kForce, 0.4), 13.0, kRoundOffAbs);
  EXPECT_NEAR(impulse_until(kTime, kForce, 0.35), 8.0,
              kRoundOffAbs);  // half of the 100 N/m interval
  EXPECT_EQ(impulse_until(kTime, kForce, 0.0), 0.0);
  EXPECT_NEAR(impulse_until(kTime, kForce, 7.0), 16.0, kRoundOffAbs);  // beyond the end: all of it
}

TEST(ImpactSummary, ImpactDurationEndsWhereTheForceSettles) {
  // Settles at 30 N/m (the last 5 %: the last sample of 21); the peak is 200; the last sample
  // more than 20 N/m from 30 is the 55 at t = 0.9.
  std::vector<double> t, f;
  for (int i = 0; i <= 20; ++i) t.push_back(0.1 * i);
  f = {0, 50, 200, 150, 120, 90, 80, 70, 60, 55, 49, 45, 40, 35, 32, 31, 30, 30, 30, 30, 30};
  const auto d = impact_duration(t, f);
  EXPECT_NEAR(d.final_force, 30.0, kRoundOffAbs);
  EXPECT_NEAR(d.duration, 0.9, kRoundOffAbs);
}

}  // namespace

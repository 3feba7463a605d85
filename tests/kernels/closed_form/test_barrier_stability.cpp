// Barrier geometry and static safety (kernels/closed_form/barrier_geometry.hpp,
// barrier_stability.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/closed_form/barrier_stability.hpp"
#include "support/tolerances.hpp"

namespace {
using namespace lsi;
using test::kRoundOffAbs;
using test::kUnitArithmeticAbs;
constexpr double deg = 3.14159265358979323846 / 180.0;
// The overturning lever (metres, a few units) from the face's sine and cosine, absolute.
constexpr double kLeverAbs = 1e-13;

TEST(BarrierGeometry, TrapezoidAreaAndCentroid) {
  // Rectangle 2 m x 4 m: centroid at B/2.
  const BarrierGeometry rect{4.0, 2.0, 2.0, 90 * deg};
  EXPECT_NEAR(rect.area(), 8.0, kUnitArithmeticAbs);
  EXPECT_NEAR(rect.centroid_x(), 1.0, kUnitArithmeticAbs);
  EXPECT_NEAR(rect.downstream_run_out(), 0.0, kUnitArithmeticAbs);
  // Right trapezoid with a vertical downstream face: B = 3, b = 1, H = 2, face run-out 2 m
  // (beta = atan(2/2) = 45 deg). Centroid from the decomposition rectangle (1 x 2, centroid 2.5)
  // + triangle (area 2, centroid at 2*2/3 = 4/3): x_c = (2*2.5 + 2*4/3) / 4 = 23/12.
  const BarrierGeometry trap{2.0, 3.0, 1.0, 45 * deg};
  EXPECT_NEAR(trap.face_run_out(), 2.0, kUnitArithmeticAbs);
  EXPECT_NEAR(trap.downstream_run_out(), 0.0, kUnitArithmeticAbs);
  EXPECT_NEAR(trap.area(), 4.0, kUnitArithmeticAbs);
  EXPECT_NEAR(trap.centroid_x(), 23.0 / 12.0, kUnitArithmeticAbs);
  // Reference barrier B1 (H 4, B 2, b 1, beta 80): valid geometry, area 6 m^2.
  const BarrierGeometry b1{4.0, 2.0, 1.0, 80 * deg};
  EXPECT_NEAR(b1.area(), 6.0, kUnitArithmeticAbs);
  EXPECT_GT(b1.downstream_run_out(), 0.0);
}

TEST(BarrierStability, RectangularBlockUnderAHorizontalForce) {
  // Vertical face, no face shear: FS_o = W (B/2) / (N z), FS_s = tan(delta_b) W / N.
  const BarrierGeometry g{4.0, 2.0, 2.0, 90 * deg};
  const FaceResolution face = resolve_face_force(90 * deg);
  const double m2 = 19200, W = m2 * 9.81, mu_b = 0.5, z = 1.5;
  const double t[3] = {0.0, 0.5, 1.0}, N[3] = {0.0, 2e5, 1e5};
  const StabilityCheck s = barrier_stability(t, N, 3, g, face, m2, mu_b, z);
  EXPECT_NEAR(s.min_overturning_safety, W * 1.0 / (2e5 * z), kRoundOffAbs);
  EXPECT_NEAR(s.min_sliding_safety, mu_b * W / 2e5, kRoundOffAbs);
  EXPECT_EQ(s.time_min_overturning, 0.5);
  EXPECT_EQ(s.time_min_sliding, 0.5);
}

TEST(BarrierStability, InclinedFaceLeverArmAndDownwardLoad) {
  // Without face shear the lever of the normal force about the downstream toe is
  // z / sin(beta) - B cos(beta) (docs/theory/models.md, "Overturning").
  const BarrierGeometry g{5.0, 6.0, 2.0, 60 * deg};
  const FaceResolution face = resolve_face_force(60 * deg);
  const double z = 1.5;
  EXPECT_NEAR(overturning_lever(g, face, z), z / std::sin(60 * deg) - 6.0 * std::cos(60 * deg),
              kLeverAbs);
  // Sliding safety counts the downward component of N in the friction.
  const double t[2] = {0.0, 1.0}, N[2] = {0.0, 3e5};
  const double m2 = 40000, mu_b = 0.5;
  const StabilityCheck s = barrier_stability(t, N, 2, g, face, m2, mu_b, z);
  EXPECT_NEAR(s.min_sliding_safety,
              mu_b * (m2 * 9.81 + 3e5 * std::cos(60 * deg)) / (3e5 * std::sin(60 * deg)),
              kRoundOffAbs);
}
}  // namespace

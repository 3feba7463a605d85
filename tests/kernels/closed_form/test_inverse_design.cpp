// Inverse design: minimum barrier mass for a tolerable displacement
// (kernels/closed_form/inverse_design.hpp), on a known function and on the two-body model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "kernels/closed_form/barrier_sliding.hpp"
#include "kernels/closed_form/face_resolution.hpp"
#include "kernels/closed_form/inverse_design.hpp"
#include "kernels/closed_form/two_body_model.hpp"

namespace {
using namespace lsi;
constexpr double deg = 3.14159265358979323846 / 180.0;

double two_body_displacement(double m2, double mu_b) {
  const auto imp = two_body_impact(97200, 12.5, 18, m2, TwoBodyCoefficients{0.41, 0.25});
  const SlidingBlock b{m2, mu_b, resolve_face_force(80 * deg).sliding_drive(mu_b)};
  return barrier_motion(imp.pulse, b).final_displacement;
}

TEST(InverseDesign, RecoversTheMassOfAKnownDecreasingFunction) {
  // d(m) = 1e4 / m: d <= 0.5 for m >= 2e4 exactly.
  const auto r = minimum_barrier_mass([](double m) { return 1e4 / m; }, 0.5);
  EXPECT_EQ(r.status, MassForDisplacement::Status::Found);
  // Bisection in log(m) to 1e-10: relative mass error ~1e-10.
  EXPECT_NEAR(r.mass, 2e4, 1e-8 * 2e4);
}

TEST(InverseDesign, TakesTheHeaviestFailingMassWhereTheModelIsNotMonotone) {
  // Two windows of masses fail; the answer lies above the heavier one, at its upper edge
  // (2e5 kg/m: the displacement steps there), and the scan from the heaviest mass down stops at
  // that window: the masses below it, where a model's barrier slides longest, are never run.
  double lightest = 1e300;
  const auto r = minimum_barrier_mass(
      [&](double m) {
        lightest = std::min(lightest, m);
        return (m >= 10.0 && m <= 100.0) || (m >= 1e5 && m <= 2e5) ? 1.0 : 0.0;
      },
      0.5);
  ASSERT_EQ(r.status, MassForDisplacement::Status::Found);
  EXPECT_NEAR(r.mass, 2e5, 1e-8 * 2e5);  // the bisection's resolution in log(m), as above
  EXPECT_GT(lightest, 1e5);
}

TEST(InverseDesign, TwoBodyMassGivesTheTolerableDisplacement) {
  const auto r = minimum_barrier_mass([](double m) { return two_body_displacement(m, 0.5); }, 0.5);
  ASSERT_EQ(r.status, MassForDisplacement::Status::Found);
  // The displacement is continuous in m2: at the minimum mass it equals the tolerance to the
  // bisection's resolution, and 1 % less mass exceeds it.
  EXPECT_NEAR(two_body_displacement(r.mass, 0.5), 0.5, 1e-6);
  EXPECT_GT(two_body_displacement(0.99 * r.mass, 0.5), 0.5);
  EXPECT_LE(two_body_displacement(1.5 * r.mass, 0.5), 0.5);
}

TEST(InverseDesign, NoFrictionMeansNoMassSuffices) {
  const auto r = minimum_barrier_mass([](double m) { return two_body_displacement(m, 0.0); }, 0.5);
  EXPECT_EQ(r.status, MassForDisplacement::Status::NoMassInRange);
}

TEST(InverseDesign, WeakImpactNeedsNoMass) {
  const auto r = minimum_barrier_mass([](double) { return 0.0; }, 0.5);
  EXPECT_EQ(r.status, MassForDisplacement::Status::AnyMassWorks);
}
}  // namespace

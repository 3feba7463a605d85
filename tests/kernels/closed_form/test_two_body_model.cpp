// Analytical two-body model (Cuomo et al. 2022), kernels/closed_form/two_body_model.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "kernels/closed_form/two_body_model.hpp"
#include "support/tolerances.hpp"

namespace {
using lsi::two_body_impact;
using lsi::TwoBodyCoefficients;
using lsi::test::kTwoRoutesRel;
using lsi::test::kUnitArithmeticAbs;
// tau within 1e-9 of 0 or 1: the pulse's impulse from a piece of near-zero length.
constexpr double kTauLimitRel = 1e-9;
constexpr double inf = std::numeric_limits<double>::infinity();
// L3 against B1: m1 = 97200 kg/m, L1,0 = 18 m, v10 = 12.5 m/s, m2 = 14400 kg/m.
constexpr double m1 = 97200, L = 18, v10 = 12.5, m2 = 14400;

TEST(TwoBodyModel, PeakDurationAndImpulseFollowFromTheInelasticCollision) {
  const TwoBodyCoefficients c{0.41, 0.25};
  const auto r = two_body_impact(m1, v10, L, m2, c);
  const double mu = m1 * m2 / (m1 + m2), s = 0.41 * L;
  // Tolerances 1e-13 relative: the same quantities by another algebraic route (round-off only).
  EXPECT_NEAR(r.reduced_mass, mu, 1e-13 * mu);
  EXPECT_NEAR(r.pulse.duration, 8.0 / 3.0 * s / v10, 1e-13);       // eq. 12
  EXPECT_NEAR(r.pulse.rise_time, 0.25 * r.pulse.duration, 1e-13);  // eq. 7
  EXPECT_NEAR(r.pulse.peak, 0.75 * mu * v10 * v10 / s, kTwoRoutesRel * r.pulse.peak);
  // Impulse = momentum lost by the landslide = mu v10; it ends at the common velocity.
  EXPECT_NEAR(r.pulse.pulse_impulse(), mu * v10, kTwoRoutesRel * mu * v10);
  EXPECT_NEAR(r.landslide_velocity(r.pulse.duration), m1 * v10 / (m1 + m2), kTwoRoutesRel * v10);
  EXPECT_NEAR(r.common_velocity, m1 * v10 / (m1 + m2), kTwoRoutesRel * v10);
}

TEST(TwoBodyModel, ForceMatchesPrintedEquations13And14AndIsContinuousAtT1) {
  const TwoBodyCoefficients c{0.5, 0.3};
  const auto r = two_body_impact(m1, v10, L, m2, c);
  const double q1 = r.q1, K1 = r.K1, tau = c.tau, T2 = r.pulse.duration;
  for (double f : {0.01, 0.1, 0.2, 0.3}) {
    const double t = f * T2;
    EXPECT_NEAR(r.pulse.force(t), 0.5 * q1 * q1 / K1 * (t / tau),
                kTwoRoutesRel * r.pulse.peak);  // eq. 13
  }
  for (double f : {0.3, 0.5, 0.9, 0.999}) {
    const double t = f * T2;
    EXPECT_NEAR(r.pulse.force(t), 0.5 * q1 * q1 / K1 * (T2 - t) / (1 - tau),
                kTwoRoutesRel * r.pulse.peak);  // eq. 14
  }
}

TEST(TwoBodyModel, VelocityMatchesPrintedEquation15) {
  // eq. 15 as printed is correct: it is the exact integral of eqs. 13-14.
  for (double tau : {0.17, 0.25, 0.6}) {
    const TwoBodyCoefficients c{0.41, tau};
    const auto r = two_body_impact(m1, v10, L, m2, c);
    const double A = r.q1 * r.q1 / (4 * r.K1 * m1), T1 = r.pulse.rise_time, T2 = r.pulse.duration;
    for (double f : {0.05, 0.2, 0.5, 0.8, 1.0}) {
      const double t = f * T2;
      const double printed =
          t < T1 ? v10 - A * t * t / tau : v10 + A * (t * t - 2 * T2 * t + T1 * T2) / (1 - tau);
      EXPECT_NEAR(r.landslide_velocity(t), printed, kTwoRoutesRel * v10)
          << "tau " << tau << " t/T2 " << f;
    }
  }
}

TEST(TwoBodyModel, FixedBarrierIsTheExactInfiniteMassLimit) {
  const auto fixed = two_body_impact(m1, v10, L, inf, lsi::default_two_body_coefficients(true));
  EXPECT_EQ(fixed.reduced_mass, m1);  // exactly, not approximately
  EXPECT_EQ(fixed.common_velocity, 0.0);
  EXPECT_NEAR(fixed.landslide_velocity(fixed.pulse.duration), 0.0, 1e-13 * v10);
  // A very heavy barrier approaches it continuously: mu = m1 / (1 + m1/m2).
  const auto heavy = two_body_impact(m1, v10, L, 1e12, lsi::default_two_body_coefficients(true));
  EXPECT_NEAR(heavy.pulse.peak, fixed.pulse.peak, 1e-6 * fixed.pulse.peak);
  EXPECT_DOUBLE_EQ(fixed.pulse.rise_time, 0.17 * fixed.pulse.duration);
  EXPECT_NEAR(fixed.max_shortening, 0.72 * L, kUnitArithmeticAbs);
}

TEST(TwoBodyModel, TauLimitsStayFinite) {
  for (double tau : {1e-9, 1 - 1e-9}) {
    const auto r = two_body_impact(m1, v10, L, m2, TwoBodyCoefficients{0.41, tau});
    EXPECT_NEAR(r.pulse.pulse_impulse(), r.reduced_mass * v10, kTauLimitRel * m1 * v10);
    for (double f : {0.0, 0.3, 0.7, 1.0}) {
      EXPECT_TRUE(std::isfinite(r.landslide_velocity(f * r.pulse.duration)));
    }
  }
}
}  // namespace

// Empirical model (Di Perna et al. 2022), kernels/closed_form/empirical_model.hpp.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/closed_form/empirical_model.hpp"
#include "support/tolerances.hpp"

namespace {
using lsi::empirical_impact;
using lsi::EmpiricalCoefficients;
using lsi::test::kIntegratedRel;
using lsi::test::kTwoRoutesRel;
// tau within 1e-9 of 0 or 1: the pulse's impulse from a piece of near-zero length.
constexpr double kTauLimitRel = 1e-9;
constexpr double deg = 3.14159265358979323846 / 180.0;

// Landslide L3 of the reference study: h = 3 m, v = 12.5 m/s, rho = 1800, 4 body squares.
constexpr double h = 3.0, v0 = 12.5, rho = 1800.0, m1 = rho * 6 * h * h;

// Composite Simpson quadrature of the pulse, split at its breakpoints (independent of the
// closed-form impulse).
template <class F>
double simpson(F f, double a, double b, int n = 20000) {
  const double hh = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += f(a + i * hh) * (i % 2 ? 4 : 2);
  return s * hh / 3.0;
}

TEST(EmpiricalModel, PeakForceOfVerticalWallMatchesHandCalculation) {
  // Computed by hand (Python, double precision) from eqs. 1-4 and 6:
  // Fr = 12.5/sqrt(9.81*3) = 2.304171931705546, alpha = 1.781 Fr^-0.515 = 1.1586939924412059,
  // F = alpha rho v^2 h = 977648.0561222675 N/m, T2 = 2 m1 v / F = 2.4855570312678013 s.
  const auto r = empirical_impact(h, v0, rho, m1, 90 * deg, EmpiricalCoefficients{});
  // Tolerance 1e-13: the same arithmetic in a different order; only round-off differs.
  EXPECT_NEAR(r.froude, 2.304171931705546, 1e-13 * 2.3);
  EXPECT_NEAR(r.alpha, 1.1586939924412059, 1e-13);
  EXPECT_NEAR(r.pulse.peak, 977648.0561222675, 1e-13 * 1e6);
  EXPECT_NEAR(r.pulse.duration, 2.4855570312678013, 1e-13 * 2.5);
  EXPECT_NEAR(r.pulse.rise_time, 0.14 * 2.4855570312678013, 1e-13);
  EXPECT_DOUBLE_EQ(r.peak_static, 0.0);  // kappa = 0 by default
}

TEST(EmpiricalModel, ImpulseEqualsMomentumChangeWithAndWithoutStaticComponent) {
  for (double kappa : {0.0, 1.0, 3.0}) {
    for (double beta : {90.0, 80.0, 60.0}) {
      EmpiricalCoefficients c;
      c.kappa = kappa;
      const auto r = empirical_impact(h, v0, rho, m1, beta * deg, c);
      const double quadrature =
          simpson([&](double t) { return r.pulse.force(t); }, 0.0, r.pulse.rise_time) +
          simpson([&](double t) { return r.pulse.force(t); }, r.pulse.rise_time, r.pulse.duration);
      // Simpson is exact on each linear piece: only round-off (1e-12 relative) remains.
      EXPECT_NEAR(quadrature, m1 * r.normal_velocity, kTwoRoutesRel * m1 * v0);
      EXPECT_NEAR(r.pulse.pulse_impulse(), m1 * r.normal_velocity, kTwoRoutesRel * m1 * v0);
      EXPECT_NEAR(r.landslide_normal_velocity(r.pulse.duration), 0.0, kTwoRoutesRel * v0);
      EXPECT_DOUBLE_EQ(r.pulse.force(10 * r.pulse.duration), r.peak_static);
    }
  }
}

TEST(EmpiricalModel, VelocityMatchesNumericalIntegrationOfTheForce) {
  EmpiricalCoefficients c;
  c.kappa = 1.0;
  const auto r = empirical_impact(h, v0, rho, m1, 70 * deg, c);
  for (double f : {0.05, 0.1, 0.3, 0.6, 0.9, 0.999}) {
    const double t = f * r.pulse.duration;
    // Direct integration of m1 dv/dt = -F(t) with RK4 on 20000 steps split at T1.
    auto rk4 = [&](double a, double b, double v) {
      const int n = 20000;
      const double dt = (b - a) / n;
      for (int i = 0; i < n; ++i) {
        const double ti = a + i * dt;
        const double k1 = -r.pulse.force(ti) / m1, k2 = -r.pulse.force(ti + dt / 2) / m1,
                     k4 = -r.pulse.force(ti + dt) / m1;
        v += dt / 6 * (k1 + 4 * k2 + k4);
      }
      return v;
    };
    double v = r.normal_velocity;
    if (t <= r.pulse.rise_time)
      v = rk4(0, t, v);
    else
      v = rk4(r.pulse.rise_time, t, rk4(0, r.pulse.rise_time, v));
    EXPECT_NEAR(r.landslide_normal_velocity(t), v, kIntegratedRel * v0) << "t/T2 = " << f;
  }
}

TEST(EmpiricalModel, ForceAndVelocityAreContinuousAtT1AndT2) {
  EmpiricalCoefficients c;
  c.kappa = 0.5;
  const auto r = empirical_impact(h, v0, rho, m1, 80 * deg, c);
  const double eps = 1e-9;
  for (double tb : {r.pulse.rise_time, r.pulse.duration}) {
    // A jump would be of order F_peak; continuity leaves F' * 2 eps (~1e-2 N/m here).
    EXPECT_NEAR(r.pulse.force(tb - eps), r.pulse.force(tb + eps), 1e-6 * r.pulse.peak);
    // Velocity: without a jump it changes by at most |dv/dt| 2 eps = F_peak/m1 * 2 eps.
    EXPECT_NEAR(r.landslide_normal_velocity(tb - eps), r.landslide_normal_velocity(tb + eps),
                2 * eps * r.pulse.peak / m1 * 1.001 + 1e-13 * v0);
  }
}

TEST(EmpiricalModel, PrintedEquation8IsDiscontinuousAtT1) {
  // docs/theory/models.md, deviation E1: the printed eq. 8, second branch, at t = T1 differs from the
  // first branch by F_peak T1 / (2 m1) - F_dyn T1^2 / (2 m1 (T2 - T1)), which is not zero.
  const auto r = empirical_impact(h, v0, rho, m1, 90 * deg, EmpiricalCoefficients{});
  const double F = r.pulse.peak, Fd = r.peak_dynamic, T1 = r.pulse.rise_time, T2 = r.pulse.duration;
  const double first = F / (2 * m1 * T1) * T1 * T1;
  const double second = F / m1 * T1 - Fd / (2 * m1 * (T2 - T1)) * T1 * T1;
  EXPECT_GT(std::abs(second - first), 0.1 * first);
  // Our velocity loss at T1 equals the first (correct) branch.
  EXPECT_NEAR(v0 - r.landslide_normal_velocity(T1), first, kTwoRoutesRel * v0);
}

TEST(EmpiricalModel, FaceInclinationResolvesVelocityAndKeepsTangentialEnergy) {
  const auto vertical = empirical_impact(h, v0, rho, m1, 90 * deg, EmpiricalCoefficients{});
  const auto inclined = empirical_impact(h, v0, rho, m1, 60 * deg, EmpiricalCoefficients{});
  EXPECT_NEAR(vertical.normal_velocity, v0, 1e-14 * v0);
  EXPECT_NEAR(vertical.tangential_velocity, 0.0, 1e-14 * v0);
  EXPECT_NEAR(inclined.normal_velocity, v0 * std::sqrt(3.0) / 2, 1e-14 * v0);
  EXPECT_LT(inclined.pulse.peak, vertical.pulse.peak);
  // Kinetic energy starts at m1 v0^2 / 2 and keeps the tangential part m1 (v0 cos beta)^2 / 2.
  EXPECT_NEAR(inclined.landslide_kinetic_energy(0), 0.5 * m1 * v0 * v0,
              kTwoRoutesRel * m1 * v0 * v0);
  EXPECT_NEAR(inclined.landslide_kinetic_energy(inclined.pulse.duration), 0.5 * m1 * v0 * v0 / 4,
              kTwoRoutesRel * m1 * v0 * v0);
}

TEST(EmpiricalModel, TauLimitsStayFiniteAndKeepTheImpulse) {
  for (double tau : {1e-9, 1e-3, 0.5, 1 - 1e-3, 1 - 1e-9}) {
    EmpiricalCoefficients c;
    c.tau = tau;
    c.kappa = 1.0;
    const auto r = empirical_impact(h, v0, rho, m1, 90 * deg, c);
    ASSERT_TRUE(std::isfinite(r.pulse.duration)) << tau;
    ASSERT_GT(r.pulse.duration, r.pulse.rise_time) << tau;
    EXPECT_NEAR(r.pulse.pulse_impulse(), m1 * v0, kTauLimitRel * m1 * v0) << tau;
    for (double f : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      EXPECT_TRUE(std::isfinite(r.landslide_normal_velocity(f * r.pulse.duration)));
    }
  }
}
}  // namespace

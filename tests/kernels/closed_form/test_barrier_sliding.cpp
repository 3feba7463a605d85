// Barrier motion: closed form (barrier_sliding.hpp, the corrected eqs. 17-20) against the direct
// numerical integration of the equation of motion (tests/support/sliding_ode.hpp) and against the
// exact piecewise integrator for any force history (rigid_block_response.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "kernels/closed_form/barrier_sliding.hpp"
#include "kernels/closed_form/empirical_model.hpp"
#include "kernels/closed_form/face_resolution.hpp"
#include "kernels/closed_form/rigid_block_response.hpp"
#include "kernels/closed_form/two_body_model.hpp"
#include "support/sliding_ode.hpp"
#include "support/tolerances.hpp"

namespace {
using namespace lsi;
using test::kFewOpsAbs;
using test::kIntegratedRel;
using test::kRoundOffAbs;
using test::kTwoRoutesRel;
constexpr double deg = 3.14159265358979323846 / 180.0;
// Eq. 20 as printed plus the term it drops against the exact displacement at T2: two routes to
// the same value, the printed one a difference of the phases' cubic terms; looser than
// kTwoRoutesRel.
constexpr double kPrintedEquation20Rel = 1e-9;

SlidingBlock block_for(double mass, double mu_b, double beta_deg) {
  return SlidingBlock{mass, mu_b, resolve_face_force(beta_deg * deg).sliding_drive(mu_b)};
}

struct Case {
  const char* name;
  ForcePulse pulse;
  SlidingBlock block;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  // Analytical L3-B1 (slides, stops after T2).
  {
    const auto imp = two_body_impact(97200, 12.5, 18, 14400, TwoBodyCoefficients{0.41, 0.25});
    out.push_back({"analytical L3-B1", imp.pulse, block_for(14400, 0.5, 80)});
  }
  // Empirical L3 on B3 with a static residual (kappa = 1): slides, stops after T2.
  {
    EmpiricalCoefficients c;
    c.kappa = 1.0;
    const auto imp = empirical_impact(3, 12.5, 1800, 97200, 60 * deg, c);
    out.push_back({"empirical L3-B3 kappa=1", imp.pulse, block_for(40000, 0.5, 60)});
  }
  // Heavy barrier: starts late and friction stops it before T2.
  {
    const auto imp = two_body_impact(97200, 12.5, 18, 60000, TwoBodyCoefficients{0.41, 0.25});
    out.push_back({"analytical heavy, stops before T2", imp.pulse, block_for(60000, 0.5, 90)});
  }
  // Low friction, long slide after T2.
  {
    const auto imp = two_body_impact(57600, 6, 16, 14400, TwoBodyCoefficients{0.41, 0.25});
    out.push_back({"analytical L1-B1 mu_b=0.05", imp.pulse, block_for(14400, 0.05, 80)});
  }
  return out;
}

TEST(BarrierSliding, ClosedFormMatchesDirectNumericalIntegration) {
  for (const auto& c : cases()) {
    const BarrierMotion m = barrier_motion(c.pulse, c.block);
    ASSERT_TRUE(m.moves) << c.name;
    ASSERT_TRUE(std::isfinite(m.final_displacement)) << c.name;
    test::SlidingOde ode{[&](double t) { return c.pulse.force(t); }, c.block.mass,
                         c.block.base_friction, c.block.drive};
    const double t_end = 1.5 * std::max(m.stop_time, c.pulse.duration);
    double ode_stop = -1;
    const auto s = ode.integrate(t_end, {c.pulse.rise_time, c.pulse.duration}, 4000, &ode_stop);
    // RK4 is exact for the cubic displacement on each smooth piece and the events are located
    // by bisection to round-off, so 1e-9 relative is the round-off of ~1e4 steps.
    EXPECT_NEAR(m.final_displacement, s.x, kIntegratedRel * s.x) << c.name;
    EXPECT_NEAR(m.stop_time, ode_stop, kIntegratedRel * ode_stop) << c.name;
    for (double f : {0.3, 0.6, 0.9, 1.0, 1.2}) {
      const double t = f * m.stop_time;
      double st = -1;
      const auto p = ode.integrate(t, {c.pulse.rise_time, c.pulse.duration}, 4000, &st);
      EXPECT_NEAR(m.displacement(t), p.x, kIntegratedRel * m.final_displacement)
          << c.name << " t " << t;
      EXPECT_NEAR(m.velocity(t), p.v, kIntegratedRel * (1 + m.velocity(t))) << c.name << " t " << t;
    }
  }
}

TEST(BarrierSliding, ClosedFormMatchesExactPiecewiseIntegratorForAnyHistory) {
  for (const auto& c : cases()) {
    const BarrierMotion m = barrier_motion(c.pulse, c.block);
    // The pulse sampled at 0, T1, T2 is exactly the pulse (piecewise linear, held after T2).
    const double t[3] = {0.0, c.pulse.rise_time, c.pulse.duration};
    const double N[3] = {0.0, c.pulse.peak, c.pulse.residual};
    double v[3], x[3];
    const auto r = rigid_block_response(t, N, 3, c.block, v, x);
    // Same exact solution by two routes: round-off only (1e-12 relative).
    EXPECT_NEAR(r.final_displacement, m.final_displacement, kTwoRoutesRel * m.final_displacement)
        << c.name;
    EXPECT_NEAR(r.stop_time, m.stop_time, kTwoRoutesRel * m.stop_time) << c.name;
    EXPECT_NEAR(r.start_time, m.start_time, kTwoRoutesRel * m.stop_time) << c.name;
    EXPECT_NEAR(x[1], m.displacement(t[1]), kTwoRoutesRel * m.final_displacement) << c.name;
    EXPECT_NEAR(v[2], m.velocity(t[2]), kTwoRoutesRel * (1 + m.velocity(t[1]))) << c.name;
    // Finely resampled history (2001 samples) gives the same answer too.
    std::vector<double> ts(2001), Ns(2001);
    for (int i = 0; i < 2001; ++i) {
      ts[i] = c.pulse.duration * i / 2000.0;
      Ns[i] = c.pulse.force(ts[i]);
    }
    // Resampling cuts the kink at T1 when T1 is not on the grid: the force differs from the pulse
    // only inside one segment of length dt = T2/2000, a relative impulse error of order
    // (dt/T2)^2 / (tau (1 - tau)) ~ 2e-6 for tau = 0.14; hence 5e-6.
    const auto rf = rigid_block_response(ts.data(), Ns.data(), 2001, c.block);
    EXPECT_NEAR(rf.final_displacement, m.final_displacement, 5e-6 * m.final_displacement) << c.name;
  }
}

TEST(BarrierSliding, PhaseAMatchesCorrectedEquation17AndStartTime) {
  // Eq. 17 with m2 (not m1) and tan(delta_b) (not tan(gamma_b)), and our drive coefficient c.
  const double m2 = 14400, mu_b = 0.5, tau = 0.25;
  const auto imp = two_body_impact(97200, 12.5, 18, m2, TwoBodyCoefficients{0.41, tau});
  const SlidingBlock b = block_for(m2, mu_b, 80);
  const BarrierMotion m = barrier_motion(imp.pulse, b);
  const double q1 = imp.q1, K1 = imp.K1, c = b.drive, g = 9.81;
  const double t_star = 2 * K1 * m2 * tau * g * mu_b / (q1 * q1 * c);  // eq. 17, t*
  EXPECT_NEAR(m.start_time, t_star, kTwoRoutesRel * t_star);
  for (double f : {0.2, 0.5, 0.8, 1.0}) {
    const double t = t_star + f * (imp.pulse.rise_time - t_star);
    const double v17 =
        q1 * q1 / (4 * K1 * m2) * c * (t * t - t_star * t_star) / tau - g * mu_b * (t - t_star);
    const double x18 = q1 * q1 / (12 * K1 * m2) * c *
                           (t * t * t - 3 * t_star * t_star * t + 2 * t_star * t_star * t_star) /
                           tau -
                       0.5 * g * mu_b * (t - t_star) * (t - t_star);
    EXPECT_NEAR(m.velocity(t), v17, kTwoRoutesRel * 10);
    EXPECT_NEAR(m.displacement(t), x18, kTwoRoutesRel * 10);
  }
}

TEST(BarrierSliding, PhaseBMatchesPrintedEquation18SecondBranch) {
  // Eq. 18, T1 < t <= T2, is correct as printed once m2 is read for m1 (docs/theory/models.md).
  const double m2 = 14400, mu_b = 0.5, tau = 0.25;
  const auto imp = two_body_impact(97200, 12.5, 18, m2, TwoBodyCoefficients{0.41, tau});
  const SlidingBlock b = block_for(m2, mu_b, 80);
  const BarrierMotion m = barrier_motion(imp.pulse, b);
  const double q1 = imp.q1, K1 = imp.K1, c = b.drive, g = 9.81, T1 = imp.pulse.rise_time,
               T2 = imp.pulse.duration;
  for (double f : {0.1, 0.5, 0.9, 1.0}) {
    const double t = T1 + f * (T2 - T1);
    const double x18 =
        q1 * q1 / (12 * K1 * m2) * c * (T1 - t) * (T1 - t) * (3 * T2 - 2 * T1 - t) / (1 - tau) -
        0.5 * g * mu_b * (T1 - t) * (T1 - t) - m.velocity(T1) * (T1 - t) + m.displacement(T1);
    EXPECT_NEAR(m.displacement(t), x18, kTwoRoutesRel * 10);
  }
}

TEST(BarrierSliding, SecondBranchOfEquation17HasTheWrongSignAndDropsATerm) {
  // Eq. 17, T1 < t < T2 (docs/theory/models.md, deviation A8): integrating the drive c N(t) / m2 gives
  //   v2 = q1^2 c / (4 K1 m2) [-(t^2 - 2 T2 t + T1 T2) / (1 - tau) - t*^2 / tau] - g mu_b (t - t*)
  // while the printed branch has + on the first term and no t*^2 / tau.
  const double m2 = 14400, mu_b = 0.5, tau = 0.25;
  const auto imp = two_body_impact(97200, 12.5, 18, m2, TwoBodyCoefficients{0.41, tau});
  const SlidingBlock b = block_for(m2, mu_b, 80);
  const BarrierMotion m = barrier_motion(imp.pulse, b);
  const double q1 = imp.q1, K1 = imp.K1, c = b.drive, g = 9.81, T1 = imp.pulse.rise_time,
               T2 = imp.pulse.duration, ts = m.start_time;
  ASSERT_GT(m.velocity(T2), 0.0);  // still sliding through the decay: the branch applies
  for (double f : {0.1, 0.5, 0.9}) {
    const double t = T1 + f * (T2 - T1);
    const double k = q1 * q1 * c / (4 * K1 * m2);
    const double derived =
        k * (-(t * t - 2 * T2 * t + T1 * T2) / (1 - tau) - ts * ts / tau) - g * mu_b * (t - ts);
    const double printed = k * (t * t - 2 * T2 * t + T1 * T2) / (1 - tau) - g * mu_b * (t - ts);
    EXPECT_NEAR(m.velocity(t), derived, kTwoRoutesRel * 10) << "t = " << t;  // m/s: round-off
    EXPECT_GT(std::fabs(printed - derived), 1.0) << "t = " << t;             // printed: off by m/s
  }
}

TEST(BarrierSliding, PrintedEquation20OmitsTermsThatMatter) {
  // docs/theory/models.md, deviation A4: eq. 20 as printed (with the same c) against the exact answer.
  const double m2 = 14400, mu_b = 0.5, tau = 0.25;
  const auto imp = two_body_impact(97200, 12.5, 18, m2, TwoBodyCoefficients{0.41, tau});
  const SlidingBlock b = block_for(m2, mu_b, 80);
  const BarrierMotion m = barrier_motion(imp.pulse, b);
  const double q1 = imp.q1, K1 = imp.K1, c = b.drive, g = 9.81, T1 = imp.pulse.rise_time,
               T2 = imp.pulse.duration, ts = m.start_time;
  const double printed =
      q1 * q1 / (12 * K1 * m2) * c *
          ((T1 - ts) * (T1 - ts) * (T1 + 2 * ts) / tau + 2 * std::pow(T2 - T1, 3) / (1 - tau)) -
      0.5 * g * mu_b * ((T1 - ts) * (T1 - ts) + (T2 - T1) * (T2 - T1));
  // The exact displacement at T2 is the printed value plus v2(T1) (T2 - T1) (the term eq. 20
  // drops) ...
  const double x_T2 = m.displacement(T2);
  const double restored = printed + m.velocity(T1) * (T2 - T1);
  EXPECT_NEAR(x_T2, restored, kPrintedEquation20Rel * x_T2);
  // ... and the barrier still moves at T2 and slides on: the final displacement is larger.
  EXPECT_GT(m.velocity(T2), 0.1);
  EXPECT_GT(m.final_displacement, 1.05 * x_T2);
  EXPECT_GT(std::abs(printed - m.final_displacement), 0.1 * m.final_displacement);
}

TEST(BarrierSliding, NoBaseFrictionMeansItNeverStops) {
  const auto imp = two_body_impact(57600, 6, 16, 14400, TwoBodyCoefficients{0.41, 0.25});
  const SlidingBlock b = block_for(14400, 0.0, 90);
  const BarrierMotion m = barrier_motion(imp.pulse, b);
  EXPECT_TRUE(m.moves);
  EXPECT_EQ(m.start_time, 0.0);
  EXPECT_TRUE(std::isinf(m.final_displacement));
  // Without friction it leaves the impact with all the impulse: v2(T2) = I / m2 = mu v10 / m2.
  EXPECT_NEAR(m.velocity(imp.pulse.duration), imp.reduced_mass * 6 / 14400, kRoundOffAbs);
  const double t[3] = {0, imp.pulse.rise_time, imp.pulse.duration};
  const double N[3] = {0, imp.pulse.peak, 0};
  EXPECT_TRUE(std::isinf(rigid_block_response(t, N, 3, b).final_displacement));
}

TEST(BarrierSliding, WeakPulseOrShallowFrictionalFaceSticks) {
  const auto imp = two_body_impact(57600, 6, 16, 14400, TwoBodyCoefficients{0.41, 0.25});
  // L1-B1: c F_peak = 0.898 * 47.4 kN/m < m2 g tan(delta_b) = 70.6 kN/m: it never slides.
  const BarrierMotion m = barrier_motion(imp.pulse, block_for(14400, 0.5, 80));
  EXPECT_FALSE(m.moves);
  EXPECT_EQ(m.final_displacement, 0.0);
  // A face flatter than the friction angle (tan(beta) < tan(delta_b)) is pressed down harder
  // than it is pushed: c <= 0, no sliding whatever the force.
  const SlidingBlock shallow = block_for(100, 2.0, 20);
  EXPECT_LT(shallow.drive, 0.0);
  ForcePulse huge{1e9, 0.1, 1.0, 0.0};
  EXPECT_FALSE(barrier_motion(huge, shallow).moves);
}

TEST(BarrierSliding, DisplacementDecreasesWithBarrierMass) {
  double previous = std::numeric_limits<double>::infinity();
  for (double m2 = 5000; m2 <= 3e5; m2 *= 1.25) {
    const auto imp = two_body_impact(97200, 12.5, 18, m2, TwoBodyCoefficients{0.41, 0.25});
    const double d = barrier_motion(imp.pulse, block_for(m2, 0.5, 80)).final_displacement;
    EXPECT_LE(d, previous) << m2;
    previous = d;
  }
  EXPECT_EQ(previous, 0.0);  // heavy enough to stick
}

TEST(BarrierSliding, VerticalFaceDrivesWithTheFullForce) {
  const FaceResolution r = resolve_face_force(90 * deg);
  EXPECT_NEAR(r.horizontal, 1.0, kFewOpsAbs);
  EXPECT_NEAR(r.vertical_down, 0.0, kFewOpsAbs);
  EXPECT_NEAR(r.sliding_drive(0.7), 1.0, kFewOpsAbs);
  // Inclined face, no face shear: c = sin(beta) - tan(delta_b) cos(beta).
  EXPECT_NEAR(resolve_face_force(60 * deg).sliding_drive(0.5), std::sqrt(3.0) / 2 - 0.25,
              kFewOpsAbs);
}
}  // namespace

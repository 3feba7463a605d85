// The momentum-consistent barrier (kernels/closed_form/momentum_barrier.hpp; docs/theory/models.md,
// "Momentum-consistent barrier"): against a direct integration of its own equations, and in its
// limits (fixed, sticking, frictionless, infinitely heavy, a vertical face).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "kernels/closed_form/face_resolution.hpp"
#include "kernels/closed_form/momentum_barrier.hpp"
#include "kernels/common/constants.hpp"
#include "support/tolerances.hpp"

namespace {
using namespace lsi;
using test::kIntegratedRel;
using test::kRoundOffAbs;
using test::kTwoRoutesRel;

// The model against a fixed-step integration of the same equations: the direct integration's own
// error at its step (below 1e-10 relative; about 2e-9 at 4 times the step).
constexpr double kDirectIntegrationRel = 1e-9;
// h J of the shortened pulse against m1 v0: the pulse's duration solved for its impulse and the
// impulse integrated back (a loose round-off bound).
constexpr double kCappedImpulseRel = 1e-9;

constexpr double kPi = 3.14159265358979323846;

// A triangle of a fixed barrier whose horizontal impulse stops the flow: F_peak T2 / 2 =
// m1 v0 / h (the analytical model's pulse with lambda, tau, made momentum-consistent).
MomentumBarrierSetup setup(double m1, double v0, double L, double m2, double mu_b, double beta_deg,
                           double mu_f, double lambda = 0.72, double tau = 0.17, double f1 = 0.0) {
  MomentumBarrierSetup s;
  s.flow_friction = f1;
  s.face = resolve_face_force(beta_deg * kPi / 180.0, mu_f);
  s.landslide_mass = m1;
  s.velocity = v0;
  s.barrier_mass = m2;
  s.base_friction = mu_b;
  const double T2 = 8.0 / 3.0 * lambda * L / v0;
  s.fixed_pulse.duration = T2;
  s.fixed_pulse.rise_time = tau * T2;
  s.fixed_pulse.peak = 2.0 * m1 * v0 / (s.face.horizontal * T2);
  return s;
}

std::vector<double> grid(double t_end, int n) {
  std::vector<double> t(n);
  for (int i = 0; i < n; ++i) t[i] = t_end * i / (n - 1);
  return t;
}

// The model's equations integrated as written, in the physical variables, by the classical
// Runge-Kutta method with a small fixed step:
//   m1 v1' = -h N - m1 f1,  m2 v2' = c N - mu_b m2 g (sliding, v2 > 0 or c N > mu_b m2 g), x2' = v2,
//   N = Phi(w), w = v0 - v1 + v2, on the rising branch until N reaches the peak.
// Phi(w) = sqrt(2 F_p (m1 w / h) / T1) rising, sqrt(2 F_p (J - m1 w / h) / (T2 - T1)) decaying.
// On a smooth flow base it starts inside the first sticking phase (where the fixed pulse is
// exact), or, without base friction, a moment after t = 0 from the exact start of the slide;
// with the flow's base friction at t = 0 (w grows from the first instant). Returns the final
// displacement and fills v2 at `times`.
double direct_integration(const MomentumBarrierSetup& s, const std::vector<double>& times,
                          std::vector<double>& v2_at, double dt_max) {
  const ForcePulse& p = s.fixed_pulse;
  const double m1 = s.landslide_mass, m2 = s.barrier_mass, v0 = s.velocity;
  const double h = s.face.horizontal, c = s.face.sliding_drive(s.base_friction);
  const double gf = s.base_friction * gravity, J = p.pulse_impulse();
  const double w1 = h * 0.5 * p.peak * p.rise_time / m1;
  bool decay = false;
  auto Phi = [&](double w) {
    if (!decay) return std::sqrt(std::max(0.0, 2.0 * p.peak * (m1 * w / h) / p.rise_time));
    return std::sqrt(std::max(0.0, 2.0 * p.peak * (J - m1 * w / h) / (p.duration - p.rise_time)));
  };
  const double f1 = s.flow_friction;
  double t, v1, v2 = 0.0, x2 = 0.0;
  if (f1 > 0.0) {
    t = 0.0;
    v1 = v0;
  } else if (gf > 0.0) {
    t = 0.5 * (gf * m2 / c) / (p.peak / p.rise_time);  // half way to the slip
    v1 = v0 - h * p.impulse(t) / m1;
  } else {
    const double a2 = 2.0 * p.peak * m1 / (h * p.rise_time);  // a^2
    const double kappa = h / m1 + c / m2;
    t = 1e-7 * p.duration;
    v1 = v0 - h * kappa * a2 * t * t / (4.0 * m1);
    v2 = c * kappa * a2 * t * t / (4.0 * m2);
    x2 = c * kappa * a2 * t * t * t / (12.0 * m2);
  }
  bool sliding = gf == 0.0 && f1 == 0.0;
  size_t k = 0;
  while (k < times.size() && times[k] <= t) v2_at[k++] = v2;
  auto rhs = [&](double v1_, double v2_, double* d) {
    const double N = Phi(v0 - v1_ + v2_);
    d[0] = -h * N / m1 - f1;
    d[1] = sliding ? (c * N - gf * m2) / m2 : 0.0;
    d[2] = v2_;
  };
  const double t_max = 50.0 * p.duration;
  for (int step = 0; t < t_max && step < 100000000; ++step) {
    if (!decay && v0 - v1 + v2 >= w1) decay = true;
    const double N = Phi(v0 - v1 + v2);
    if (!sliding && c * N > gf * m2 && m2 < 1e300) sliding = true;
    // Land on the next sample time.
    const double dt = k < times.size() && times[k] < t + dt_max ? times[k] - t : dt_max;
    double k1[3], k2[3], k3[3], k4[3];
    rhs(v1, v2, k1);
    rhs(v1 + 0.5 * dt * k1[0], v2 + 0.5 * dt * k1[1], k2);
    rhs(v1 + 0.5 * dt * k2[0], v2 + 0.5 * dt * k2[1], k3);
    rhs(v1 + dt * k3[0], v2 + dt * k3[1], k4);
    v1 += dt / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]);
    v2 += dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]);
    x2 += dt / 6 * (k1[2] + 2 * k2[2] + 2 * k3[2] + k4[2]);
    t += dt;
    if (sliding && v2 <= 0.0) {  // stops; the drive has fallen below the friction
      // v2 is nearly linear over the step: take back the displacement after the stop.
      const double v_before = v2 - dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]);
      const double f = v_before / (v_before - v2);
      x2 -= 0.5 * v2 * (1.0 - f) * dt;
      v2 = 0.0;
      sliding = false;
    }
    while (k < times.size() && times[k] <= t) v2_at[k++] = v2;
    if (decay && !sliding && Phi(v0 - v1 + v2) <= 0.0) break;  // the contact is over
  }
  while (k < times.size()) v2_at[k++] = v2;
  return x2;
}

// L2-B1-like (90 t/m at 9 m/s against 26.4 t/m) and L1-B1-like cases: each slides on both
// branches and decelerates together with the flow after the pulse.
TEST(MomentumBarrier, MatchesADirectIntegrationOfItsEquations) {
  struct Case {
    double m1, v0, L, m2, mu_b, beta, mu_f, f1;
  };
  // The last three with the flow braked by its base (f1 = 0.2 g x 0.72: the reference study's
  // flow base on a saturated flow's grain contacts).
  for (const Case& c :
       {Case{90000, 9, 20, 26400, 0.5, 80, 0.3, 0}, Case{57600, 6, 16, 26400, 0.5, 80, 0.3, 0},
        Case{97200, 12.5, 18, 82000, 0.5, 60, 0.3, 0}, Case{57600, 6, 16, 26400, 0.2, 90, 0.0, 0},
        Case{90000, 9, 20, 26400, 0.5, 80, 0.3, 1.416},
        Case{97200, 12.5, 18, 26400, 0.5, 80, 0.3, 1.416},
        Case{57600, 6, 16, 26400, 0.2, 90, 0.0, 1.416}}) {
    const MomentumBarrierSetup s =
        setup(c.m1, c.v0, c.L, c.m2, c.mu_b, c.beta, c.mu_f, 0.72, 0.17, c.f1);
    const MomentumBarrierResult r0 = momentum_barrier(s);
    ASSERT_TRUE(r0.ok);
    ASSERT_GT(r0.start_time, 0.0) << "the case must slide";
    const std::vector<double> t = grid(1.2 * r0.contact_end, 61);
    std::vector<MomentumBarrierState> st(t.size());
    const MomentumBarrierResult r = momentum_barrier(s, t.data(), int(t.size()), st.data());
    std::vector<double> v2(t.size());
    const double x_direct = direct_integration(s, t, v2, s.fixed_pulse.duration * 5e-7);
    // 1e-9: the fixed-step integration converges to the model as its step shrinks (its error at
    // this step is below 1e-10 relative; at 4 times the step, about 2e-9).
    EXPECT_NEAR(r.final_displacement, x_direct, kDirectIntegrationRel * x_direct + kRoundOffAbs)
        << c.m1 << " " << c.m2;
    double vmax = 0.0;
    for (size_t i = 0; i < t.size(); ++i) vmax = std::max(vmax, v2[i]);
    for (size_t i = 0; i < t.size(); ++i)
      EXPECT_NEAR(st[i].barrier_velocity, v2[i], 1e-8 * vmax) << "t = " << t[i];
    EXPECT_EQ(r.final_displacement, r0.final_displacement);  // sampling does not change it
  }
}

TEST(MomentumBarrier, NeverFasterThanTheFlowAndMomentumOnlyLostToFriction) {
  for (double m2 : {2000.0, 10000.0, 26400.0, 60000.0}) {
    const MomentumBarrierSetup s = setup(97200, 12.5, 18, m2, 0.5, 80, 0.3);
    const MomentumBarrierResult r0 = momentum_barrier(s);
    const std::vector<double> t = grid(r0.contact_end, 2001);
    std::vector<MomentumBarrierState> st(t.size());
    momentum_barrier(s, t.data(), int(t.size()), st.data());
    for (const auto& x : st) {
      // 1e-9 of v0: the integration's tolerance.
      EXPECT_LE(x.barrier_velocity, x.landslide_velocity + kIntegratedRel * 12.5)
          << "m2 " << m2 << " t " << x.time;
      EXPECT_GE(x.barrier_velocity, 0.0);
      EXPECT_GE(x.force, 0.0);
      EXPECT_LE(x.force, s.fixed_pulse.peak * (1 + 1e-12));
    }
    // Everything at rest at the end: the flow's momentum went into the barrier's base.
    EXPECT_NEAR(st.back().landslide_velocity, 0.0, kIntegratedRel * 12.5) << m2;
    EXPECT_EQ(st.back().barrier_velocity, 0.0);
    EXPECT_TRUE(std::isfinite(r0.final_displacement));
  }
}

TEST(MomentumBarrier, FixedAndStickingBarriersGetTheFixedPulse) {
  for (double m2 : {std::numeric_limits<double>::infinity(), 1e9}) {
    const MomentumBarrierSetup s = setup(57600, 6, 16, m2, 0.5, 80, 0.3);
    const std::vector<double> t = grid(1.2 * s.fixed_pulse.duration, 241);
    std::vector<MomentumBarrierState> st(t.size());
    const MomentumBarrierResult r = momentum_barrier(s, t.data(), int(t.size()), st.data());
    EXPECT_EQ(r.start_time, -1.0);
    EXPECT_EQ(r.final_displacement, 0.0);
    EXPECT_NEAR(r.rise_time, s.fixed_pulse.rise_time, kRoundOffAbs);
    EXPECT_NEAR(r.contact_end, s.fixed_pulse.duration, kTwoRoutesRel * s.fixed_pulse.duration);
    for (size_t i = 0; i < t.size(); ++i) {
      // Sticking phases are exact: round-off.
      EXPECT_NEAR(st[i].force, s.fixed_pulse.force(t[i]), kIntegratedRel * s.fixed_pulse.peak)
          << t[i];
      EXPECT_EQ(st[i].barrier_velocity, 0.0);
    }
    // The fixed barrier stops the flow: its horizontal impulse is m1 v0.
    EXPECT_NEAR(st.back().landslide_velocity, 0.0, kIntegratedRel);
  }
}

TEST(MomentumBarrier, WithoutBaseFrictionBothEndAtTheCommonVelocityAndNeverStop) {
  // A vertical smooth face (h = 1, c = 1): the perfectly inelastic collision's common velocity.
  const double m1 = 57600, m2 = 26400, v0 = 6;
  const MomentumBarrierSetup s = setup(m1, v0, 16, m2, 0.0, 90, 0.0);
  const MomentumBarrierResult r = momentum_barrier(s);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.start_time, 0.0);
  EXPECT_TRUE(std::isinf(r.final_displacement));
  EXPECT_TRUE(std::isinf(r.stop_time));
  const double v_cm = m1 * v0 / (m1 + m2);
  EXPECT_NEAR(r.final_landslide_velocity, v_cm, kIntegratedRel * v0);
  EXPECT_NEAR(r.largest_barrier_velocity, v_cm, kIntegratedRel * v0);
  // The pulse is faster than the fixed one (the relative velocity falls from both sides) and as
  // high.
  EXPECT_LT(r.contact_end, s.fixed_pulse.duration);
  EXPECT_EQ(r.peak_force, s.fixed_pulse.peak);
}

TEST(MomentumBarrier, AfterThePulseFlowAndBarrierDecelerateTogether) {
  // Vertical smooth face: the pair (m1 + m2) is braked by the friction of the barrier's weight
  // alone (the flow's base is smooth): a = mu_b g m2 / (m1 + m2), in every late interval.
  const double m1 = 97200, m2 = 26400, mu_b = 0.5;
  const MomentumBarrierSetup s = setup(m1, 12.5, 18, m2, mu_b, 90, 0.0);
  const MomentumBarrierResult r0 = momentum_barrier(s);
  ASSERT_GT(r0.stop_time, 2.0 * s.fixed_pulse.duration);  // a long joint slide
  const double t_a = 1.5 * s.fixed_pulse.duration, t_b = 0.9 * r0.stop_time;
  const std::vector<double> t = {t_a, t_b};
  std::vector<MomentumBarrierState> st(2);
  momentum_barrier(s, t.data(), 2, st.data());
  const double a = -(st[1].barrier_velocity - st[0].barrier_velocity) / (t_b - t_a);
  const double expected = mu_b * gravity * m2 / (m1 + m2);
  // The joint motion is approached, not reached: the push relaxes to its equilibrium on the
  // pulse's time scale; 1e-4 relative once several pulse durations have passed.
  EXPECT_NEAR(a, expected, 1e-4 * expected);
  // The push that brakes the flow, N = mu_b g / kappa (kappa = h / m1 + c / m2), needs the flow
  // to be a little faster than the barrier: N = b sqrt(W - w) gives v1 - v2 = (N / b)^2 (b of the
  // decaying branch, W = v0 here).
  const ForcePulse& p = s.fixed_pulse;
  const double b = std::sqrt(2.0 * p.peak * m1 / (p.duration - p.rise_time));
  const double N = mu_b * gravity / (1.0 / m1 + 1.0 / m2);
  EXPECT_NEAR(st[1].landslide_velocity - st[1].barrier_velocity, (N / b) * (N / b),
              1e-3 * (N / b) * (N / b));
}

TEST(MomentumBarrier, TheFaceFrictionAndTheVerticalLoadEnterTheDrive) {
  // The same flow against the same barrier: a 60 deg face without shear pushes the barrier down
  // (more friction, less slide) than a vertical one; face friction on a vertical face lifts it
  // (less friction, more slide).
  auto slide = [](double beta, double mu_f) {
    return momentum_barrier(setup(90000, 9, 20, 36000, 0.5, beta, mu_f)).final_displacement;
  };
  EXPECT_LT(slide(60, 0.0), slide(90, 0.0));
  EXPECT_GT(slide(90, 0.3), slide(90, 0.0));
}

}  // namespace

namespace {
// The flow's base friction (F1 = m1 f1) takes its share of the flow's momentum: against a fixed
// barrier the flow ends at rest with h J + m1 f1 t_c = m1 v0 (J the barrier's impulse, t_c the
// contact), the pulse is shorter and lower in impulse than on a smooth base, and a free barrier
// slides less.
TEST(MomentumBarrier, TheFlowsBaseFrictionTakesItsShareOfTheMomentum) {
  const double m1 = 90000, v0 = 9, f1 = 1.416;
  const MomentumBarrierSetup fixed =
      setup(m1, v0, 20, std::numeric_limits<double>::infinity(), 0.5, 80, 0.3, 0.72, 0.17, f1);
  const MomentumBarrierResult r0 = momentum_barrier(fixed);
  ASSERT_TRUE(r0.ok);
  EXPECT_LT(r0.contact_end, fixed.fixed_pulse.duration);
  const std::vector<double> t = grid(r0.contact_end, 20001);
  std::vector<MomentumBarrierState> st(t.size());
  momentum_barrier(fixed, t.data(), int(t.size()), st.data());
  double J = 0.0;  // trapezoids on 20001 samples: 1e-6 of the impulse
  for (size_t i = 1; i < t.size(); ++i)
    J += 0.5 * (st[i].force + st[i - 1].force) * (t[i] - t[i - 1]);
  EXPECT_NEAR(fixed.face.horizontal * J + m1 * f1 * r0.contact_end, m1 * v0, 1e-6 * m1 * v0);
  EXPECT_NEAR(r0.final_landslide_velocity, 0.0, kIntegratedRel * v0);
  // A free barrier slides less when the flow's base brakes it too.
  const double smooth = momentum_barrier(setup(m1, v0, 20, 26400, 0.5, 80, 0.3)).final_displacement;
  const double rough =
      momentum_barrier(setup(m1, v0, 20, 26400, 0.5, 80, 0.3, 0.72, 0.17, f1)).final_displacement;
  EXPECT_LT(rough, 0.8 * smooth);
  EXPECT_GT(rough, 0.0);
}
}  // namespace

namespace {
// A pulse whose horizontal impulse exceeds the flow's momentum (the empirical pulse with face
// friction on a steep face) is shortened to h J = m1 v0, its peak and tau kept; one within it is
// left as it is.
TEST(MomentumBarrier, PulsesAreCappedAtTheFlowsMomentum) {
  ForcePulse p;
  p.peak = 5e5;
  p.duration = 2.0;
  p.rise_time = 0.3;
  const double m1 = 90000, v0 = 9, h = 1.04;
  const ForcePulse same = momentum_capped_pulse(p, m1, v0, h);  // h J = 5.2e5 < m1 v0 = 8.1e5
  EXPECT_EQ(same.duration, p.duration);
  p.duration = 4.0;  // h J = 1.04e6 > 8.1e5
  p.rise_time = 0.6;
  const ForcePulse c = momentum_capped_pulse(p, m1, v0, h);
  EXPECT_NEAR(h * c.pulse_impulse(), m1 * v0, kCappedImpulseRel * m1 * v0);
  EXPECT_EQ(c.peak, p.peak);
  EXPECT_NEAR(c.rise_time / c.duration, 0.15, kRoundOffAbs);
  // The barrier then never outruns the flow: a light barrier on a vertical face with friction.
  MomentumBarrierSetup s = setup(m1, v0, 20, 5000, 0.5, 90, 0.3);
  s.fixed_pulse = momentum_capped_pulse(p, m1, v0, s.face.horizontal);
  const std::vector<double> t = grid(3.0, 601);
  std::vector<MomentumBarrierState> st(t.size());
  ASSERT_TRUE(momentum_barrier(s, t.data(), int(t.size()), st.data()).ok);
  for (const auto& x : st)
    EXPECT_LE(x.barrier_velocity, x.landslide_velocity + kIntegratedRel * v0);
}
}  // namespace

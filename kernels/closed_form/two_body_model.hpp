// Design approach No. 2, analytical two-body inelastic collision (Cuomo et al. 2022; the paper's
// eqs. 11-16), the landslide's side. The barrier's motion is in barrier_sliding.hpp.
//
// Symbols (SI): m1 landslide mass per metre (kg/m), m2 barrier mass per metre (kg/m; +infinity
// for a barrier fixed to the ground), v10 approach velocity (m/s), L10 equivalent landslide length
// (m), lambda = s1,max / L1,0 and tau = T1 / T2 the two model parameters.
//   reduced mass   mu = m1 m2 / (m1 + m2) = m1 / (1 + m1/m2)      (= m1 exactly when m2 = inf)
//   K1   = mu v10 / s1,max                                  (kg/s)
//   eq. 11  q1 = (3/4) K1 v10 / sqrt(s1,max)                (kg m^0.5 / s^2)
//   eq. 12  T2 = (8/3) s1,max / v10,      eq. 7  T1 = tau T2
//   eq. 13  F(t) = (1/2) (q1^2 / K1) (t / tau)              0 < t <= T1
//   eq. 14  F(t) = (1/2) (q1^2 / K1) (T2 - t) / (1 - tau)   T1 <= t < T2
//   so F_peak = (1/2) (q1^2/K1) T2 = (3/4) mu v10^2 / s1,max and the impulse is mu v10: the
//   momentum that body 1 loses in a perfectly inelastic collision (common velocity v_CM).
//   eq. 15  v1(t) = v10 - I(t) / m1,      eq. 16  E_k,1 = m1 v1^2 / 2
// F(t) is the contact force normal to the impacted face (the paper resolves it with sin(beta) and
// cos(beta) on the barrier, eq. 17). See docs/theory/models.md, "Analytical model".
#pragma once
#include "kernels/closed_form/force_pulse.hpp"
#include "kernels/common/math.hpp"

namespace lsi {

struct TwoBodyCoefficients {
  double lambda = 0.41;  // s1,max / L1,0, in (0, 1]
  double tau = 0.25;     // T1 / T2, in (0, 1)
};

// The paper's calibrated values (Cuomo et al. 2022): fixed barriers 0.72 / 0.17, free 0.41 / 0.25.
KOKKOS_INLINE_FUNCTION TwoBodyCoefficients default_two_body_coefficients(bool fixed_barrier) {
  TwoBodyCoefficients c;
  c.lambda = fixed_barrier ? 0.72 : 0.41;
  c.tau = fixed_barrier ? 0.17 : 0.25;
  return c;
}

struct TwoBodyImpact {
  double landslide_mass = 0.0;     // m1, kg/m
  double reduced_mass = 0.0;       // mu, kg/m
  double approach_velocity = 0.0;  // v10, m/s
  double max_shortening = 0.0;     // s1,max, m
  double K1 = 0.0;                 // kg/s
  double q1 = 0.0;                 // kg m^0.5 / s^2
  double common_velocity = 0.0;    // v_CM = m1 v10 / (m1 + m2), m/s
  ForcePulse pulse;                // normal force on the face

  // eq. 15; after T2 the landslide keeps v_CM.
  KOKKOS_INLINE_FUNCTION double landslide_velocity(double t) const {
    return approach_velocity - pulse.impulse(math::min(t, pulse.duration)) / landslide_mass;
  }
  // eq. 16 (J/m).
  KOKKOS_INLINE_FUNCTION double landslide_kinetic_energy(double t) const {
    const double v = landslide_velocity(t);
    return 0.5 * landslide_mass * v * v;
  }
};

// barrier_mass = +infinity for a fixed barrier (exact: mu = m1).
KOKKOS_INLINE_FUNCTION TwoBodyImpact two_body_impact(double landslide_mass, double velocity,
                                                     double equivalent_length, double barrier_mass,
                                                     const TwoBodyCoefficients& c) {
  TwoBodyImpact r;
  r.landslide_mass = landslide_mass;
  r.approach_velocity = velocity;
  r.reduced_mass = landslide_mass / (1.0 + landslide_mass / barrier_mass);
  r.max_shortening = c.lambda * equivalent_length;  // s1,max = lambda L1,0
  r.K1 = r.reduced_mass * velocity / r.max_shortening;
  r.q1 = 0.75 * r.K1 * velocity / math::sqrt(r.max_shortening);  // eq. 11
  const double T2 = (8.0 / 3.0) * r.max_shortening / velocity;   // eq. 12
  r.pulse.duration = T2;
  r.pulse.rise_time = c.tau * T2;                // eq. 7
  r.pulse.peak = 0.5 * r.q1 * r.q1 / r.K1 * T2;  // eq. 13 at t = T1
  r.pulse.residual = 0.0;
  r.common_velocity = velocity - r.reduced_mass * velocity / landslide_mass;
  return r;
}

}  // namespace lsi

// Design approach No. 1, empirical (Di Perna et al. 2022; the paper's eqs. 1-10).
//
// Symbols (SI): h flow thickness (m), v0 approach velocity (m/s), rho_m mixture density (kg/m^3),
// m1 landslide mass per metre (kg/m), beta face inclination (rad). The impact is resolved along
// the normal of the impacted face: v_n = v0 sin(beta) is the "reference velocity" of the paper,
// v_t = v0 cos(beta) slides along a smooth face and is not destroyed by the impact.
//   eq. 1  Froude number       Fr = v_n / sqrt(g h)
//   eq. 2  coefficient         alpha = a1 Fr^a2
//   eq. 4  dynamic peak        F_peak,dyn  = alpha rho_m v_n^2 h
//   eq. 5  static peak         F_peak,stat = kappa rho_m g h^2 / 2
//   eq. 3  peak force          F_peak = F_peak,dyn + F_peak,stat        (normal to the face, N/m)
//   eq. 6  impact duration     T2 = 2 m1 v_n / (F_peak + F_peak,stat - tau F_peak,stat)
//   eq. 7  rise time           T1 = tau T2
//   eq. 8  velocity loss       Delta v(t) = I(t) / m1, I = exact integral of the pulse
//   eq. 9  velocity            v_n(t) = v_n - Delta v(t)
//   eq. 10 kinetic energy      E_k,1(t) = m1 (v_n(t)^2 + v_t^2) / 2
// The pulse rises linearly to F_peak at T1 and decays linearly to F_peak,stat at T2 (this is the
// pulse whose impulse eq. 6 equates to m1 v_n); the printed eq. 8 is not its integral and is
// discontinuous at T1. Derivations and deviations: docs/theory/models.md, "Empirical model".
// No library calls (sin, cos and pow without branches: kernels/common/), so that the batched
// models vectorise (kernels/closed_form/batch.hpp); the face angle is in (0, pi/2], as scenes and
// studies keep it.
#pragma once
#include "kernels/closed_form/force_pulse.hpp"
#include "kernels/common/constants.hpp"
#include "kernels/common/math.hpp"
#include "kernels/common/pow_nonnegative.hpp"
#include "kernels/common/sincos_first_quadrant.hpp"

namespace lsi {

struct EmpiricalCoefficients {
  double a1 = 1.781;  // alpha = a1 Fr^a2
  double a2 = -0.515;
  double tau = 0.14;   // T1 / T2, in (0, 1)
  double kappa = 0.0;  // static coefficient
};

struct EmpiricalImpact {
  double normal_velocity = 0.0;      // v_n, m/s
  double tangential_velocity = 0.0;  // v_t, m/s
  double froude = 0.0;               // Fr
  double alpha = 0.0;
  double peak_dynamic = 0.0;    // F_peak,dyn, N/m
  double peak_static = 0.0;     // F_peak,stat, N/m
  double landslide_mass = 0.0;  // m1, kg/m
  ForcePulse pulse;             // normal force on the face; peak = F_peak

  // Landslide velocity normal to the face, eq. 9; zero from T2 on (the flow is stopped).
  KOKKOS_INLINE_FUNCTION double landslide_normal_velocity(double t) const {
    const double tt = math::min(t, pulse.duration);
    return math::max(normal_velocity - pulse.impulse(tt) / landslide_mass, 0.0);
  }
  // Landslide kinetic energy, eq. 10 (J/m).
  KOKKOS_INLINE_FUNCTION double landslide_kinetic_energy(double t) const {
    const double vn = landslide_normal_velocity(t);
    return 0.5 * landslide_mass * (vn * vn + tangential_velocity * tangential_velocity);
  }
};

// The flow as it reaches the face: eqs. 1 and 9's v_n, v_t. The first half of empirical_impact,
// apart so that a batch can raise many Froude numbers to a2 at once (closed_form/batch.hpp).
struct EmpiricalApproach {
  double normal_velocity = 0.0;      // v_n, m/s
  double tangential_velocity = 0.0;  // v_t, m/s
  double froude = 0.0;               // Fr
};

KOKKOS_INLINE_FUNCTION EmpiricalApproach empirical_approach(double thickness, double velocity,
                                                            double face_angle_rad) {
  EmpiricalApproach a;
  const math::SinCos face = math::sincos_first_quadrant(face_angle_rad);
  a.normal_velocity = velocity * face.sin;
  a.tangential_velocity = velocity * face.cos;
  a.froude = a.normal_velocity / math::sqrt(gravity * thickness);  // eq. 1
  return a;
}

// The impact from the approach and froude_power = Fr^a2 (eqs. 2-7).
KOKKOS_INLINE_FUNCTION EmpiricalImpact empirical_impact(const EmpiricalApproach& a,
                                                        double froude_power, double thickness,
                                                        double density, double landslide_mass,
                                                        const EmpiricalCoefficients& c) {
  EmpiricalImpact r;
  r.normal_velocity = a.normal_velocity;
  r.tangential_velocity = a.tangential_velocity;
  r.landslide_mass = landslide_mass;
  r.froude = a.froude;
  r.alpha = c.a1 * froude_power;                                                           // eq. 2
  r.peak_dynamic = r.alpha * density * r.normal_velocity * r.normal_velocity * thickness;  // eq. 4
  r.peak_static = 0.5 * c.kappa * density * gravity * thickness * thickness;               // eq. 5
  const double peak = r.peak_dynamic + r.peak_static;                                      // eq. 3
  const double T2 = 2.0 * landslide_mass * r.normal_velocity /
                    (peak + r.peak_static - c.tau * r.peak_static);  // eq. 6
  r.pulse.peak = peak;
  r.pulse.duration = T2;
  r.pulse.rise_time = c.tau * T2;  // eq. 7
  r.pulse.residual = r.peak_static;
  return r;
}

KOKKOS_INLINE_FUNCTION EmpiricalImpact empirical_impact(double thickness, double velocity,
                                                        double density, double landslide_mass,
                                                        double face_angle_rad,
                                                        const EmpiricalCoefficients& c) {
  const EmpiricalApproach a = empirical_approach(thickness, velocity, face_angle_rad);
  return empirical_impact(a, math::pow_nonnegative(a.froude, c.a2), thickness, density,
                          landslide_mass, c);
}

}  // namespace lsi

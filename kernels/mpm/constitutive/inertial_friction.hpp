// Rate-dependent friction, the mu(I) rheology of dense granular flows (GDR MiDi, Eur. Phys. J. E
// 14:341, 2004; Jop, Forterre & Pouliquen, Nature 441:727, 2006), as a friction angle of the
// Mohr-Coulomb model that follows the inertial number of the point:
//   I = gamma_dot d / sqrt(p / rho_s)                                 (inertial number)
//   sin(phi(I)) = sin(phi_s) + (sin(phi_2) - sin(phi_s)) I / (I0 + I)
// gamma_dot = sqrt(2 D' : D') is the shear rate (D' the deviator of the strain rate, with
// D_zz = 0 in plane strain; gamma_dot is du/dy in simple shear), p = -(sigma_xx + sigma_yy)/2
// the in-plane mean (effective) pressure of the trial stress, d the grain diameter, rho_s the
// grains' density.
//
// Why the in-plane mean and not tr(sigma)/3: the theory's stress is -p I + (a deviator coaxial
// with D), so in simple shear all three normal stresses equal p. A plane-strain Mohr-Coulomb
// solid keeps the out-of-plane stress of its elastic history instead (psi = 0 flow has no
// out-of-plane plastic strain): in a steady layer on a slope sigma_zz settles at about 0.62
// sigma_yy, and tr(sigma)/3 was 0.87 sigma_yy, which made I, and the flow's shear rate, 7 % off
// the theory's. The in-plane mean is the centre of the Mohr circle that yields (sigma_zz is the
// intermediate stress in shear), the normal stress on the planes of greatest shear, and equal to
// the theory's p in simple shear.
//
// Why sin(phi) carries Jop's mu: in steady simple shear of a non-dilatant (psi = 0)
// Mohr-Coulomb material the principal axes are at 45 degrees to the shear plane, so the shear
// stress on that plane is the Mohr circle's radius R = p sin(phi) and the normal stress its
// centre p: tau / sigma_n = sin(phi). Jop's mu = |tau| / p is that ratio (tan(theta) of a
// steady flow down a slope theta). So Jop's glass beads (mu_s = tan 20.9 deg, mu_2 =
// tan 32.76 deg) are phi_s = asin(0.382) = 22.5 deg, phi_2 = asin(0.643) = 40.0 deg here
// (docs/theory/mpm.md, "Rate-dependent friction").
//
// Written as I / (I0 + I) = gamma_dot k / (I0 sqrt(p) + gamma_dot k), k = d sqrt(rho_s), the rise
// is finite for every state: a point without pressure (p <= 0, torn apart or at the apex) that
// shears takes the limit angle, a point at rest the static one. The angle is evaluated from the
// step's rate and the trial pressure (explicit in the rate, as the rest of the step).
#pragma once
#include "kernels/mpm/constitutive/material.hpp"

namespace lsi::mpm {

// Shear rate gamma_dot = sqrt(2 D' : D') of the plane-strain rate (Dxx, Dyy, Dxy; Dzz = 0).
KOKKOS_INLINE_FUNCTION double shear_rate(const double Dxx, const double Dyy, const double Dxy) {
  const double m = (Dxx + Dyy) / 3.0;
  const double a = Dxx - m, b = Dyy - m, c = -m;
  return math::sqrt(2.0 * (a * a + b * b + c * c + 2.0 * Dxy * Dxy));
}

// I / (I0 + I) for the shear rate and the mean pressure p (Pa; <= 0 gives 1 if shearing).
KOKKOS_INLINE_FUNCTION double inertial_fraction(const PreparedMaterial& pm, const double gamma_dot,
                                                const double p) {
  const double num = gamma_dot * pm.inertial_length;
  const double den = pm.material.reference_inertial_number * math::sqrt(p > 0.0 ? p : 0.0) + num;
  return den > 0.0 ? num / den : 0.0;
}

// The inertial number itself (the tests check the law with it): infinite without pressure.
KOKKOS_INLINE_FUNCTION double inertial_number(const PreparedMaterial& pm, const double gamma_dot,
                                              const double p) {
  return p > 0.0 ? gamma_dot * pm.inertial_length / math::sqrt(p) : 1e300;
}

// The material at the point's inertial number: its friction constants set for
// sin(phi(I)) (a copy; the prepared material of the body is left alone).
KOKKOS_INLINE_FUNCTION PreparedMaterial at_inertial_state(const PreparedMaterial& pm,
                                                          const double gamma_dot, const double p) {
  PreparedMaterial r = pm;
  const double sphi = pm.sin_phi + pm.inertial_rise * inertial_fraction(pm, gamma_dot, p);
  r.set_friction(sphi, math::sqrt(1.0 - sphi * sphi));
  return r;
}

}  // namespace lsi::mpm

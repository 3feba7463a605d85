// Rate-dependent friction, mu(I) (kernels/mpm/constitutive/inertial_friction.hpp), on one
// material point driven through update_point_stress (host Views, every constant of the kernel):
//
//  * the shear rate gamma_dot = sqrt(2 D':D') is du/dy in simple shear and does not depend on the
//    axes (rotated rate tensors give the same value);
//  * the friction angle at rest is the static one, without pressure (a torn-apart point) the
//    limit one, and in between it follows sin(phi) = sin(phi_s) + (sin(phi_2) - sin(phi_s))
//    I / (I0 + I), I = gamma_dot d / sqrt(p / rho_s), evaluated here from the formula, not from
//    the kernel;
//  * steady simple shear at a prescribed rate under a confining pressure P (constant volume, no
//    dilatancy, so P stays exact) ends on the yield surface of phi(I): the Mohr circle's radius
//    over its centre is sin(phi(I)) to round-off, and the shear stress over the normal stress on
//    the shear plane, the friction coefficient a flow down a slope sees, is Jop's mu(I) within
//    1e-4 (the small normal-stress difference the Jaumann rate leaves in steady shear, printed).
//    Three rates: I = I0 / 10, I0, 10 I0.
//  * a rate-independent material is left exactly as it was (same stress bit for bit as the
//    same material without mu(I) at the static angle, when the rate is zero).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "kernels/mpm/constitutive/inertial_friction.hpp"
#include "kernels/mpm/stress_update.hpp"
#include "support/tolerances.hpp"

namespace {
using namespace lsi::mpm;
using HostParticles = Particles<Kokkos::HostSpace>;
using lsi::test::kFewOpsAbs;
using lsi::test::kRoundOffAbs;
using lsi::test::kTwoRoutesRel;
using lsi::test::kUnitArithmeticAbs;

// I = gamma_dot d / sqrt(p / rho_s) recomputed from the rate made for it: a square root, a few
// products and a quotient, relative.
constexpr double kInertialNumberRel = 1e-14;
// Invariants after 4000 stress updates (Jaumann rotation and return) in steady shear: the
// round-off accumulated over the steps.
constexpr double kSteadyShearRel = 1e-9;

constexpr double kPi = 3.14159265358979323846;

// Jop, Forterre & Pouliquen (2006) glass beads: mu_s = tan 20.9 deg, mu_2 = tan 32.76 deg,
// I0 = 0.279, d = 0.5 mm, rho_s = 2450 kg/m^3; as Mohr-Coulomb angles sin(phi) = mu.
const double kMuS = std::tan(20.9 * kPi / 180), kMu2 = std::tan(32.76 * kPi / 180);
constexpr double kI0 = 0.279, kD = 0.5e-3, kRhoS = 2450;

Material glass_beads() {
  Material m;
  m.model = Material::Model::MohrCoulomb;
  m.density = 0.6 * kRhoS;
  m.young_modulus = 1e7;
  m.poisson_ratio = 0.3;
  m.friction_angle = std::asin(kMuS);
  m.limit_friction_angle = std::asin(kMu2);
  m.reference_inertial_number = kI0;
  m.grain_diameter = kD;
  m.grain_density = kRhoS;
  return m;
}

double mu_of_I(double I) { return kMuS + (kMu2 - kMuS) * I / (kI0 + I); }

TEST(InertialFriction, ShearRateIsDuDyInSimpleShearAndFrameIndependent) {
  // Simple shear u = g y: Dxy = g / 2.
  EXPECT_NEAR(shear_rate(0.0, 0.0, 0.5 * 3.0), 3.0, kFewOpsAbs);
  // Pure shear Dxx = -Dyy = e is simple shear rotated by 45 degrees: gamma_dot = 2 e.
  EXPECT_NEAR(shear_rate(1.5, -1.5, 0.0), 3.0, kFewOpsAbs);
  // A general plane rate tensor, rotated by 0.3 rad: the same gamma_dot.
  const double Dxx = 0.7, Dyy = -0.2, Dxy = 0.45, c = std::cos(0.3), s = std::sin(0.3);
  const double Rxx = c * c * Dxx + s * s * Dyy + 2 * c * s * Dxy;
  const double Ryy = s * s * Dxx + c * c * Dyy - 2 * c * s * Dxy;
  const double Rxy = (c * c - s * s) * Dxy + c * s * (Dyy - Dxx);
  EXPECT_NEAR(shear_rate(Rxx, Ryy, Rxy), shear_rate(Dxx, Dyy, Dxy), kUnitArithmeticAbs);
}

TEST(InertialFriction, AngleRunsFromStaticAtRestToLimitWithoutPressure) {
  const PreparedMaterial pm(glass_beads());
  ASSERT_TRUE(pm.rate_dependent);
  // At rest: the static angle, whatever the pressure.
  EXPECT_EQ(at_inertial_state(pm, 0.0, 1e3).sin_phi, pm.sin_phi);
  EXPECT_NEAR(at_inertial_state(pm, 0.0, 1e3).sin_phi, kMuS, kFewOpsAbs);
  // Shearing without pressure (p <= 0): the limit angle (I infinite).
  EXPECT_NEAR(at_inertial_state(pm, 5.0, 0.0).sin_phi, kMu2, kFewOpsAbs);
  EXPECT_NEAR(at_inertial_state(pm, 5.0, -20.0).sin_phi, kMu2, kFewOpsAbs);
  // In between, the formula: p = 100 Pa, gamma_dot such that I = 0.05, 0.279, 2.
  for (double I : {0.05, kI0, 2.0}) {
    const double p = 100.0, g = I * std::sqrt(p / kRhoS) / kD;
    EXPECT_NEAR(inertial_number(pm, g, p), I, kInertialNumberRel * I);
    const PreparedMaterial mi = at_inertial_state(pm, g, p);
    EXPECT_NEAR(mi.sin_phi, mu_of_I(I), kUnitArithmeticAbs) << "I = " << I;
    EXPECT_NEAR(mi.cos_phi, std::sqrt(1 - mu_of_I(I) * mu_of_I(I)), kUnitArithmeticAbs);
    // The return constants are those of a rate-independent material at that angle.
    Material fixed = glass_beads();
    fixed.reference_inertial_number = 0.0;
    fixed.friction_angle = std::asin(mu_of_I(I));
    const PreparedMaterial ref(fixed);
    EXPECT_NEAR(mi.main_plane, ref.main_plane, kTwoRoutesRel * ref.main_plane);
    EXPECT_NEAR(mi.edge_upper, ref.edge_upper, kTwoRoutesRel * ref.main_plane);
    EXPECT_NEAR(mi.edge_lower, ref.edge_lower, kTwoRoutesRel * ref.main_plane);
  }
}

// One point under confining pressure P sheared at rate g for n steps of dt: the final stress.
struct Sheared {
  double s[4];
  double plastic_work;
};
Sheared shear(const Material& m, double P, double g, int n, double dt) {
  HostParticles p(1);
  p.volume0(0) = p.volume(0) = 1e-4;
  p.stress(0, XX) = p.stress(0, YY) = p.stress(0, ZZ) = -P;
  p.stress(0, XY) = 0.0;
  const PreparedMaterial pm(m);
  for (int k = 0; k < n; ++k) update_point_stress<true>(p, 0, pm, 0.0, g, 0.0, 0.0, dt);
  return {{p.stress(0, XX), p.stress(0, YY), p.stress(0, XY), p.stress(0, ZZ)}, p.plastic_work(0)};
}

TEST(InertialFriction, SteadySimpleShearEndsOnTheRateDependentYieldSurface) {
  const Material m = glass_beads();
  const double P = 200.0;  // Pa: about 14 mm of glass beads
  for (double I : {0.1 * kI0, kI0, 10 * kI0}) {
    const double g = I * std::sqrt(P / kRhoS) / kD;
    // Shear strain 2 (far past the elastic strain P / G ~ 5e-5) in 4000 steps.
    const Sheared r = shear(m, P, g, 4000, 2.0 / g / 4000);
    const double* s = r.s;
    const double centre = 0.5 * (s[0] + s[1]);
    const double radius = std::hypot(0.5 * (s[0] - s[1]), s[2]);
    // Volume-preserving shear, psi = 0, Jaumann rotation: the in-plane mean pressure (the one
    // in I) and the mean pressure are unchanged.
    EXPECT_NEAR(-centre, P, kSteadyShearRel * P);
    EXPECT_NEAR(-(s[0] + s[1] + s[3]) / 3, P, kSteadyShearRel * P);
    // s_zz is the intermediate principal stress: the yield surface is the in-plane circle's.
    ASSERT_LT(s[3], centre + radius);
    ASSERT_GT(s[3], centre - radius);
    const double sin_phi = radius / -centre;
    EXPECT_NEAR(sin_phi, mu_of_I(I), kSteadyShearRel) << "I = " << I;
    // On the shear plane (normal y): tau / sigma_n = mu(I) within 1e-4 (the normal-stress
    // difference s_xx - s_yy that the Jaumann rate keeps in steady shear; measured 2-4e-5 P,
    // -1e-5 to -2e-5 relative on the ratio).
    const double slope_friction = std::fabs(s[2]) / -s[1];
    std::printf(
        "[measured] I = %.4f: sin(phi) = %.6f, mu(I) = %.6f, tau/sigma_n = %.6f "
        "(%+.3f %%), (s_xx - s_yy)/P = %.2e\n",
        I, sin_phi, mu_of_I(I), slope_friction, 100 * (slope_friction / mu_of_I(I) - 1),
        (s[0] - s[1]) / P);
    EXPECT_NEAR(slope_friction / mu_of_I(I), 1.0, 1e-4) << "I = " << I;
    EXPECT_GT(r.plastic_work, 0.0);
  }
}

TEST(InertialFriction, RateIndependentMaterialIsUnchanged) {
  // The same beads without mu(I), and with mu(I) at zero rate: a stress outside the static
  // surface returns to the same point, bit for bit.
  Material fixed = glass_beads();
  fixed.reference_inertial_number = 0.0;
  const Material rate = glass_beads();
  ASSERT_EQ(PreparedMaterial(fixed).sin_phi, PreparedMaterial(rate).sin_phi);
  auto one_step = [](const Material& m) {
    HostParticles p(1);
    p.volume0(0) = p.volume(0) = 1e-4;
    p.stress(0, XX) = -100.0;
    p.stress(0, YY) = -300.0;
    p.stress(0, XY) = 80.0;
    p.stress(0, ZZ) = -200.0;
    update_point_stress<true>(p, 0, PreparedMaterial(m), 0.0, 0.0, 0.0, 0.0, 1e-3);
    return std::array<double, 4>{p.stress(0, XX), p.stress(0, YY), p.stress(0, XY),
                                 p.stress(0, ZZ)};
  };
  // L = 0 (no rate): both materials have the static angle.
  const auto a = one_step(fixed), b = one_step(rate);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(a[k], b[k]) << k;
  // And that state was plastic: it was returned (it started outside the static surface).
  const double centre = -200.0, radius = std::hypot(100.0, 80.0);
  ASSERT_GT(radius / -centre, std::sin(fixed.friction_angle));
  EXPECT_NEAR(std::hypot(0.5 * (a[0] - a[1]), a[2]) / -(0.5 * (a[0] + a[1])),
              std::sin(fixed.friction_angle), kRoundOffAbs);
}

}  // namespace
